import argparse
import copy
import tomllib

import pytest

from pstlib import contract
from pstlib.explore import sweep
from pstlib.paths import ROOT

REDUCED = ROOT / "rtl" / "configs" / "reduced.toml"
FULL = ROOT / "rtl" / "configs" / "full_1clk.toml"   # eight octaves on eight units


def load(p):
    return tomllib.loads(p.read_text())


def test_shipped_profiles_are_valid():
    assert contract.validate(load(FULL)) == []
    assert contract.validate(load(REDUCED)) == []


def test_invalid_points_are_skipped_with_the_reason():
    full = load(FULL)                       # matrix.frac 16: coord.frac 0 leaves 16 >= lattice_frac 16
    assert sweep.point_profile(full, "coord_frac", 0)[1] == []
    base = dict(full, formats=dict(full["formats"], matrix={"int": 8, "frac": 4}))
    _, bad = sweep.point_profile(base, "coord_frac", 10)          # 4 + 10 < 16
    assert [b.split(":")[0] for b in bad] == ["noise.lattice_frac", "formats.offset"]
    _, bad = sweep.point_profile(load(REDUCED), "noise_steps", 2)  # reduced is serial
    assert bad == ["pipeline.datapath: serial needs pipeline.noise_steps >= 4"]
    _, bad = sweep.point_profile(full, "octaves", 17)            # full's 8 units follow its 8 octaves
    assert bad == ["pipeline.octaves: must be an integer in [1, 16] (is 17)",
                   "pipeline.noise_units: must be an integer in [1, 16] (is 17)"]


def test_noise_grad_frac_knob_sets_only_the_derivative_lanes_and_a_worley_unit_refuses_it():
    full = load(FULL)
    doc, bad = sweep.point_profile(full, "noise_grad_frac", 12)
    assert bad == [] and doc["noise"]["grad_frac"] == 12
    assert {k for k in doc["noise"] if doc["noise"][k] != full["noise"][k]} == {"grad_frac"}
    worley = load(ROOT / "sim" / "test_profiles" / "reduced_worley.toml")
    _, bad = sweep.point_profile(worley, "noise_grad_frac", 8)
    assert [b.split(":")[0] for b in bad] == ["noise.grad_frac"]


def test_point_names_are_c_identifiers():
    assert sweep.point_name("reduced", "coord_frac", 8) == "reduced_coord_frac_8"
    assert sweep.point_name("my-base", "hash", "perm256") == "my_base_hash_perm256"
    assert sweep.ident("9lives") == "p_9lives"


def test_octaves_knob_keeps_one_pass_or_takes_the_largest_divisor():
    full = load(FULL)                       # 8 octaves through 8 units: one pass per pixel
    doc, bad = sweep.point_profile(full, "octaves", 3)
    assert bad == [] and doc["pipeline"]["octaves"] == 3 and doc["pipeline"]["noise_units"] == 3
    base = copy.deepcopy(full)
    base["pipeline"].update(octaves=8, noise_units=4)
    doc, _ = sweep.point_profile(base, "octaves", 6)
    assert doc["pipeline"]["noise_units"] == 3
    assert base["pipeline"]["noise_units"] == 4     # the base is not changed


def test_amp_frac_knob_moves_three_formats_and_invalid_values_are_reported():
    red = load(REDUCED)
    doc, bad = sweep.point_profile(red, "amp_frac", 10)
    assert [doc["formats"][n]["frac"] for n in ("amplitude", "grad_matrix", "matrix")] == [10, 10, 10]
    assert bad == []
    assert sweep.KNOBS["amp_frac"][3](red) == 8
    doc, bad = sweep.point_profile(red, "coord_frac", 30)     # 10 + 30 = 40 bits: the most
    assert bad == []
    doc, bad = sweep.point_profile(red, "coord_frac", 31)
    assert bad == ["formats.coord: int + frac must be at most 40 (is 41)"]


def test_parse_values():
    assert sweep.parse_values("coord_frac=8,10") == ("coord_frac", [8, 10])
    assert sweep.parse_values("hash=perm256") == ("hash", ["perm256"])
    for bad in ("coord_frac=8,x", "hash=md5", "nosuch=1", "coord_frac"):
        with pytest.raises(ValueError):
            sweep.parse_values(bad)


def test_set_texture_keys_in_a_real_scene():
    text = (ROOT / "scenes" / "marble.toml").read_text()
    new = sweep.set_texture_keys(text, {"filter": "mip", "noise": {"interp": "linear", "corner": "value",
                                                                   "hash": "perm256"}})
    tex = tomllib.loads(new)["textures"]
    assert tex and all(t["filter"] == "mip" for t in tex.values())
    assert all(t["noise"] == {"interp": "linear", "corner": "value", "hash": "perm256"} for t in tex.values())
    assert tomllib.loads(new)["objects"] == tomllib.loads(text)["objects"]


