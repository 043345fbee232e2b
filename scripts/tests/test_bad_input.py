"""Bad input to the `pst` tool, one test per class of bad input (found by trying the tool as a
hostile user would): each must give `error: FILE:LINE: FIELD: ...` (or `error: --flag: ...` for
a flag), exit status 2, and leave no output file behind. Run by ctest (cli_bad_input) with
PST_BIN set to the built tool; skipped without it. The noise bases' keys and what a hardware
profile's noise unit cannot do: test_bad_input_noise.py."""
import os
import re
import subprocess

import pytest

from pstlib.paths import ROOT
from pst_cli import PLANE, PST, needs_pst, profile_copy, pst, refused, scene

pytestmark = needs_pst


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
