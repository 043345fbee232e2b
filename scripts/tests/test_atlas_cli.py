"""`pst atlas` (texture-atlas mode): bad input is refused (`error: --flag: ...` or
`error: FILE:LINE: FIELD: ...`, exit 2, nothing written), and a tiny run through the verilated
RTL of a profile with input gaps and output stalls is bit-exact with 0 seams. Run by ctest
(cli_atlas) with PST_BIN set to the built tool; skipped without it."""
import json
import os
import pathlib
import re

import pytest

from pst_cli import ROOT, needs_pst, run
from pst_cli import refused as refused_all

RTL = os.environ.get("PST_ATLAS_RTL", "")  # a verilated profile of the build, "" = skip the RTL run
pytestmark = needs_pst

SCENE = """title = "atlas"
[image]
width = 16
height = 16
[camera]
eye = [2.0, 2.5, 3.0]
target = [0.0, 0.0, 0.0]
fovy = 40.0
[textures.t]
quadric = {{ A = 1.0, E = 1.0 }}
filter = "sat"
colormap = {{ size = 256, wrap = "mod", ramp = [[0.0, 0.0, 0.0, 0.0], [1.0, 1.0, 1.0, 1.0]] }}
[[textures.t.octaves]]
amplitude = 0.5
scale = 4.0

[[objects]]
mesh = "cube"
texture = "t"
scale = {scale}
"""


def scene(tmp, scale="[1.0, 1.0, 1.0]"):
    p = tmp / "cube.toml"
    p.write_text(SCENE.format(scale=scale))
    return p


def pst(*args):
    r = run(*args)
    return r.returncode, r.stdout, r.stderr


def refused(args, pattern, out):
    refused_all(args, pattern, [out])


def test_unknown_atlas_kind(tmp_path):
    out = tmp_path / "out"
    refused(["atlas", scene(tmp_path), "--atlas", "rhino", "-o", out, "-q"], r"--atlas: 'rhino' is not uniform", out)


def test_unknown_magnification(tmp_path):
    out = tmp_path / "out"
    refused(["atlas", scene(tmp_path), "--magnification", "cubic", "-o", out, "-q"], r"--magnification: 'cubic'", out)


# The cube's 12 triangles need 6 pair cells; bilinear cells are at least 5 x 2 texels, so an
# 8 x 8 atlas holds 1 x 4 cells = 8 triangles (nearest: 3 x 2 cells, 2 x 4 = 16 triangles).
def test_more_triangles_than_the_size_holds(tmp_path):
    out = tmp_path / "out"
    refused(["atlas", scene(tmp_path), "--size", 8, "-o", out, "-q"],
            r"--size: 12 triangles do not fit a 8 x 8 atlas \(it holds 8 ", out)
    rc, _, err = pst("atlas", scene(tmp_path), "--size", 8, "--magnification", "nearest", "--truth", 1, "-o", out, "-q")
    assert rc == 0, err


# A scale that flattens the cube to 1e-20 of its height leaves its 8 side triangles without
# area: skipped, as render skips them (scenes/README.md, "Zero-area triangles"); the top and
# bottom (4 triangles) make the atlas.
def test_degenerate_triangle(tmp_path):
    out = tmp_path / "out"
    s = scene(tmp_path, "[1.0, 1e-20, 1.0]")
    rc, stdout, err = pst("atlas", s, "--size", 16, "--truth", 1, "-o", out, "-q")
    assert rc == 0, stdout + err
    assert json.loads((out / "atlas.json").read_text())["triangles"] == 4


def test_two_profiles(tmp_path):
    out = tmp_path / "out"
    refused(["atlas", scene(tmp_path), "--profile", "full", "--profile", "reduced", "--model", "golden", "-o", out, "-q"],
            r"--profile: atlas takes one profile", out)


@pytest.mark.skipif(not RTL, reason="PST_ATLAS_RTL not set")
@pytest.mark.parametrize("kind", ["uniform", "length"])
def test_rtl_fill_bit_exact_with_gaps_and_stalls(tmp_path, kind):
    out = tmp_path / kind
    rc, stdout, err = pst("atlas", scene(tmp_path), "--atlas", kind, "--size", 64, "--truth", 2, "--profile", RTL,
                          "--gap-rate", 0.3, "--stall-rate", 0.4, "-o", out, "-q")
    assert rc == 0, stdout + err
    j = json.loads((out / "atlas.json").read_text())
    hw = j["hardware"]
    assert hw["passed"] and hw["mismatches"] == 0
    assert hw["texels"] > 0 and hw["cycles"] >= hw["texels"]
    if hw["fmax_mhz"]:  # a profile of scripts/synth/baseline.json: also its time after layout
        assert 0 < hw["fmax_layout_mhz"] < hw["fmax_mhz"]
        assert hw["fill_ms_at_layout_fmax"] > hw["fill_ms_at_fmax"]
    assert j["seams"]["nearest"] == 0 and j["seams"]["bilinear"] == 0
    assert j["seams"]["standard_bilinear"] > 0
    for f in ["atlas.png", "atlas_rtl.png", "render_nearest.png", "render_bilinear.png", "scale.png", "atlas.md"]:
        assert (out / f).exists(), f


