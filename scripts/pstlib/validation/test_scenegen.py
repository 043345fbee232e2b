"""scripts/pstlib/validation/scenegen.py: random scenes are valid, deterministic per seed, and cover the features."""
import math
import tomllib

from pstlib.validation import scenegen

SCENE_KEYS = {"title", "image", "camera", "textures", "objects"}
TEXTURE_KEYS = {"quadric", "filter", "colormap", "octaves"}


def _all(seed=1, n=8):
    return scenegen.generate(seed, {"train": n, "valid": n})


def test_same_seed_same_files_other_seed_other_files():
    a, b, c = _all(1), _all(1), _all(2)
    assert [t for s in a.values() for _, t, _ in s] == [t for s in b.values() for _, t, _ in s]
    assert not set(t for _, t, _ in a["train"]) & set(t for _, t, _ in c["train"])


def test_scene_k_does_not_depend_on_the_set_size():
    small, big = scenegen.generate(5, {"train": 3}), scenegen.generate(5, {"train": 11})
    assert small["train"] == big["train"][:3]


def test_training_and_validation_sets_differ():
    s = _all(3)
    tex = lambda t: tomllib.loads(t)["textures"]     # noqa: E731
    train = [tex(t) for _, t, _ in s["train"]]
    assert all(tex(t) not in train for _, t, _ in s["valid"])


def test_files_parse_and_stay_inside_the_formats():
    for scenes in _all(7, 12).values():
        for fname, text, feats in scenes:
            d = tomllib.loads(text)
            assert set(d) <= SCENE_KEYS and fname == feats["name"] + ".toml"
            (tex,) = d["textures"].values()
            assert set(tex) <= TEXTURE_KEYS
            assert tex["filter"] in scenegen.FILTERS
            cm = tex["colormap"]
            assert cm["size"] == 256 and cm["wrap"] in ("mod", "clamp") and cm["interp"] in ("linear", "step")
            pos = [k[0] for k in cm["ramp"]]
            assert pos[0] == 0.0 and pos[-1] == 1.0 and pos == sorted(pos)
            assert all(0 <= c <= 1 for k in cm["ramp"] for c in k[1:])
            octs = tex["octaves"]
            assert len(octs) == feats["octaves"] and 1 <= len(octs) <= 8
            for o in octs:
                assert len(o["matrix"]) == 3 and all(len(r) == 3 for r in o["matrix"])
                assert max(abs(v) for r in o["matrix"] for v in r) <= scenegen.MAX_FREQ
                assert 0 < abs(o["amplitude"]) < 1 and max(map(abs, o["offset"])) <= 40
                assert "scale" not in o
            assert all(abs(v) < 4 for v in tex.get("quadric", {}).values())
            (obj,) = d["objects"]
            assert obj["mesh"] in scenegen.MESHES and obj["texture"] in d["textures"]
            assert math.dist(d["camera"]["eye"], d["camera"]["target"]) > 1


def test_eight_scenes_a_set_cover_every_listed_feature():
    for set_name, scenes in _all(11, 8).items():
        docs = [(tomllib.loads(t), f) for _, t, f in scenes]
        texs = [next(iter(d["textures"].values())) for d, _ in docs]
        assert {len(t["octaves"]) for t in texs} == set(range(1, 9)), set_name
        assert {t["filter"] for t in texs} == set(scenegen.FILTERS)
        assert {t["colormap"]["wrap"] for t in texs} == {"mod", "clamp"}
        assert {t["colormap"]["interp"] for t in texs} == {"linear", "step"}
        assert {d["objects"][0]["mesh"] for d, _ in docs} == set(scenegen.MESHES)
        ms = [o["matrix"] for t in texs for o in t["octaves"]]
        assert any(m[i][j] != 0 for m in ms for i in range(3) for j in range(3) if i != j)     # rotated
        diag = [abs(m[k][k]) for m in ms for k in range(3)]
        assert all(abs(math.log2(v) - round(math.log2(v))) > 1e-6 for v in diag if v)         # never 2^k
        assert any(o["offset"] != [0.0, 0.0, 0.0] for t in texs for o in t["octaves"])
        full = [t["quadric"] for t in texs if len(t.get("quadric", {})) == 10]
        assert full and all(q["B"] and q["C"] and q["F"] for q in full)                          # cross terms
        assert {f["matrix_kind"] for _, f in docs} == set(scenegen.MATRIX_KINDS)


def test_every_fourth_training_scene_is_step_sensitive_and_validation_is_a_plain_draw():
    s = scenegen.generate(4, {"train": 16, "valid": 16})
    for i, (_, text, feats) in enumerate(s["train"]):
        (tex,) = tomllib.loads(text)["textures"].values()
        forced = (tex["colormap"]["wrap"], tex["colormap"]["interp"]) == ("mod", "step") and \
            tex["filter"] in scenegen.STEP_FILTERS
        assert feats["step_sensitive"] == (i % 4 == 3)
        if i % 4 == 3:
            assert forced, feats["name"]
    assert {tomllib.loads(t)["textures"]["t"]["filter"] for i, (_, t, _) in enumerate(s["train"])
            if i % 4 == 3} == set(scenegen.STEP_FILTERS)
    assert not any(f["step_sensitive"] for _, _, f in s["valid"])
    # the validation set keeps its independent strata: both wraps and interps with every filter
    assert {(tomllib.loads(t)["textures"]["t"]["colormap"]["wrap"]) for _, t, _ in s["valid"]} == {"mod", "clamp"}


def test_lacunarity_is_never_two():
    for scenes in _all(13, 20).values():
        for _, _, f in scenes:
            if f["octaves"] > 1:
                assert abs(f["lacunarity"] - 2.0) >= 0.03 - 1e-12


def test_write_makes_files_and_manifest_and_drops_extra_files(tmp_path):
    m = scenegen.write(tmp_path, 4, {"train": 5, "valid": 2})
    assert len(list((tmp_path / "train").glob("*.toml"))) == 5 and len(m["sets"]["valid"]) == 2
    first = (tmp_path / "train" / "train_000.toml").read_text()
    scenegen.write(tmp_path, 4, {"train": 2, "valid": 2})
    assert sorted(p.name for p in (tmp_path / "train").glob("*.toml")) == ["train_000.toml", "train_001.toml"]
    assert (tmp_path / "train" / "train_000.toml").read_text() == first
