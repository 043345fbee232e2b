"""The command-line habits of pst's users (issue 40 part 3, 41 parts 1 and 4): --version, a typo'd
subcommand, defaults and verilated profiles in help, compare gating, provenance in every JSON
and JUnit output, --reseed, progress and -q, regress --waves on an injected mismatch and animate
--trace of one frame (each FST checked by its header), outputs that would overwrite an input or cannot be made, and self-tests
that cannot fire. Run by ctest (cli_habits) with PST_BIN set to the built tool."""
import json
import re
import struct
import subprocess
import tomllib
import xml.etree.ElementTree as ET

import pytest

from pstlib.paths import ROOT
from pst_cli import needs_pst, run

pytestmark = needs_pst
ZONE = str(ROOT / "scenes" / "zoneplate.toml")
FIRE = str(ROOT / "scenes" / "fire.toml")


def pst(*args, cwd=None):
    return run(*args, cwd=cwd, timeout=600)


def version():
    r = pst("--version")
    assert r.returncode == 0, r.stderr
    return r.stdout


def test_version():
    out = version()
    assert re.match(r"pst \d+\.\d+\ncommit [0-9a-f]{40}(-dirty)?\nVerilator \d+\.\d+[^\n]*\ncompiler \S+ \d+[^\n]*\n"
                    r"verilated profiles: \w+", out), out


def test_unknown_subcommand_suggests_the_nearest():
    r = pst("rendr", ZONE)
    assert r.returncode == 2
    assert "error: unknown subcommand 'rendr'; did you mean 'render'?" in r.stderr, r.stderr
    r = pst("regres")
    assert r.returncode == 2 and "did you mean 'regress'?" in r.stderr, r.stderr
    r = pst("zzzzzzzz")
    assert r.returncode == 2 and "unknown subcommand 'zzzzzzzz'" in r.stderr and "did you mean" not in r.stderr


def test_help_shows_defaults_and_verilated_profiles():
    verilated = re.search(r"verilated profiles: ([^\n]+)", version()).group(1).split(", ")
    h = pst("regress", "--help").stdout
    assert re.search(r"--size INT[^\n]*=64\b", h), h
    assert re.search(r"--waves-before UINT[^\n]*=2000\b", h), h
    h = pst("render", "--help").stdout
    assert re.search(r"-j,--threads INT[^\n]*=0\b", h), h
    m = re.search(r"--profile [^\n]*\n?[^\n]*verilated in this build: ([^;]+);", h)
    assert m, h
    assert m.group(1).split(", ") == verilated
    for sub in ("eval", "animate", "atlas"):
        assert ", ".join(verilated) in pst(sub, "--help").stdout, sub


@pytest.fixture(scope="module")
def images(tmp_path_factory):
    d = tmp_path_factory.mktemp("cmp")
    r = pst("render", ZONE, "--size", 16, "-o", d / "r", "-q")
    assert r.returncode == 0, r.stderr
    return d, d / "r" / "filtered.png", d / "r" / "unfiltered.png"


