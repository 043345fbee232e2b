"""Bad input to the `pst` tool, one test per class of bad input (found by trying the tool as a
hostile user would): each must give `error: FILE:LINE: FIELD: ...` (or `error: --flag: ...` for
a flag), exit status 2, and leave no output file behind. Run by ctest (cli_bad_input) with
PST_BIN set to the built tool; skipped without it."""
import os
import pathlib
import re
import shutil
import subprocess

import pytest

from pstlib.paths import ROOT
PST = os.environ.get("PST_BIN", "")
pytestmark = pytest.mark.skipif(not PST or not os.path.exists(PST), reason="PST_BIN not set")

SCENE = """title = "tiny"
[image]
width = {width}
height = 8
background = {background}
[camera]
eye = {eye}
target = [0.5, 0.5, 0.0]
fovy = 53.13
[textures.t]
quadric = {{ A = 5.0, E = 5.0 }}
filter = "sat"
colormap = {{ size = {clut}, wrap = "mod", ramp = [[0.0, 0.0, 0.0, 0.0], [1.0, {ramp}, 1.0, 1.0]] }}
[[textures.t.octaves]]
amplitude = {amplitude}
scale = 4.0
[[objects]]
{object}
texture = "t"
rotate = [90.0, 0.0, 0.0]
translate = [0.5, 0.5, 0.0]
"""
PLANE = 'mesh = "plane"\nhalf_size = 0.5'


def scene(tmp, name="s.toml", **kw):
    v = dict(width=8, background="[0.0, 0.0, 0.0]", eye="[0.5, 0.5, 1.0]", clut=256, ramp=1.0,
             amplitude=0.5, object=PLANE)
    v.update(kw)
    p = tmp / name
    p.write_text(SCENE.format(**v))
    return p


def pst(*args, cwd=None):
    r = subprocess.run([PST, *map(str, args)], capture_output=True, text=True, cwd=cwd, timeout=300,
                       env=dict(os.environ, PST_SOURCE_DIR=str(ROOT)))
    return r.returncode, r.stderr


def refused(args, pattern, absent=(), cwd=None):
    """Exit 2, an `error: ...` line matching pattern, and none of `absent` exists afterwards."""
    rc, err = pst(*args, cwd=cwd)
    assert rc == 2, f"exit {rc}, stderr:\n{err}"
    assert re.search(r"^error: " + pattern, err, re.M), f"stderr does not match {pattern!r}:\n{err}"
    for a in absent:
        assert not pathlib.Path(a).exists(), f"{a} was left behind"


def profile_copy(tmp, name, edit=None, src="full"):
    text = (ROOT / "rtl" / "configs" / f"{src}.toml").read_text()
    if edit:
        text = edit(text)
    d = tmp / "profiles"
    d.mkdir(exist_ok=True)
    p = d / f"{name}.toml"
    p.write_text(text)
    return p


# 1. Nothing is written before every input is loaded and checked.
def test_1_second_profile_bad_writes_nothing(tmp_path):
    bad = profile_copy(tmp_path, "bad", lambda t: t.replace("octaves = 8", "octaves = 99"))
    out = tmp_path / "out"
    refused(["render", scene(tmp_path), "--profile", "full", "--profile", bad, "--model", "golden", "-o", out, "-q"],
            re.escape(str(bad)) + r":\d+: pipeline\.octaves: ", [out])


def test_1_regress_bad_second_scene_writes_nothing(tmp_path):
    bad = scene(tmp_path, "bad.toml", width='"wide"')
    images = tmp_path / "images"
    refused(["regress", scene(tmp_path), bad, "--profile", "full", "--size", 4, "--images", images],
            re.escape(str(bad)) + r":\d+: image\.width: ", [images])


# 2. A profile is matched to the verilated RTL by its values, not by its file name.
def test_2_profile_named_like_verilated_but_different(tmp_path):
    fake = profile_copy(tmp_path, "full", lambda t: re.sub(r"(?m)^f *= \{ int = (\d+)", r"f = { int = 9", t))
    assert fake.read_text() != (ROOT / "rtl/configs/full.toml").read_text()
    out = tmp_path / "out"
    refused(["render", scene(tmp_path), "--profile", fake, "--size", 4, "-o", out, "-q"],
            re.escape(str(fake)) + r": formats\.f: differs from the profile the 'full' RTL was verilated from", [out])


