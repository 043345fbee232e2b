"""scripts/pstlib/validation/valset.py: the held-out validation set holds every stratum, is deterministic,
and is kept apart from the training scenes by seed."""
import math
import sys
import tomllib

import pytest

from pstlib.validation import scenegen, valset


def _docs(seed=valset.DEFAULT_SEED, count=64, size=128):
    return [(tomllib.loads(t), f) for _, t, f in valset.generate(seed, count, size)]


def _tex(d):
    (t,) = d["textures"].values()
    return t


def test_same_seed_same_files_scene_k_fixed_other_seed_other_files():
    a, b = valset.generate(count=16), valset.generate(count=16)
    assert a == b
    assert valset.generate(count=40)[:16] == a                  # scene k does not depend on the count
    other = valset.generate(valset.DEFAULT_SEED + 1, 16)
    assert not {t for _, t, _ in a} & {t for _, t, _ in other}
    assert [f["stratum"] for _, _, f in a] == [f["stratum"] for _, _, f in other]   # same strata, other draws


def test_size_sets_the_image_only():
    a, b = valset.generate(count=4, size=128), valset.generate(count=4, size=256)
    for (_, ta, fa), (_, tb, fb) in zip(a, b):
        da, db = tomllib.loads(ta), tomllib.loads(tb)
        assert da["image"]["width"] == 128 and db["image"]["height"] == 256
        assert fa == fb and da["textures"] == db["textures"] and da["objects"] == db["objects"]


def test_seeds_are_apart_from_training():
    assert valset.SEED_BEGIN >= scenegen.TRAIN_SEED_END and valset.DEFAULT_SEED in range(valset.SEED_BEGIN,
                                                                                            valset.SEED_END)
    for s in (0, 1, scenegen.TRAIN_SEED_END - 1, valset.SEED_END, -1):
        with pytest.raises(ValueError, match="validation seeds"):
            valset.scene(s, 0)
    for s in (valset.SEED_BEGIN, valset.DEFAULT_SEED, valset.SEED_END - 1):
        with pytest.raises(ValueError, match="training seeds"):
            scenegen.scene(s, "train", 0)
        with pytest.raises(ValueError, match="training seeds"):
            scenegen.check_training_seed(s)
    # and no validation texture is a training texture of the first training seeds (either stream)
    train = {tomllib.loads(t)["textures"]["t"].__repr__() for seed in range(4)
             for sc in scenegen.generate(seed, {"train": 16, "valid": 16}).values() for _, t, _ in sc}
    assert not any(repr(_tex(d)) in train for d, _ in _docs(count=32))


def test_the_search_and_gen_scenes_refuse_a_validation_seed_for_training(tmp_path):
    from pstlib.cli import gen_scenes, search as cli     # scripts/gen_scenes.py, scripts/search.py
    with pytest.raises(SystemExit) as e:
        gen_scenes.main(["--seed", str(valset.DEFAULT_SEED), "--out", str(tmp_path / "g")])
    assert e.value.code == 2 and not (tmp_path / "g").exists()
    (tmp_path / "hash4096.memh").write_text("0\n")
    base = ["--pst", sys.executable, "--rom-dir", str(tmp_path)]
    for bad in (["--seed", str(valset.DEFAULT_SEED)], ["--valid-seed", "7"]):
        with pytest.raises(SystemExit) as e:
            cli.parse_args(base + bad)
        assert e.value.code == 2, bad
    assert cli.parse_args(base).valid_seed == valset.DEFAULT_SEED


def test_eight_scenes_hold_every_stratum_once_and_64_eight_times():
    assert [f["stratum"] for _, _, f in valset.generate(count=8)] == valset.STRATUM_NAMES
    strata = [f["stratum"] for _, f in _docs()]
    assert all(strata.count(s) == 8 for s in valset.STRATUM_NAMES)


def test_64_scenes_cover_every_feature_of_the_training_generator():
    docs = _docs()
    texs = [_tex(d) for d, _ in docs]
    feats = [f for _, f in docs]
    assert {t["filter"] for t in texs} == set(scenegen.FILTERS)
    assert {t["colormap"]["wrap"] for t in texs} == set(scenegen.WRAPS)
    assert {t["colormap"]["interp"] for t in texs} == set(scenegen.INTERPS)
    assert {f["octave_kind"] for f in feats} == set(scenegen.MATRIX_KINDS)
    assert {f["quadric"] for f in feats} == set(scenegen.QUADRIC_KINDS)
    assert {len(t["octaves"]) for t in texs} == set(scenegen.OCTAVE_COUNTS)
    assert {d["objects"][0]["mesh"] for d, _ in docs} == set(scenegen.MESHES)
    # step-sensitive: step map taken mod under none / nearest MIP / SAT, every one of those filters
    step = [t for t in texs if t["colormap"]["interp"] == "step" and t["colormap"]["wrap"] == "mod"
            and t["filter"] in scenegen.STEP_FILTERS]
    assert {t["filter"] for t in step} == set(scenegen.STEP_FILTERS)
    assert sum(f["step_sensitive"] for f in feats) == len(step)
    # full quadrics with cross terms; rotated (off-diagonal) and never-2^k octave matrices
    full = [t["quadric"] for t in texs if len(t.get("quadric", {})) == 10]
    assert len(full) >= 16 and all(q["B"] and q["C"] and q["F"] for q in full)
    ms = [o["matrix"] for t in texs for o in t["octaves"]]
    assert any(m[i][j] != 0 for m in ms for i in range(3) for j in range(3) if i != j)
    diag = [abs(m[k][k]) for m, f in zip(ms, [f for f in feats for _ in range(f["octaves"])])
            if f["octave_kind"] == "axis" for k in range(3)]
    assert diag and all(abs(math.log2(v) - round(math.log2(v))) > 1e-6 for v in diag)