def test_compare_thresholds_difference_image_json(images):
    d, a, b = images
    r = pst("compare", a, b)
    assert r.returncode == 0, r.stderr
    psnr = float(re.search(r"psnr (\S+) dB", r.stdout).group(1))
    mx = float(re.search(r"max (\S+)", r.stdout).group(1))
    assert 0 < mx <= 1 and psnr > 0
    r = pst("compare", a, b, "--fail-psnr", psnr + 1)
    assert r.returncode == 1 and re.search(r"FAILED: psnr [0-9.]+ dB is below --fail-psnr [0-9.]+\n", r.stdout), r.stdout
    assert "000000" not in r.stdout   # numbers printed short
    assert pst("compare", a, b, "--fail-psnr", psnr - 1).returncode == 0
    r = pst("compare", a, b, "--fail-max", mx / 2)
    assert r.returncode == 1 and "is above --fail-max" in r.stdout, r.stdout
    assert pst("compare", a, b, "--fail-max", mx).returncode == 0
    assert pst("compare", a, a, "--fail-psnr", 200, "--fail-max", 0).returncode == 0   # identical: inf dB
    r = pst("compare", a, b, "--fail-psnr", psnr + 1, "--diff-out", d / "diff.png", "--json", d / "c.json", "-q")
    assert r.returncode == 1 and r.stderr == ""
    j = json.loads((d / "c.json").read_text())
    assert j["passed"] is False and j["fail_psnr"] == pytest.approx(psnr + 1) and j["psnr"] == pytest.approx(psnr, rel=1e-4)
    assert j["schema"] >= 2 and re.fullmatch(r"[0-9a-f]{40}(-dirty)?", j["commit"])
    assert "Verilator" in j["tool_versions"]["verilator"] and j["command_line"][1] == "compare"
    # The difference image's largest value is the largest difference (8-bit PNG: within one step).
    r = pst("compare", d / "diff.png", d / "diff.png")
    black = d / "black.png"
    assert pst("compare", d / "diff.png", a, "--diff-out", black, "--diff-scale", 0).returncode == 0
    r = pst("compare", d / "diff.png", black)
    assert float(re.search(r"max (\S+)", r.stdout).group(1)) == pytest.approx(mx, abs=1.5 / 255)


def test_outputs_that_are_inputs_are_refused(images, tmp_path):
    d, a, b = images
    before = a.read_bytes()
    r = pst("compare", a, b, "--json", a)
    assert r.returncode == 2 and "is the input" in r.stderr and a.read_bytes() == before, r.stderr
    frags = tmp_path / "f.txt"
    assert pst("fragments", ZONE, "--size", 4, "-o", frags).returncode == 0
    tex = tmp_path / "t.toml"
    tex.write_text('quadric = { A = 5.0 }\nfilter = "none"\n'
                   'colormap = { size = 16, ramp = [[0.0, 0.0, 0.0, 1.0], [1.0, 1.0, 1.0, 1.0]] }\n')
    text = frags.read_text()
    r = pst("eval", "-t", tex, "-f", frags, "-o", frags)
    assert r.returncode == 2 and "-o: " in r.stderr and "is the input" in r.stderr, r.stderr
    assert frags.read_text() == text
    scene = tmp_path / "s.toml"
    scene.write_text(open(ZONE).read())
    for args in (["fragments", scene, "-o", scene], ["regress", scene, "--size", 4, "--profile", "reduced", "-o", scene],
                 ["regress", scene, "--size", 4, "--profile", "reduced", "--junit", scene]):
        r = pst(*args)
        assert r.returncode == 2 and "is the input" in r.stderr, (args, r.stderr)
        assert scene.read_text() == open(ZONE).read()


def test_output_folder_that_cannot_be_made_is_refused_first(tmp_path):
    f = tmp_path / "file"
    f.write_text("x")
    r = pst("render", ZONE, "--size", 4, "-o", f / "sub", "-q")
    assert r.returncode == 2 and "cannot be created" in r.stderr and "is not a folder" in r.stderr, r.stderr
    r = pst("regress", ZONE, "--size", 4, "--profile", "reduced", "-o", tmp_path / "missing" / "r.json")
    assert r.returncode == 2 and "folder" in r.stderr and "does not exist" in r.stderr, r.stderr
    assert "PASSED" not in r.stdout   # refused before any run


def test_regress_provenance_json_and_junit(tmp_path):
    r = pst("regress", ZONE, "--size", 8, "--profile", "reduced", "-o", tmp_path / "r.json",
            "--junit", tmp_path / "r.xml", "-q")
    assert r.returncode == 0, r.stdout + r.stderr
    j = json.loads((tmp_path / "r.json").read_text())
    assert j["schema"] == 2 and re.fullmatch(r"[0-9a-f]{40}(-dirty)?", j["commit"])
    assert set(j["tool_versions"]) >= {"pst", "verilator", "compiler", "openimageio"}
    assert j["command_line"][1:3] == ["regress", ZONE]
    assert [(x["profile"], x["passed"]) for x in j["runs"]] == [("reduced", True)]
    props = {p.get("name"): p.get("value") for p in ET.parse(tmp_path / "r.xml").iter("property")}
    assert props["commit"] == j["commit"] and props["schema"] == "2" and "regress" in props["command_line"]
    assert props["tool_versions.verilator"] == j["tool_versions"]["verilator"]