# 3. Input errors are input errors (exit 2 with FILE:LINE: FIELD), not internal errors.
def test_3_profile_cross_constraint(tmp_path):
    # reduced: matrix.frac + coord.frac = 8 + 12 < 24
    bad = profile_copy(tmp_path, "bad", lambda t: re.sub(r"(?m)^offset( *)= \{ int = (\d+), *frac = \d+ \}",
                                                          r"offset\1= { int = 4, frac = 24 }", t), src="reduced")
    out = tmp_path / "out"
    refused(["render", scene(tmp_path), "--profile", bad, "--model", "golden", "-o", out, "-q"],
            re.escape(str(bad)) + r":\d+: formats\.offset: ", [out])


def test_3_colour_map_size_differs_from_profile(tmp_path):
    s = scene(tmp_path, clut=64)
    out = tmp_path / "out"
    refused(["render", s, "--profile", "full", "--model", "golden", "-o", out, "-q"],
            re.escape(str(s)) + r":\d+: textures\.t\.colormap\.size: 64 entries; profile 'full' has a 256-entry", [out])


def test_3_profile_without_verilated_model(tmp_path):
    other = profile_copy(tmp_path, "other")
    out = tmp_path / "out"
    refused(["render", scene(tmp_path), "--profile", other, "-o", out, "-q"],
            re.escape(str(other)) + r": profile 'other' has no verilated model in this build", [out])


# 4. Huge finite numbers and colours outside [0, 1] are refused (they gave NaN pixels).
@pytest.mark.parametrize("kw,field", [
    (dict(ramp=2.0), r"textures\.t\.colormap\.ramp\[1\]: colour components must be in \[0, 1\]"),
    (dict(background="[1e308, 0.0, 0.0]"), r"image\.background\[0\]: magnitude must be at most 1e6"),
    (dict(background="[0.5, -0.1, 0.0]"), r"image\.background: colour components must be in \[0, 1\]"),
    (dict(amplitude="1e308"), r"textures\.t\.octaves\[0\]\.amplitude: magnitude must be at most 1e6"),
    (dict(eye="[1.7e308, 0.5, 1.0]"), r"camera\.eye\[0\]: magnitude must be at most 1e6"),
])
def test_4_huge_numbers(tmp_path, kw, field):
    s = scene(tmp_path, **kw)
    out = tmp_path / "out"
    refused(["render", s, "-o", out, "-q"], re.escape(str(s)) + r":\d+: " + field, [out])


# 5. Profiles reject unknown keys and sections, as scene files do.
@pytest.mark.parametrize("extra,field", [
    ("\n[extra]\nfoo = 1\n", r"extra: unknown section"),
    ("", r"pipeline\.octavez: unknown key"),
])
def test_5_profile_unknown_keys(tmp_path, extra, field):
    bad = profile_copy(tmp_path, "bad", lambda t: t.replace("[pipeline]\n", "[pipeline]\noctavez = 3\n") if not extra
                       else t + extra)
    out = tmp_path / "out"
    refused(["render", scene(tmp_path), "--profile", bad, "--model", "golden", "-o", out, "-q"],
            re.escape(str(bad)) + r":\d+: " + field, [out])


# 6. NaN rates are refused by the range check.
@pytest.mark.parametrize("flag", ["--stall-rate", "--gap-rate"])
def test_6_nan_rates(tmp_path, flag):
    out = tmp_path / "out"
    rc, err = pst("render", scene(tmp_path), "--profile", "full", flag, "nan", "-o", out, "-q")
    assert rc == 2 and re.search(flag + r".*finite", err), (rc, err)
    assert not out.exists()


# 7. Trace options that would write nothing are refused.
@pytest.mark.parametrize("args,pattern", [
    (["--profile", "full", "--trace", "{tmp}/missing/t.fst"], r"--trace: folder '.*missing' does not exist"),
    (["--profile", "full", "--trace", "{tmp}/t.fst", "--trace-start", "50", "--trace-end", "10"],
     r"--trace-start: 50 is after --trace-end 10"),
    (["--trace", "{tmp}/t.fst"], r"--trace: needs --profile"),
    (["--profile", "full", "--model", "golden", "--trace", "{tmp}/t.fst"], r"--trace: needs --model rtl"),
])
def test_7_trace_options(tmp_path, args, pattern):
    out = tmp_path / "out"
    args = [a.replace("{tmp}", str(tmp_path)) for a in args]
    refused(["render", scene(tmp_path), *args, "--size", 4, "-o", out, "-q"], pattern, [out, tmp_path / "t.fst"])


# 7b. pst animate --trace: render's trace options, of one frame's stream (--trace-frame).
FIRE = ROOT / "scenes" / "fire.toml"


