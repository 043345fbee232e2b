"""Outputs are whole or absent (issue 41 part 2): every command writes into a temporary folder
beside (or inside) its target and moves the files in only when the run succeeds. A run stopped
by SIGTERM or SIGINT mid-way, a frame that fails mid-animation and an `--html` page that cannot
be written leave no file of the run and no temporary folder; files that were there before are
kept. Run by ctest (cli_outputs) with PST_BIN set to the built tool; skipped without it."""
import os
import pathlib
import re
import signal
import subprocess
import time

import pytest

from pstlib.paths import ROOT
from pst_cli import PST, needs_pst

pytestmark = needs_pst
ENV = dict(os.environ, PST_SOURCE_DIR=str(ROOT))
SIGNALS = [signal.SIGTERM, signal.SIGINT]


def tree(root: pathlib.Path) -> list:
    """Every path under root (relative), sorted."""
    return sorted(str(p.relative_to(root)) for p in root.rglob("*"))


def temp_folders(root: pathlib.Path) -> list:
    return [str(p) for p in root.rglob("*") if ".pst-tmp-" in p.name]


def stop_after(args, pattern, sig, cwd, delay=0.0, timeout=300):
    """Runs pst, waits for a stderr line matching pattern (the run is under way), waits `delay`
    seconds more, sends sig; returns (exit status, stderr)."""
    with open(cwd / "stdout.txt", "w") as out:
        p = subprocess.Popen([PST, *map(str, args)], stdout=out, stderr=subprocess.PIPE, text=True, cwd=cwd, env=ENV)
        seen = []
        for line in p.stderr:
            seen.append(line)
            if re.search(pattern, line):
                break
        else:
            p.wait()
            pytest.fail(f"pst ended (exit {p.returncode}) before a line matching {pattern!r}:\n{''.join(seen)}")
        time.sleep(delay)
        p.send_signal(sig)
        try:
            rest = p.stderr.read()
            p.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            p.kill()
            pytest.fail(f"pst did not stop within {timeout} s of {sig.name}")
    return p.returncode, "".join(seen) + rest


def assert_stopped(rc, err, sig):
    # Ended by the signal itself (a shell shows 128 + sig), after removing its temporary folders.
    assert rc == -sig, f"exit {rc}, expected the signal {sig.name}; stderr:\n{err[-2000:]}"


@pytest.mark.parametrize("sig", SIGNALS, ids=lambda s: s.name)
def test_stopped_render_leaves_nothing(tmp_path, sig):
    # Two profiles: the first one's folder is complete before the second one runs; stopped
    # during the second, neither may be left (the old tool left out/full).
    (tmp_path / "keep").mkdir()
    (tmp_path / "keep" / "mine.txt").write_text("not pst's")
    out = tmp_path / "out"
    rc, err = stop_after(["render", ROOT / "scenes/zoneplate.toml", "--size", 640, "--profile", "full",
                          "--profile", "reduced", "-o", out], r"zoneplate/full: .*done", sig, tmp_path, delay=0.5)
    assert_stopped(rc, err, sig)
    assert not out.exists(), tree(out)
    assert temp_folders(tmp_path) == []
    assert (tmp_path / "keep" / "mine.txt").read_text() == "not pst's"


@pytest.mark.parametrize("sig", SIGNALS, ids=lambda s: s.name)
def test_stopped_animation_leaves_no_frame(tmp_path, sig):
    # The old tool wrote each frame as it went: stopped at frame 3, frames 0 and 1 were left.
    out = tmp_path / "anim"
    rc, err = stop_after(["animate", ROOT / "scenes/fire.toml", "--frames", 300, "--size", 48, "--no-video",
                          "-o", out], r"frame 3/300", sig, tmp_path)
    assert_stopped(rc, err, sig)
    assert not out.exists(), tree(out)
    assert temp_folders(tmp_path) == []


@pytest.mark.parametrize("sig", SIGNALS, ids=lambda s: s.name)
def test_stopped_regression_leaves_nothing_new(tmp_path, sig):
    # Into an existing folder with a file of its own: kept; the run's images, JSON and JUnit not
    # written (the old tool left the first runs' images).
    out = tmp_path / "reg"
    out.mkdir()
    (out / "notes.txt").write_text("kept")
    # Scenes every profile runs (a skipped one would print the first progress line before any image).
    scenes = [ROOT / "scenes" / f"{n}.toml" for n in ("zoneplate", "fire", "marble", "planet", "moonrise", "seascape")]
    rc, err = stop_after(["regress", *scenes, "--size", 32, "--profile", "full", "--profile", "reduced",
                          "--images", out, "-o", out / "r.json", "--junit", out / "j.xml"],
                         r"regress: 1/\d+ runs", sig, tmp_path)
    assert_stopped(rc, err, sig)
    assert tree(out) == ["notes.txt"]
    assert temp_folders(tmp_path) == []


SCENE = """title = "eye through target"
[image]
width = 16
height = 16
[camera]
eye = [0.5, 0.5, 1.0]
target = [0.5, 0.5, 0.0]
fovy = 53.13
[textures.t]
quadric = { A = 5.0, E = 5.0 }
colormap = { size = 256, wrap = "mod", ramp = [[0.0, 0.0, 0.0, 0.0], [1.0, 1.0, 1.0, 1.0]] }
[[textures.t.octaves]]
amplitude = 0.5
scale = 4.0
[[objects]]
mesh = "plane"
half_size = 0.5
texture = "t"
rotate = [90.0, 0.0, 0.0]
translate = [0.5, 0.5, 0.0]
[animation]
frames = 5
[[animation.track]]
field = "camera.eye"
keys = [[0.0, 0.5, 0.5, 1.0], [1.0, 0.5, 0.5, -1.0]]
"""