def args_for(tmp_path, knobs, values, scenes=("marble",)):
    a = argparse.Namespace(base_path=REDUCED, base_doc=load(REDUCED), base_name="reduced", match_variant=False,
                           knob_list=list(knobs), value_lists=dict(values),
                           scene_files={s: ROOT / "scenes" / f"{s}.toml" for s in scenes})
    return a


def test_make_points_writes_one_change_per_point(tmp_path):
    a = args_for(tmp_path, ["coord_frac", "hash", "filter"],
                 {"coord_frac": [8, 12, 31], "hash": ["rayshade", "perm256"], "filter": ["sat", "mip"]})
    base, points, skipped, bv = sweep.make_points(a, tmp_path)
    # 12 (coord), rayshade (hash) and sat (the scenes' filter) are the base's values: skipped silently
    assert [p.name for p in points] == ["reduced_coord_frac_8", "reduced_hash_perm256", "reduced_filter_mip"]
    assert [(k, v) for k, v, _ in skipped] == [("coord_frac", 31)]
    assert bv["coord_frac"] == 12 and bv["filter"] == "sat"
    base_doc = load(REDUCED)
    p8 = points[0]
    assert p8.profile == tmp_path / "points" / "reduced_coord_frac_8.toml"
    doc = load(p8.profile)
    assert doc["formats"]["coord"] == {"int": 10, "frac": 8}
    doc["formats"]["coord"]["frac"] = 12
    assert doc == base_doc                            # nothing else changed
    assert p8.synth_name == p8.name
    mip = points[2]
    assert mip.profile == REDUCED and mip.synth_name == "reduced"       # the same hardware
    assert tomllib.loads(mip.scene_files["marble"].read_text())["textures"]["marble"]["filter"] == "mip"
    assert len({base.sha, *(p.sha for p in points)}) == 4
    # again: same files, same content hashes
    base2, points2, _, _ = sweep.make_points(a, tmp_path)
    assert [p.sha for p in points2] == [p.sha for p in points]


def test_basis_knob_sets_the_triple_and_the_scene_copies(tmp_path):
    assert sweep.basis_of(load(REDUCED)) == "rayshade"
    doc, bad = sweep.point_profile(load(REDUCED), "basis", "perlin2002")
    assert bad == [] and doc["noise"]["interp"] == "quintic" and doc["noise"]["corner"] == "grad12"
    assert doc["noise"]["hash"] == "perlin256" and sweep.basis_of(doc) == "perlin2002"
    # one axis of the triple alone is an invalid profile: skipped with the contract's reason
    _, bad = sweep.point_profile(load(REDUCED), "interp", "quintic")
    assert [b.split(":")[0] for b in bad] == ["noise.interp"]
    for match in (False, True):
        a = args_for(tmp_path, ["basis"], {"basis": ["rayshade", "perlin2002"]})
        a.match_variant = match
        base, points, skipped, bv = sweep.make_points(a, tmp_path / str(match))
        assert bv["basis"] == "rayshade" and skipped == []
        assert [p.name for p in points] == ["reduced_basis_perlin2002"]
        assert tomllib.loads(points[0].profile.read_text())["noise"]["corner"] == "grad12"
        tex = tomllib.loads(points[0].scene_files["marble"].read_text())["textures"]
        assert tex and all(t["noise"] == {"basis": "perlin2002"} for t in tex.values())
        if match:
            assert all(t["norm"] == "euclid" for t in tex.values())


def test_basis_knob_worley_sets_the_unit_and_the_variant_keys(tmp_path):
    doc, bad = sweep.point_profile(load(REDUCED), "basis", "worley")
    assert bad == [] and doc["noise"]["worley_search"] == "octant" and doc["noise"]["hash"] == "perm256"
    assert sweep.basis_of(doc) == "worley"
    a = args_for(tmp_path, ["basis"], {"basis": ["worley"]})
    base, points, skipped, bv = sweep.make_points(a, tmp_path)
    assert skipped == [] and [p.name for p in points] == ["reduced_basis_worley"]
    tex = tomllib.loads(points[0].scene_files["marble"].read_text())["textures"]
    want = {"basis": "worley", "search": "octant", "max_points": doc["noise"]["worley_points"], "cubes": "rom256"}
    assert tex and all(t["noise"] == want for t in tex.values())