@pytest.mark.parametrize("args,pattern", [
    (["--profile", "reduced", "--trace", "{tmp}/missing/t.fst", "--trace-frame", "0"],
     r"--trace: folder '.*missing' does not exist"),
    (["--profile", "reduced", "--trace", "{tmp}/t.fst", "--trace-frame", "0", "--trace-start", "50",
      "--trace-end", "10"], r"--trace-start: 50 is after --trace-end 10"),
    (["--trace", "{tmp}/t.fst", "--trace-frame", "0"], r"--trace: needs --profile"),
    (["--profile", "reduced", "--model", "golden", "--trace", "{tmp}/t.fst", "--trace-frame", "0"],
     r"--trace: needs --model rtl"),
    (["--profile", "reduced", "--trace", "{tmp}/t.fst"], r"--trace: needs --trace-frame K"),
    (["--profile", "reduced", "--trace-frame", "1"], r"--trace-frame, --trace-start, --trace-end: need --trace FILE"),
    (["--profile", "reduced", "--trace-start", "5"], r"--trace-frame, --trace-start, --trace-end: need --trace FILE"),
    (["--profile", "reduced", "--trace", "{tmp}/t.fst", "--trace-frame", "2"],
     r"--trace-frame: 2 is not a frame of this run \(0\.\.1\)"),
    (["--profile", "reduced", "--profile", "full", "--trace", "{tmp}/t.fst", "--trace-frame", "0"],
     r"--trace: one --profile only"),
    (["--profile", "reduced", "--trace", str(FIRE), "--trace-frame", "0"], r"--trace: .*is the input"),
])
def test_7_animate_trace_options(tmp_path, args, pattern):
    out = tmp_path / "out"
    args = [a.replace("{tmp}", str(tmp_path)) for a in args]
    refused(["animate", FIRE, "--frames", 2, *args, "--size", 4, "--no-video", "-o", out, "-q"], pattern,
            [out, tmp_path / "t.fst"])


# 8. What a flag or a file may ask for is bounded (memory).
def test_8_huge_image_flag(tmp_path):
    out = tmp_path / "out"
    refused(["render", scene(tmp_path), "--size", 16384, "-o", out, "-q"], r"--size: 16384 x 16384 pixels: at most",
            [out])


def test_8_huge_meshes(tmp_path):
    objs = "\n".join(f'[[objects]]\nmesh = "sphere"\nslices = 1024\nstacks = 1024\ntexture = "t"\n' for _ in range(50))
    s = scene(tmp_path)
    s.write_text(s.read_text() + objs)
    out = tmp_path / "out"
    refused(["render", s, "--size", 8, "-o", out, "-q"],
            re.escape(str(s)) + r":\d+: objects\[\d+\]: the scene's meshes exceed 4194304 triangles", [out])


# 9. The scene's own size is checked with --size too; --profile takes one value per flag.
def test_9_scene_size_checked_with_size_flag(tmp_path):
    for w in ['"wide"', -5, 100000]:
        s = scene(tmp_path, width=w)
        out = tmp_path / "out"
        refused(["render", s, "--size", 8, "-o", out, "-q"], re.escape(str(s)) + r":\d+: image\.width: ", [out])


def test_9_regress_profiles_before_scene(tmp_path):
    s = scene(tmp_path, "one.toml")
    r = subprocess.run([PST, "regress", "--profile", "full", "--profile", "reduced", str(s), "--size", "4"],
                       capture_output=True, text=True, timeout=300, env=dict(os.environ, PST_SOURCE_DIR=str(ROOT)))
    assert r.returncode == 0, r.stdout + r.stderr
    rows = [l.split()[:2] for l in r.stdout.splitlines() if l.startswith("one ")]
    assert rows == [["one", "full"], ["one", "reduced"]], r.stdout


# 10. Minor classes.
@pytest.mark.parametrize("obj,field", [
    ('mesh = "torus"\nmajor_radius = 0.0', r"objects\[0\]\.major_radius: must be positive"),
    ('mesh = "torus"\nminor_radius = -0.2', r"objects\[0\]\.minor_radius: must be positive"),
    ('mesh = "cube"\nslices = 8', r"objects\[0\]\.slices: belongs to mesh = \"sphere\""),
    (PLANE + "\nscale = [1.0, 0.0, 1.0]", r"objects\[0\]\.scale: must be non-zero"),
])
def test_10_object_parameters(tmp_path, obj, field):
    s = scene(tmp_path, object=obj)
    out = tmp_path / "out"
    refused(["render", s, "-o", out, "-q"], re.escape(str(s)) + r":\d+: " + field, [out])