def test_failing_frame_mid_animation_leaves_no_frame(tmp_path):
    # Valid at both keys; at t = 0.5 (frame 2 of 5) the eye is the target.
    s = tmp_path / "s.toml"
    s.write_text(SCENE)
    out = tmp_path / "anim"
    r = subprocess.run([PST, "animate", str(s), "--no-video", "-q", "-o", str(out)], capture_output=True, text=True,
                       cwd=tmp_path, env=ENV, timeout=300)
    assert r.returncode == 2, r.stderr
    assert re.search(r"^error: " + re.escape(str(s)) + r": animation at t = 0\.5: ", r.stderr, re.M), r.stderr
    assert not out.exists(), tree(out)
    assert temp_folders(tmp_path) == []


ZONE = ROOT / "scenes/zoneplate.toml"


def test_html_into_a_folder_refused_before_any_work(tmp_path):
    # The page named a folder: the old tool ran the regression, wrote its images and JSON beside
    # it, then report.py failed with a traceback (exit 1).
    page = tmp_path / "page"
    page.mkdir()
    r = subprocess.run([PST, "regress", str(ZONE), "--size", "8", "--profile", "reduced", "--html", str(page)],
                       capture_output=True, text=True, cwd=tmp_path, env=ENV, timeout=300)
    assert r.returncode == 2, r.stdout + r.stderr
    assert re.search(r"^error: --html: '" + re.escape(str(page)) + "' is a folder", r.stderr, re.M), r.stderr
    assert "Traceback" not in r.stderr
    assert tree(tmp_path) == ["page"]


def test_html_where_no_folder_can_be_made(tmp_path):
    # /proc takes no new folder, not even from root: refused (exit 2, the path named) before any
    # run; the images folder given too is not left behind (the old tool wrote it, then failed
    # with a raw std::filesystem message, exit 1).
    images = tmp_path / "images"
    page = "/proc/pst-no-such-folder/page.html"
    r = subprocess.run([PST, "regress", str(ZONE), "--size", "8", "--profile", "reduced", "--images", str(images),
                        "--html", page], capture_output=True, text=True, cwd=tmp_path, env=ENV, timeout=300)
    assert r.returncode == 2, r.stdout + r.stderr
    # (named with the page, or with its folder when the folder check refuses it first)
    assert re.search(r"^error: --html: '/proc/pst-no-such-folder(/page\.html)?' cannot be", r.stderr, re.M), r.stderr
    assert tree(tmp_path) == []


def test_failed_report_step_leaves_nothing(tmp_path):
    # scripts/report.py fails (a source tree whose report.py exits 3): the run's images and
    # summaries are not left (the old tool kept them, exit 1).
    src = tmp_path / "src"
    src.mkdir()
    for e in ROOT.iterdir():
        if e.name != "scripts":
            (src / e.name).symlink_to(e)
    (src / "scripts").mkdir()
    (src / "scripts" / "report.py").write_text("import sys\nsys.exit(3)\n")
    work = tmp_path / "work"
    work.mkdir()
    r = subprocess.run([PST, "render", str(ZONE), "--size", "8", "--profile", "full", "-o", "out", "--html",
                        "out/page.html", "-q"], capture_output=True, text=True, cwd=work,
                       env=dict(ENV, PST_SOURCE_DIR=str(src)), timeout=300)
    assert r.returncode == 1, r.stdout + r.stderr
    assert tree(work) == []
    assert re.search(r"^error: --html: .*report\.py did not write 'out/page\.html'", r.stderr, re.M), r.stderr


def test_rerun_into_existing_folder_replaces_its_files_keeps_others(tmp_path):
    # A finished run moves its files in one by one: the old ones replaced, a file of the user's kept.
    out = tmp_path / "out"
    out.mkdir()
    (out / "filtered.png").write_bytes(b"old")
    (out / "mine.txt").write_text("kept")
    r = subprocess.run([PST, "render", str(ZONE), "--size", "8", "-o", str(out), "-q"], capture_output=True, text=True,
                       cwd=tmp_path, env=ENV, timeout=300)
    assert r.returncode == 0, r.stderr
    assert (out / "filtered.png").read_bytes()[:4] == b"\x89PNG"
    assert (out / "mine.txt").read_text() == "kept"
    assert "report.json" in tree(out) and temp_folders(tmp_path) == []


def test_a_killed_runs_temporary_folder_is_removed_by_the_next_run(tmp_path):
    # SIGKILL cannot be caught: the killed run's .pst-tmp-PID stays until the next run writing
    # into the same folder finds its process gone and removes it. A live process's is kept.
    p = subprocess.Popen(["true"])
    p.wait()
    dead = p.pid                                     # a process id that no longer runs
    out = tmp_path / "out"
    out.mkdir()
    for name in (f".pst-tmp-{dead}", f".marble.pst-tmp-{dead}", f".pst-tmp-{os.getpid()}"):
        (out / name).mkdir()
        (out / name / "partial.png").write_bytes(b"x")
    r = subprocess.run([PST, "render", str(ROOT / "scenes" / "marble.toml"), "--size", "8", "-q", "-o",
                        str(out / "marble")], capture_output=True, text=True, env=ENV)
    assert r.returncode == 0, r.stderr
    assert (out / "marble" / "filtered.png").exists() or any((out / "marble").iterdir())
    assert temp_folders(out) == [str(out / f".pst-tmp-{os.getpid()}")]