OBJ_SCENE = SCENE.format(scale="1.0").replace('mesh = "cube"', 'mesh = "obj"\nfile = "m.obj"')


@pytest.mark.parametrize("name,obj,pattern", [
    ("index", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", r":4: f: vertex index '9' out of range \(3 vertices defined above\)"),
    ("junk", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n", r":4: f: vertex index 'x' is not an integer"),
    ("empty", "v 0 0 0\n", r": no faces"),
    ("missing", None, r": cannot open \(No such file or directory\)"),
    ("directory", "DIR", r": not a regular file \(a directory\)"),
])
def test_broken_obj_file(tmp_path, name, obj, pattern):
    s = tmp_path / "obj.toml"
    s.write_text(OBJ_SCENE)
    if obj == "DIR":
        (tmp_path / "m.obj").mkdir()
    elif obj is not None:
        (tmp_path / "m.obj").write_text(obj)
    out = tmp_path / "out"
    refused(["atlas", s, "-o", out, "-q"], re.escape(str(s)) + r":19: objects\[0\]\.file: " +
            re.escape(str(tmp_path / "m.obj")) + pattern, out)


# A face whose three corners are collinear, or that repeats one, has no chart: skipped, as render
# skips it (scenes/README.md, "Zero-area triangles"); the other faces make the atlas.
def test_degenerate_obj_face_skipped(tmp_path):
    s = tmp_path / "obj.toml"
    s.write_text(OBJ_SCENE)
    for obj in ["v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 4\nf 1 2 3\n",
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 1 2\n"]:  # collinear; a repeated vertex
        (tmp_path / "m.obj").write_text(obj)
        out = tmp_path / "out"
        rc, stdout, err = pst("atlas", s, "--size", 16, "--image", 16, "--truth", 1, "-o", out, "-q")
        assert rc == 0, stdout + err
        assert json.loads((out / "atlas.json").read_text())["triangles"] == 1


# The multiresolution atlas (--mip, every kind): MIP levels halve the size, the pairs must fit
# the smallest cells (bilinear: 8 x 8 texels, so a 16 x 16 atlas holds 4 of the cube's pairs),
# and its dual graph needs every edge on at most two triangles.
@pytest.mark.parametrize("kind", ["uniform", "area", "length"])
def test_mip_size_not_a_power_of_two_or_too_small(tmp_path, kind):
    out = tmp_path / "out"
    refused(["atlas", scene(tmp_path), "--mip", "--atlas", kind, "--size", 48, "-o", out, "-q"],
            r"--size: 48 is not a power of two \(the MIP levels halve it\)", out)
    refused(["atlas", scene(tmp_path), "--mip", "--atlas", kind, "--size", 16, "-o", out, "-q"],
            r"--size: 12 triangles \(\d+ pairs\) do not fit a 16 x 16 multiresolution atlas \(it holds 4 pairs in 8 x 8 "
            r"cells\)", out)


def test_mip_turntable(tmp_path):
    out = tmp_path / "out"
    rc, _, err = pst("atlas", scene(tmp_path), "--mip", "--size", 64, "--truth", 2, "--turntable", 3, "-o", out, "-q")
    assert rc == 0 and (out / "render_trilinear.png").exists(), err
    # The turntable: 3 views, each stream's frames, flicker over the 2 steps of each stream.
    t = json.loads((out / "atlas.json").read_text())["turntable"]
    assert t["frames"] == 3 and len(list((out / "turntable").glob("atlas_frame_*.png"))) == 3
    assert all(t["flicker"][k] > 0 for k in ("atlas_bilinear", "atlas_trilinear", "per_pixel"))


# The non-uniform multiresolution atlases: power-of-two cells per pair, MIP texels averaging
# no non-neighbours up to the pair cells' level (the cube is one closed, connected surface).
@pytest.mark.parametrize("kind", ["area", "length"])
def test_mip_non_uniform(tmp_path, kind):
    out = tmp_path / "out"
    rc, _, err = pst("atlas", scene(tmp_path), "--mip", "--atlas", kind, "--size", 64, "--truth", 1, "-o", out, "-q")
    assert rc == 0 and (out / "render_trilinear.png").exists(), err
    j = json.loads((out / "atlas.json").read_text())
    mip = j["mip"]
    assert j["atlas"] == kind and mip["levels"] == 7 and len(mip["mixing_texels"]) == 7
    assert mip["cell_min"] <= mip["cell"] and mip["cell"] & (mip["cell"] - 1) == 0
    assert all(m == 0 for m in mip["mixing_texels"][:mip["cell"].bit_length()]), mip
    assert j["seams"]["nearest"] == 0 and j["seams"]["bilinear"] == 0
    assert "atlas_trilinear" in j["rms_vs_truth"]


# --mip pairs triangles across shared edges: an edge on three triangles is refused, named by the
# OBJ file (the scene's `file` key, line 19) with the count; the strip atlas takes it.
def test_mip_non_manifold_mesh(tmp_path):
    s = tmp_path / "obj.toml"
    s.write_text(OBJ_SCENE)
    # Three triangles on the edge (0,0,0)-(1,0,0).
    (tmp_path / "m.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n")
    out = tmp_path / "out"
    for kind in ["uniform", "area", "length"]:
        refused(["atlas", s, "--mip", "--atlas", kind, "--size", 64, "-o", out, "-q"],
                re.escape(f"{s}:19: objects[0].file: {tmp_path / 'm.obj'}: 1 edge on 3 or more triangles "
                          "(non-manifold; up to 3 on one edge, the first at triangle 0); --mip pairs triangles across "
                          "their shared edges, which needs every edge on at most two triangles"), out)
    rc, _, err = pst("atlas", s, "--size", 64, "--truth", 1, "-o", out, "-q")  # the strip atlas takes it
    assert rc == 0, err
    assert json.loads((out / "atlas.json").read_text())["mesh_edges"] == {"open": 6, "non_manifold": 1}


# An open mesh (a cube without its +x face: 4 edges on one triangle) is accepted, with --mip too:
# the dual graph only lacks the hole's 4 adjacencies; atlas.json counts the open edges.
CUBE_WITHOUT_PLUS_X = ("v -1 -1 -1\nv 1 -1 -1\nv -1 1 -1\nv 1 1 -1\nv -1 -1 1\nv 1 -1 1\nv -1 1 1\nv 1 1 1\n"
                       "f 1 5 7\nf 1 7 3\nf 3 7 8\nf 3 8 4\nf 1 2 6\nf 1 6 5\nf 5 6 8\nf 5 8 7\n"
                       "f 1 3 4\nf 1 4 2\n")


@pytest.mark.parametrize("mip", [False, True])
def test_open_mesh_accepted_and_counted(tmp_path, mip):
    s = tmp_path / "obj.toml"
    s.write_text(OBJ_SCENE)
    (tmp_path / "m.obj").write_text(CUBE_WITHOUT_PLUS_X)
    out = tmp_path / "out"
    rc, _, err = pst("atlas", s, *(["--mip"] if mip else []), "--size", 64, "--truth", 1, "-o", out, "-q")
    assert rc == 0, err
    assert json.loads((out / "atlas.json").read_text())["mesh_edges"] == {"open": 4, "non_manifold": 0}
    assert "| mesh edges: open / non-manifold | 4 / 0 |" in (out / "atlas.md").read_text()


# The atlas render's quality (ctest atlas_quality, label atlas): at a 1024 x 1024 atlas the
# bilinear render's RMS against the 4 x 4 truth stays within 1.5x of the per-pixel render's,
# on the paper's teapot and torus, the planet's sphere and the chess-king cross with its slivers
# (measured 1.32, 1.37, 1.05, 1.40 for length).
@pytest.mark.parametrize("name", ["wood_teapot", "wood_torus", "planet", "atlas/king"])
def test_quality_atlas_render_within_1_5x_of_per_pixel(tmp_path, name):
    out = tmp_path / pathlib.Path(name).name
    rc, _, err = pst("atlas", ROOT / "scenes" / f"{name}.toml", "--atlas", "length", "--size", 1024, "--image", 256,
                     "--truth", 4, "-o", out, "-q")
    assert rc == 0, err
    j = json.loads((out / "atlas.json").read_text())
    r = j["rms_vs_truth"]
    assert r["atlas_bilinear"] < 1.5 * r["per_pixel"], r
    assert j["seams"]["nearest"] == 0 and j["seams"]["bilinear"] == 0