def tex_and_frags(tmp):
    t = tmp / "tex.toml"
    t.write_text('quadric = { A = 1.0 }\nfilter = "sat"\n'
                 'colormap = { size = 256, ramp = [[0, 0, 0, 0], [1, 1, 1, 1]] }\n')
    f = tmp / "f.frag"
    f.write_text("0.1 0.2 0.3  0.01 0 0  0 0.01 0\n")
    return t, f


def test_10_eval_out_is_folder(tmp_path):
    t, f = tex_and_frags(tmp_path)
    d = tmp_path / "dir"
    d.mkdir()
    refused(["eval", "-t", t, "-f", f, "-o", d], r"-o: '.*dir' is a folder; give a file name")
    assert list(d.iterdir()) == []


def test_10_fragment_numbers(tmp_path):
    t, f = tex_and_frags(tmp_path)
    f.write_text("1e-320 0.2 0.3  0.01 0 0  0 0.01 0\n")   # subnormal: a valid number
    rc, err = pst("eval", "-t", t, "-f", f)
    assert rc == 0, err
    f.write_bytes(b"0.1\x00junk 0.2 0.3  0.01 0 0  0 0.01 0\n")  # NUL inside a number
    refused(["eval", "-t", t, "-f", f], re.escape(str(f)) + r":1: s: not a number: '0\.1\\x00junk'")


def test_10_compare_nan_image(tmp_path):
    oiio = pytest.importorskip("OpenImageIO")
    import numpy as np
    p = tmp_path / "nan.exr"
    buf = oiio.ImageBuf(oiio.ImageSpec(4, 4, 3, oiio.FLOAT))
    buf.set_pixels(oiio.ROI(), np.full((4, 4, 3), np.nan, dtype=np.float32))
    assert buf.write(str(p))
    refused(["compare", p, p], re.escape(str(p)) + r": pixel \(0, 0\): NaN or infinite value")


def test_10_failed_write_leaves_no_partial_output(tmp_path):
    out = tmp_path / "out"
    (out / "width.png").mkdir(parents=True)     # stands for a full disk at the third image
    rc, err = pst("render", scene(tmp_path), "-o", out, "-q")
    assert rc != 0 and "width.png" in err, err
    assert sorted(p.name for p in out.iterdir()) == ["width.png"], list(out.iterdir())


# 7 (also): regress --random writes its -o JSON summary; the scene-mode options it cannot honour
# are refused instead of silently ignored.
@pytest.mark.parametrize("args,pattern", [
    (["--images", "{tmp}/images"], r"--images: not with --random"),
    (["--html", "{tmp}/page.html"], r"--html: not with --random"),
    (["--size", "16"], r"--size: not with --random"),
])
def test_7_random_refuses_scene_options(tmp_path, args, pattern):
    args = [a.replace("{tmp}", str(tmp_path)) for a in args]
    out = tmp_path / "r.json"
    refused(["regress", "--random", 10, "--seed", 1, "--profile", "reduced", "-o", out, "-q", *args], pattern,
            [out, tmp_path / "images", tmp_path / "page.html"])


def test_7_random_writes_its_summary(tmp_path):
    import json
    out = tmp_path / "r.json"
    r = subprocess.run([PST, "regress", "--random", "300", "--seed", "5", "--from", "1000", "--profile", "reduced",
                        "-o", str(out), "-q"], capture_output=True, text=True, timeout=300,
                       env=dict(os.environ, PST_SOURCE_DIR=str(ROOT)))
    assert r.returncode == 0, r.stdout + r.stderr
    doc = json.loads(out.read_text())
    assert doc["schema"] == 2 and doc["command_line"][1:3] == ["regress", "--random"]
    runs = doc["runs"]
    assert [x["profile"] for x in runs] == ["reduced"]
    run = runs[0]
    assert run["seed"] == 5 and run["mismatches"] == 0 and run["passed"] is True and run["first_bad"] is None
    # --from starts at the segment holding fragment 1000; at least the 300 fragments asked for are checked.
    assert run["first_fragment"] <= 1000 and run["first_fragment"] + run["fragments"] >= 1300
    assert run["textures"] >= 1 and run["cycles_per_pixel"] > 0