def test_render_summary_and_report_provenance(tmp_path):
    assert pst("render", ZONE, "--size", 4, "-o", tmp_path / "a", "-q").returncode == 0
    assert "commit" in json.loads((tmp_path / "a" / "report.json").read_text())
    assert pst("render", ZONE, "--size", 4, "--profile", "reduced", "--model", "golden", "-o", tmp_path / "b",
               "-q").returncode == 0
    s = json.loads((tmp_path / "b" / "summary.json").read_text())
    assert s["schema"] == 2 and s["command_line"][1] == "render"


def test_reseed_prints_each_seed(tmp_path):
    r = pst("regress", ZONE, "--size", 4, "--profile", "reduced", "--reseed", 2, "--gap-rate", 0.3, "-q",
            "-o", tmp_path / "r.json")
    assert r.returncode == 0, r.stdout + r.stderr
    seeds = [int(s) for s in re.findall(r"reseed: seed (\d+)", r.stdout)]
    assert len(seeds) == 2, r.stdout
    runs = json.loads((tmp_path / "r.json").read_text())["runs"]
    assert [x["sim_seed"] for x in runs] == seeds
    r = pst("regress", ZONE, "--size", 4, "--profile", "reduced", "--reseed", 2)
    assert r.returncode == 2 and "--reseed" in r.stderr and "--gap-rate" in r.stderr
    r = pst("regress", "--random", 40, "--profile", "reduced", "--reseed", 2, "-q")
    assert r.returncode == 0, r.stdout
    seeds = re.findall(r"reseed: seed (\d+)", r.stdout)
    assert re.search(r"PASSED: 2 profiles, 0 failed \(seeds " + ", ".join(seeds) + r"\)", r.stdout), r.stdout


def test_scene_regress_progress_with_eta_and_quiet():
    r = pst("regress", ZONE, FIRE, "--size", 4, "--profile", "reduced")
    assert r.returncode == 0
    assert re.search(r"regress: 1/2 runs \(50\.0%\), [^\n]*ETA \d+ s", r.stderr), r.stderr
    assert re.search(r"regress: 2/2 runs", r.stderr), r.stderr
    r = pst("regress", ZONE, FIRE, "--size", 4, "--profile", "reduced", "-q")
    assert r.returncode == 0 and r.stderr == "", r.stderr


def fst_header(path):
    """The FST header block (gtkwave's fstapi.c fstWriterEmitHdrBytes): tag 0, length 329, start and
    end time, the endian test double e, then scope, variable and value-change section counts."""
    b = path.read_bytes()
    assert len(b) > 330 and b[0] == 0, "not an FST file"
    seclen, start, end = struct.unpack(">QQQ", b[1:25])
    (e,) = struct.unpack("<d", b[25:33])
    scopes, nvars, _maxh, sections = struct.unpack(">QQQQ", b[41:73])
    assert seclen == 329 and abs(e - 2.718281828459045) < 1e-12
    return {"start": start, "end": end, "scopes": scopes, "vars": nvars, "sections": sections}


def test_animate_trace_of_one_frame(tmp_path):
    """pst animate --trace FILE --trace-frame K: the FST of frame K's RTL stream, its cycles counted
    from that stream's start (as pst render's); a window after the stream's end writes no file."""
    fst, out = tmp_path / "f.fst", tmp_path / "o"
    r = pst("animate", FIRE, "--frames", 3, "--size", 8, "--profile", "reduced", "--no-video", "-q", "-o", out,
            "--trace", fst, "--trace-frame", 2, "--trace-start", 100, "--trace-end", 300)
    assert r.returncode == 0, r.stdout + r.stderr
    h = fst_header(fst)
    assert h["vars"] > 10 and h["scopes"] > 0 and h["sections"] >= 1, h
    # Two dumps per cycle: the window of the traced frame's stream, not of the run's cycles.
    assert h["start"] == 200 and h["end"] == 601, h
    assert (out / "reduced" / "frame_0002.png").exists()
    # A window after the frame's stream has ended: nothing traced, no file (as pst render).
    late = tmp_path / "late.fst"
    r = pst("animate", FIRE, "--frames", 2, "--size", 8, "--profile", "reduced", "--no-video", "-q", "-o",
            tmp_path / "o2", "--trace", late, "--trace-frame", 1, "--trace-start", 10 ** 9)
    assert r.returncode == 0, r.stdout + r.stderr
    assert not late.exists()