def test_the_three_hidden_kinds_are_in_every_set_of_eight_or_more():
    docs = _docs(count=8)
    kinds = [(f, _tex(d), d) for d, f in docs]
    assert any(f["quadric"] == "full" and t["colormap"]["interp"] == "step" and t["filter"] == "mip_linear"
               for f, t, _ in kinds)
    assert any(f["horizon"] and t["filter"] == "mip" and len(t["octaves"]) == 8 and f["octave_kind"] == "rotated"
               and f["non_power_of_two"] for f, t, _ in kinds)
    assert any(f["octave_kind"] == "rotated" and f["quadric"] == "linear" and t["colormap"]["wrap"] == "clamp"
               and d["objects"][0]["mesh"] == "torus" for f, t, d in kinds)


def test_horizon_scenes_reach_the_horizon_inside_the_input_formats():
    hz = [(d, f) for d, f in _docs() if f["horizon"]]
    assert len(hz) == 8
    for d, _ in hz:
        (obj,) = d["objects"]
        cam = d["camera"]
        assert obj["mesh"] == "plane" and obj["half_size"] >= 100 and cam["eye"][1] < 2
        # looking down a little: the horizon is in the picture (the pitch is under half the fovy)
        dx, dy, dz = (t - e for t, e in zip(cam["target"], cam["eye"]))
        pitch = math.degrees(math.atan2(-dy, math.hypot(dx, dz)))
        assert 0 < pitch < cam["fovy"] / 2
        # |s| < 12 to the plane's corner (tex_scale * |p| + the offset)
        assert obj["tex_scale"] * obj["half_size"] * math.sqrt(2) + max(map(abs, obj["tex_offset"])) < 12


def test_files_stay_inside_the_formats_and_name_their_features():
    for d, f in _docs():
        t = _tex(d)
        assert f["name"].startswith("val_") and f["filter"] == t["filter"] and f["wrap"] == t["colormap"]["wrap"]
        assert len(t["octaves"]) == f["octaves"]
        for o in t["octaves"]:
            assert max(abs(v) for r in o["matrix"] for v in r) <= scenegen.MAX_FREQ
            assert 0 < abs(o["amplitude"]) < 1
        assert all(abs(v) < 4 for v in t.get("quadric", {}).values())
        assert valset.describe(f).startswith(f["stratum"] + ": ")


def test_bad_counts_sizes_and_the_writer(tmp_path):
    for kw, msg in (({"count": 0}, "--count"), ({"count": valset.MAX_COUNT + 1}, "--count"), ({"size": 8}, "--size"),
                    ({"size": 100000}, "--size"), ({"seed": 3}, "--seed")):
        with pytest.raises(ValueError, match=msg):
            valset.generate(**kw)
    m = valset.write(tmp_path, count=5)
    assert sorted(p.name for p in tmp_path.glob("val_*.toml")) == [f"val_{i:03d}.toml" for i in range(5)]
    assert [f["name"] for f in m["scenes"]] == [f"val_{i:03d}" for i in range(5)]
    valset.write(tmp_path, count=2)
    assert len(list(tmp_path.glob("val_*.toml"))) == 2


def test_the_training_twin_has_the_same_strata_on_training_seeds_and_other_textures():
    train = valset.generate(valset.TRAIN_DEFAULT_SEED, 16, 64, valset.TRAINING)
    held = valset.generate(count=16, size=64)
    assert [f["stratum"] for _, _, f in train] == [f["stratum"] for _, _, f in held]
    assert [n for n, _, _ in train][:2] == ["trn_000.toml", "trn_001.toml"]
    assert not {repr(_tex(tomllib.loads(t))) for _, t, _ in train} & {repr(_tex(tomllib.loads(t))) for _, t, _ in held}
    for s in (valset.SEED_BEGIN, valset.DEFAULT_SEED, -1):
        with pytest.raises(ValueError, match="training seeds are"):
            valset.scene(s, 0, split=valset.TRAINING)
    # the held-out set itself is unchanged by the twin: same files as its default
    assert held == valset.generate(valset.DEFAULT_SEED, 16, 64, valset.HOLDOUT)