# 11. The subband basis (anisotropic noise, model/subband.h): its keys' values, its bandlimit,
# and a hardware profile (no unit for it) refuse with the scene's line and field.
def subband_scene(tmp, noise, bandlimit=None):
    p = scene(tmp)
    extra = f"noise = {noise}\n" + (f'bandlimit = "{bandlimit}"\n' if bandlimit else "")
    p.write_text(p.read_text().replace('filter = "sat"\n', 'filter = "sat"\n' + extra))
    return p


@pytest.mark.parametrize("noise,bandlimit,pattern", [
    ('{ basis = "subband", orientations = 6 }', None, r"textures\.t\.noise\.orientations: must be 4 or 8"),
    ('{ basis = "subband", tile_size = 300 }', None, r"textures\.t\.noise\.tile_size: must be a power of two"),
    ('{ basis = "subband", tile_size = 128 }', None, r"textures\.t\.noise\.tile_size: must be a power of two in \[256"),
    ('{ basis = "rayshade", orientations = 4 }', None, r"textures\.t\.noise\.orientations: applies to basis subband only"),
    ('{ basis = "subband", param = "uv" }', None, r"textures\.t\.noise\.param: unknown value 'uv'"),
    ('{ basis = "rayshade" }', "anisotropic", r"textures\.t\.bandlimit: anisotropic filtering needs basis subband"),
])
def test_11_subband_keys(tmp_path, noise, bandlimit, pattern):
    s = subband_scene(tmp_path, noise, bandlimit)
    out = tmp_path / "out"
    refused(["render", s, "--size", 8, "-o", out, "-q"], re.escape(str(s)) + r":\d+: " + pattern, [out])


def test_11_subband_on_a_profile(tmp_path):
    s = subband_scene(tmp_path, '{ basis = "subband", orientations = 8 }')
    out = tmp_path / "out"
    refused(["render", s, "--profile", "full", "--model", "golden", "--size", 8, "-o", out, "-q"],
            re.escape(str(s)) + r":\d+: textures\.t\.noise\.basis: basis 'subband' has no hardware unit in profile 'full'",
            [out])


def test_11_anisotropic_flag_needs_subband(tmp_path):
    out = tmp_path / "out"
    refused(["render", scene(tmp_path), "--bandlimit", "anisotropic", "--size", 8, "-o", out, "-q"],
            r"--bandlimit: anisotropic: texture 't': anisotropic filtering needs basis subband", [out])
    refused(["render", scene(tmp_path), "--variants", "sat+anisotropic", "--size", 8, "-o", out, "-q"],
            r"--variants: sat\+anisotropic: texture 't': anisotropic filtering needs basis subband", [out])


# 12. The subband unit (rtl/noise/pst_subband.sv, test profile reduced_subband): its profile key and
# constraints, and scenes that ask for another tile or plane than the unit's ROM holds.
def test_12_subband_profile_keys(tmp_path):
    out = tmp_path / "out"
    for name, edit, pattern in [
        ("bad_plane", lambda t: t.replace('subband = "none"', 'subband = "uv"'), r"noise\.subband: "),
        ("bad_both", lambda t: t.replace('subband = "none"', 'subband = "xz"').replace(
            'worley_search = "none"', 'worley_search = "octant"').replace('hash = "rayshade"', 'hash = "perm256"'),
         r"noise\.subband: must be none with a worley unit"),
        ("bad_frac", lambda t: t.replace('subband = "none"', 'subband = "xz"').replace(
            "lattice_frac = 8", "lattice_frac = 3"), r"noise\.lattice_frac: must be more than 3"),
    ]:
        bad = profile_copy(tmp_path, name, edit, src="reduced")
        assert bad.read_text() != (ROOT / "rtl/configs/reduced.toml").read_text()
        refused(["render", scene(tmp_path), "--profile", bad, "--model", "golden", "-o", out, "-q"],
                re.escape(str(bad)) + r":\d+: " + pattern, [out])


@pytest.mark.parametrize("noise,pattern", [
    ('{ basis = "subband", param = "xy" }',
     r"textures\.t\.noise\.param: 'xy'; the subband unit of profile 'reduced_subband' samples the plane 'xz'"),
    ('{ basis = "subband", param = "xz", tile_size = 512 }',
     r"textures\.t\.noise\.tile_size/seed: 512, 1; the subband unit of profile 'reduced_subband' holds the tile of "
     r"tile_size 256, seed 1"),
    ('{ basis = "subband", param = "xz", seed = 7 }', r"textures\.t\.noise\.tile_size/seed: 256, 7"),
    ('{ basis = "rayshade" }', r"textures\.t\.noise\.basis: basis 'rayshade' has no hardware unit in profile "
                               r"'reduced_subband' \(its noise unit computes 'subband'\)"),
])
def test_12_subband_scene_on_the_unit(tmp_path, noise, pattern):
    s = subband_scene(tmp_path, noise)
    prof = ROOT / "sim" / "test_profiles" / "reduced_subband.toml"
    out = tmp_path / "out"
    refused(["render", s, "--profile", prof, "--model", "golden", "--size", 8, "-o", out, "-q"],
            re.escape(str(s)) + r":\d+: " + pattern, [out])