def test_regress_waves_on_an_injected_mismatch(tmp_path):
    r = pst("regress", ZONE, "--size", 8, "--profile", "reduced", "--inject-fault", "clut", "-q")
    assert r.returncode == 1
    assert re.search(r"replay alone: pst regress \S+zoneplate.toml --size 8 --profile reduced --inject-fault clut\n"
                     r"waves: add --waves DIR to the replay", r.stdout), r.stdout
    waves = tmp_path / "w"
    r = pst("regress", ZONE, "--size", 8, "--profile", "reduced", "--inject-fault", "clut", "--waves", waves,
            "--waves-before", 100, "--waves-after", 10, "-q", "-o", tmp_path / "r.json")
    assert r.returncode == 1
    m = re.search(r"waves: (\S+zoneplate\.reduced\.fst) \(cycles (\d+)\.\.(\d+), first failure at cycle (\d+); "
                  r"open with gtkwave\)", r.stdout)
    assert m, r.stdout
    fst = waves / "zoneplate.reduced.fst"
    assert m.group(1) == str(fst) and fst.exists()
    first, last, cycle = int(m.group(2)), int(m.group(3)), int(m.group(4))
    assert (first, last) == (max(0, cycle - 100), cycle + 10)
    h = fst_header(fst)
    assert h["vars"] > 10 and h["scopes"] > 0 and h["sections"] >= 1, h
    # Two dumps per cycle (the low phase at 2c, the edge at 2c + 1): the window and nothing else.
    assert h["start"] == 2 * first and 2 * cycle < h["end"] <= 2 * last + 1, h
    # GTKWave's own reader (fst2vcd, from Debian's gtkwave package) opens it: the signals are
    # declared and the value changes start at the window's first dump.
    vcd = subprocess.run(["fst2vcd", "-f", str(fst)], capture_output=True, text=True, timeout=120)
    assert vcd.returncode == 0, vcd.stderr
    assert vcd.stdout.count("$var ") == h["vars"] and "$enddefinitions" in vcd.stdout
    assert re.search(rf"^#{2 * first}$", vcd.stdout, re.M) and re.search(r"^\$scope module ", vcd.stdout, re.M)
    run = json.loads((tmp_path / "r.json").read_text())["runs"][0]
    assert run["waves"] == {"file": str(fst), "cycle": cycle, "start": first, "end": last}
    assert pst("regress", "--random", 10, "--waves", waves).returncode == 2


def test_inject_assert_refused_where_no_assertion_is_verilated():
    plain = [p for p in re.search(r"verilated profiles: ([^\n]+)", version()).group(1).split(", ")
             if p not in re.search(r"with assertions: ([^\n]+)", version()).group(1).split(", ")]
    if not plain:
        pytest.skip("every profile of this build is verilated with assertions")
    r = pst("regress", ZONE, "--size", 4, "--profile", plain[0], "--inject-assert", 3)
    assert r.returncode == 2 and "without assertions" in r.stderr and "cannot fire" in r.stderr, r.stderr


def test_html_page_records_provenance(tmp_path):
    page = tmp_path / "p" / "regress.html"
    r = pst("regress", ZONE, "--size", 4, "--profile", "reduced", "--html", page, "-q")
    assert r.returncode == 0, r.stdout + r.stderr
    html = page.read_text()
    commit = json.loads((tmp_path / "p" / "regress.json").read_text())["commit"]
    assert re.search(r'<div class="provenance" data-schema="2">commit <code>' + re.escape(commit) + r"</code>; compiler [^;]*pst \d", html)
    assert "verilator Verilator" in html and "regress" in html