# The subband unit's anisotropic filter (noise.subband_orientations, test profile reduced_subband_k8):
# the key's values and what it needs, and scenes that ask for another filter than the unit's.
def test_12_subband_orientations_key(tmp_path):
    out = tmp_path / "out"
    sub = lambda t: t.replace('subband = "none"', 'subband = "xz"')
    for name, edit, pattern in [
        ("bad_k", lambda t: sub(t).replace("subband_orientations = 0", "subband_orientations = 6"),
         r"noise\.subband_orientations: "),
        ("bad_nounit", lambda t: t.replace("subband_orientations = 0", "subband_orientations = 4"),
         r"noise\.subband_orientations: must be 0 without a subband unit"),
        ("bad_nofade", lambda t: sub(t).replace("subband_orientations = 0", "subband_orientations = 8"),
         r"noise\.subband_orientations: 4 or 8 needs filter\.bandlimit = isotropic"),
    ]:
        bad = profile_copy(tmp_path, name, edit, src="reduced")
        refused(["render", scene(tmp_path), "--profile", bad, "--model", "golden", "-o", out, "-q"],
                re.escape(str(bad)) + r":\d+: " + pattern, [out])


@pytest.mark.parametrize("noise,bandlimit,pattern", [
    ('{ basis = "subband", param = "xz", orientations = 4 }', "anisotropic",
     r":\d+: textures\.t\.noise\.orientations: 4; the subband unit of profile 'reduced_subband_k8' holds 8 oriented tiles"),
    ('{ basis = "subband", param = "xz", orientations = 8, weights = "least_squares" }', "anisotropic",
     r":\d+: textures\.t\.noise\.weights: the subband unit of profile 'reduced_subband_k8' computes the heuristic weights"),
    ('{ basis = "subband", param = "xz", orientations = 8 }', "isotropic",
     r":\d+: textures\.t\.bandlimit: 'isotropic'; the subband unit of profile 'reduced_subband_k8' filters with its "
     r"anisotropic weights"),
])
def test_12_subband_filter_scene_on_the_unit(tmp_path, noise, bandlimit, pattern):
    s = subband_scene(tmp_path, noise, bandlimit)
    prof = ROOT / "sim" / "test_profiles" / "reduced_subband_k8.toml"
    out = tmp_path / "out"
    refused(["render", s, "--profile", prof, "--model", "golden", "--size", 8, "-o", out, "-q"],
            (re.escape(str(s)) if pattern.startswith(":") else "") + pattern, [out])


# A bandlimit the profile cannot do, named by the scene's line (the fade unit missing; a
# reference-only option).
@pytest.mark.parametrize("bandlimit,pattern", [
    ("isotropic", r"textures\.t\.bandlimit: profile 'reduced' has no fade unit"),
    ("footprint", r"textures\.t\.bandlimit: 'footprint' is in the reference model only"),
])
def test_12_bandlimit_the_profile_cannot_do_names_the_line(tmp_path, bandlimit, pattern):
    s = subband_scene(tmp_path, '{ basis = "rayshade" }', bandlimit)
    out = tmp_path / "out"
    refused(["render", s, "--profile", "reduced", "--model", "golden", "--size", 8, "-o", out, "-q"],
            re.escape(str(s)) + r":\d+: " + pattern, [out])


# 44. Filter options the hardware refuses because they measured worse than unfiltered (issue 44
# part 2; docs/HARDWARE.md unit 6, refused combinations; testbench/verify/driver refusedFilter): the
# colour-table MIP map on a ramp colour map on bases worley and subband without its anisotropic
# filter. Named by the scene's colormap line, exit 2, nothing written; the same scene
# with a step map, with sat, or on a basis the rule does not cover renders.
WORLEY = '{ basis = "worley", coef = [1.0, 0.0], search = "octant", max_points = 4, cubes = "rom256" }'
SUBBAND = '{ basis = "subband", param = "xz", orientations = 8 }'


def filter_scene(tmp, noise, filt, interp=None, bandlimit=None):
    s = subband_scene(tmp, noise, bandlimit)
    text = s.read_text().replace('filter = "sat"', f'filter = "{filt}"')
    if interp:
        text = text.replace('wrap = "mod",', f'wrap = "mod", interp = "{interp}",')
    s.write_text(text)
    return s


@pytest.mark.parametrize("noise,prof,filt,bandlimit", [
    (WORLEY, "reduced_worley", "mip", None),
    (WORLEY, "reduced_worley", "mip_linear", None),
    (SUBBAND, "reduced_subband", "mip_linear", None),
    (SUBBAND, "reduced_subband_k8", "mip", None),            # the unit's filter off: the isotropic sum
])
def test_44_mip_on_a_ramp_refused(tmp_path, noise, prof, filt, bandlimit):
    s = filter_scene(tmp_path, noise, filt, bandlimit=bandlimit)
    out = tmp_path / "out"
    refused(["render", s, "--profile", ROOT / "sim" / "test_profiles" / f"{prof}.toml", "--model", "golden",
             "--size", 8, "-o", out, "-q"],
            re.escape(str(s)) + r":\d+: textures\.t\.colormap\.interp: 'linear' \(a ramp\) with filter '" + filt +
            r"' is refused on profile '" + prof + r"' \(basis \w+.*\): the colour-table MIP map's box .* measured worse "
            r"than unfiltered .*docs/HARDWARE\.md unit 6", [out])


@pytest.mark.parametrize("noise,prof,filt,interp,bandlimit", [
    (WORLEY, "reduced_worley", "mip", "step", None),             # a step map
    (WORLEY, "reduced_worley", "sat", None, None),               # the SAT
    (SUBBAND, "reduced_subband_k8", "mip", None, "anisotropic"),  # the subband unit's filter on
    ('{ basis = "rayshade" }', "reduced", "mip", None, None),    # bases the rule does not cover
    ('{ basis = "perlin2002" }', "reduced_perlin2002", "mip_linear", None, None),
])
def test_44_what_the_rule_does_not_cover_renders(tmp_path, noise, prof, filt, interp, bandlimit):
    s = filter_scene(tmp_path, noise, filt, interp, bandlimit)
    path = ROOT / "sim" / "test_profiles" / f"{prof}.toml"
    out = tmp_path / "out"
    rc, err = pst("render", s, "--profile", path if path.exists() else prof, "--model", "golden", "--size", 8,
                  "-o", out, "-q")
    assert rc == 0, err
    assert out.is_dir() and any(out.iterdir())


# 13. OBJ meshes read strictly (issue 41): every malformed coordinate or index, a short face, a
# file that is not a regular file refused with the OBJ's own line (`error: SCENE:LINE:
# objects[0].file: PATH:LINE: KEYWORD: what`), exit 2, nothing written; a byte-order mark and
# CRLF line ends read as plain LF text.
TRI = "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
OBJ = 'mesh = "obj"\nfile = "m.obj"'


@pytest.mark.parametrize("obj,pattern", [
    ("v 0 one 1\n", r":1: v: y 'one' is not a number"),
    ("v 0 1 nan\n", r":1: v: z 'nan' is not finite"),
    ("v 0 inf 1\n", r":1: v: y 'inf' is not finite"),
    ("v 0 1\n", r":1: v: expected x y z \(or x y z w, x y z r g b\), got 2 values"),
    ("v 0 1.0abc 1\n", r":1: v: y '1\.0abc' is not a number \(trailing 'abc'\)"),
    (TRI + "f 1 2 4294967299\n", r":4: f: vertex index '4294967299' out of range \(3 vertices defined above\)"),
    (TRI + "f 1 2 3abc\n", r":4: f: vertex index '3abc' is not an integer"),
    (TRI + "f 1 2 3.7\n", r":4: f: vertex index '3\.7' is not an integer"),
    (TRI + "f 0 1 2\n", r":4: f: vertex index 0 \(OBJ indices count from 1, or back from -1\)"),
    (TRI + "f 1 2 4\n", r":4: f: vertex index '4' out of range \(3 vertices defined above\)"),
    (TRI + "f -1 -2 -4\n", r":4: f: vertex index '-4' out of range \(3 vertices defined above\)"),
    (TRI + "f 1 2 3\nf 1\n", r":5: f: a face needs at least 3 vertices, got 1"),
    (TRI + "f 1 2\n", r":4: f: a face needs at least 3 vertices, got 2"),
    ("v 0 0 0\rv 1 0 0\rv 0 1 0\rf 1 2 3\r", r":1: a carriage return inside the line \(lines end in LF or CRLF\)"),
    (TRI + "\0\n", r":4: control character 0x00 \(not a text file\?\)"),
    (TRI, r": no faces"),
    ("DIR", r": not a regular file \(a directory\)"),
    ("FIFO", r": not a regular file \(a FIFO\)"),
])
def test_13_obj_refused_with_its_line(tmp_path, obj, pattern):
    s = scene(tmp_path, object=OBJ)
    m = tmp_path / "m.obj"
    if obj == "DIR":
        m.mkdir()
    elif obj == "FIFO":
        os.mkfifo(m)  # opening it would block: refused by kind, unopened
    else:
        m.write_bytes(obj.encode())
    out = tmp_path / "out"
    refused(["render", s, "-o", out, "-q"],
            re.escape(str(s)) + r":\d+: objects\[0\]\.file: " + re.escape(str(m)) + pattern, [out])