@pytest.mark.parametrize("args,pattern", [
    (["render", ZONE, "--model", "golden"], r"--model: needs --profile"),
    (["render", ZONE, "--gap-rate", "0.2"], r"--gap-rate: needs --profile"),
    (["render", ZONE, "--profile", "reduced", "--model", "golden", "--sim-seed", "3"], r"--sim-seed: needs --model rtl"),
    (["atlas", ZONE, "--stall-rate", "0.2"], r"--stall-rate: needs --profile"),
    (["animate", FIRE, "--model", "golden"], r"--model: needs --profile"),
    (["eval", "-t", ZONE, "-f", ZONE, "--profile", "full"], r"--profile: needs --model golden or rtl"),
    (["regress", "--random", "10", "--gap-rate", "0.2"], r"--gap-rate: not with --random"),
])
def test_options_that_would_do_nothing_are_refused(tmp_path, args, pattern):
    out = tmp_path / "o"
    r = pst(*args, *(["-o", out] if args[0] != "regress" else []), "-q")
    assert r.returncode == 2 and re.search("error: " + pattern, r.stderr), r.stderr
    assert not out.exists()


def _rayshade(name: str) -> bool:
    """Whether profile NAME (rtl/configs/ or sim/test_profiles/) computes basis rayshade, the
    zoneplate's (no subband or worley unit, not Perlin 2002's hash)."""
    for d in ("rtl/configs", "sim/test_profiles"):
        f = ROOT / d / f"{name}.toml"
        if f.is_file():
            n = tomllib.loads(f.read_text())["noise"]
            return n.get("subband", "none") == "none" and n.get("worley_search", "none") == "none" and \
                n.get("hash") != "perlin256"
    return False


def test_inject_assert_refused_outside_the_run():
    asserted = re.search(r"with assertions: ([^\n]+)", version()).group(1).split(", ")
    if asserted == ["none"]:
        pytest.skip("no profile of this build is verilated with assertions")
    r = pst("regress", "--random", 100, "--profile", asserted[0], "--inject-assert", 500, "-q")
    assert r.returncode == 2 and re.search(r"--inject-assert: fragment 500 is outside the run \(fragments 0\.\.99\)",
                                           r.stderr), r.stderr
    r = pst("regress", "--random", 100, "--profile", asserted[0], "--inject-assert", 50, "-q")
    assert r.returncode == 1 and "RTL assertion" in r.stdout, r.stdout   # inside: it fires
    # Scene mode: an index past a scene's fragments (zoneplate at 4 x 4 has 16) is refused, with
    # the scene named, before any run; inside, the assertion fires (on a profile that renders the
    # zoneplate's basis).
    asserted = [p for p in asserted if _rayshade(p)]
    if not asserted:
        pytest.skip("no profile of basis rayshade in this build is verilated with assertions")
    r = pst("regress", ZONE, "--size", 4, "--profile", asserted[0], "--inject-assert", 16, "-q")
    assert r.returncode == 2 and re.search(r"--inject-assert: fragment 16 is past the run of \S+zoneplate\.toml at "
                                           r"--size 4 \(16 fragments\); the self-test could not fire", r.stderr), r.stderr
    r = pst("regress", ZONE, "--size", 4, "--profile", asserted[0], "--inject-assert", 3, "-q")
    assert r.returncode == 1 and "ASSERTION" in r.stdout, r.stdout


def test_render_page_finds_the_truth_on_a_rerun(tmp_path):
    # The truth of `render SCENE --truth N` beside `render SCENE --profile P --html`: the page
    # shows it as a layer on the first run and on a rerun into the existing folders (whose files
    # are staged inside the target, not beside it, until the run commits).
    assert pst("render", ZONE, "--size", 8, "--truth", 2, "-q", cwd=tmp_path).returncode == 0
    for _ in range(2):
        r = pst("render", ZONE, "--size", 8, "--profile", "reduced", "--html", "out/page.html", "-q", cwd=tmp_path)
        assert r.returncode == 0, r.stdout + r.stderr
        assert '"label": "ground truth", "kind": "truth"' in (tmp_path / "out" / "page.html").read_text()