# A device is refused by kind, not read until memory runs out (it used to grow to 2 GB).
def test_13_obj_device_refused_by_kind(tmp_path):
    s = scene(tmp_path, object='mesh = "obj"\nfile = "/dev/zero"')
    out = tmp_path / "out"
    for mode in (["render", s, "-o", out, "-q"], ["atlas", s, "--size", 16, "-o", out, "-q"]):
        refused(mode, re.escape(str(s)) + r":\d+: objects\[0\]\.file: /dev/zero: not a regular file "
                r"\(a character device\)", [out])


# A byte-order mark no longer hides the first line (every index shifted by one, another
# triangle drawn): with it, and with CRLF line ends, the image is the plain file's.
def test_13_obj_bom_and_crlf_read_as_plain(tmp_path):
    plain = "v -0.5 0 -0.5\nv 0.5 0 -0.5\nv 0.5 0 0.5\nv -0.5 0 0.5\nf 1 2 3\n"  # the plane y = 0, as PLANE
    images = {}
    for name, data in [("plain", plain.encode()), ("bom", b"\xef\xbb\xbf" + plain.encode()),
                       ("bom_crlf", b"\xef\xbb\xbf" + plain.replace("\n", "\r\n").encode())]:
        d = tmp_path / name
        d.mkdir()
        s = scene(d, object=OBJ)
        (d / "m.obj").write_bytes(data)
        rc, err = pst("render", s, "-o", d / "out", "-q")
        assert rc == 0, err
        pngs = sorted((d / "out").glob("*.png"))
        assert pngs, f"no image in {d / 'out'}"
        images[name] = pngs[0].read_bytes()
    assert images["bom"] == images["plain"]
    assert images["bom_crlf"] == images["plain"]


# 41 part 5: messages that say the truth.
# --variants lists the bandlimits it takes (it listed fade, widen and match, which it refused).
def test_41_5_variants_list_only_what_they_take(tmp_path):
    out = tmp_path / "out"
    refused(["render", scene(tmp_path), "--variants", "sat+fade", "-o", out, "-q"],
            r"--variants: 'fade' is not a bandlimit \(off, footprint, isotropic, anisotropic\)$", [out])


# regress has no --model: its refusal of a profile without a verilated model does not suggest it.
def test_41_5_regress_suggests_no_option_it_lacks(tmp_path):
    other = profile_copy(tmp_path, "other")
    out = tmp_path / "r.json"
    rc, err = pst("regress", scene(tmp_path), "--profile", other, "--size", 4, "-o", out)
    assert rc == 2, err
    assert re.search(r"^error: " + re.escape(str(other)) + r": profile 'other' has no verilated model", err, re.M), err
    assert "--model" not in err, err
    assert not out.exists()
    # render has --model: there it is suggested.
    rc, err = pst("render", scene(tmp_path), "--profile", other, "-o", tmp_path / "o", "-q")
    assert rc == 2 and "or use --model golden" in err, err


# A number in a message is printed short (1e308 was printed in 316 digits).
@pytest.mark.parametrize("kw,got", [
    (dict(background="[1e308, 0.0, 0.0]"), "1e+308"),
    (dict(amplitude="1234567.5"), "1234567.5"),
])
def test_41_5_numbers_printed_short(tmp_path, kw, got):
    out = tmp_path / "out"
    refused(["render", scene(tmp_path, **kw), "-o", out, "-q"],
            r".*magnitude must be at most 1e6 \(got " + re.escape(got) + r"\)$", [out])
