"""scripts/power.py's refusals: exit 2, one error line naming what is wrong, nothing written."""
import subprocess

import pytest

from pstlib.paths import PY, ROOT

POWER = ROOT / "scripts" / "power.py"


@pytest.mark.parametrize("args, message", [
    (["nosuch"], "nosuch: no such profile"),
    (["reduced", "--scenes", "nosuch"], "--scenes: nosuch: no such scene"),
    (["reduced", "--work", "/nonexistent"], "--work: /nonexistent: not a kept synthesis"),
    (["reduced", "--pst", "/nonexistent/pst"], "--pst: /nonexistent/pst: no such binary"),
    (["reduced", "--window", "5"], "--window: must be in"),
    (["reduced", "--random", "-1"], "--random: must be in"),
])
def test_refused_before_any_work(tmp_path, args, message):
    out = tmp_path / "out"
    r = subprocess.run([PY, str(POWER), *args, "--out", str(out)], capture_output=True, text=True)
    assert r.returncode == 2, r.stderr
    assert message in r.stderr
    assert not out.exists()


# --animate: frames of a scene's time track as workloads (refused before any work when wrong).
@pytest.mark.parametrize("args, message", [
    (["reduced", "--frames", "4"], "--frames, --at, --record-animation: need --animate SCENE"),
    (["reduced", "--at", "0,1"], "--frames, --at, --record-animation: need --animate SCENE"),
    (["reduced", "--animate", "seascape", "--record"], "--record: not with --animate"),
    (["reduced", "--record-animation"], "--record-animation: need --animate SCENE"),
    (["reduced", "--animate", "seascape", "--scenes", "--random", "0"], "--animate: needs a still workload"),
    (["reduced", "--animate", "seascape", "--frames", "0"], "--frames: must be in"),
    (["reduced", "--animate", "nosuch"], "--animate: nosuch: no such scene"),
    (["reduced", "--animate", "zoneplate"], "--animate: zoneplate: the scene has no [animation] time track"),
    (["reduced", "--animate", "seascape", "--frames", "4", "--at", "0,4"], "--at: frame 4 is not in the track"),
    (["reduced", "--animate", "seascape", "--at", "0,x"], "--at: 'x' is not a frame number"),
    (["reduced", "--animate", "seascape", "--at", "3,3"], "--at: frame 3 given twice"),
])
def test_animate_refused_before_any_work(tmp_path, args, message):
    out = tmp_path / "out"
    # --pst: any existing file (the refusals come before a binary is run)
    r = subprocess.run([PY, str(POWER), *args, "--out", str(out), "--pst", str(POWER)], capture_output=True, text=True)
    assert r.returncode == 2, r.stderr
    assert message in r.stderr
    assert not out.exists()


def _power_module():
    from pstlib.cli import power
    return power


def test_frames_at():
    p = _power_module()
    assert p.frames_at(None, 48) == [0, 16, 31, 47]
    assert p.frames_at(None, 4) == [0, 1, 2, 3]
    assert p.frames_at(None, 2) == [0, 1]
    assert p.frames_at(None, 1) == [0]
    assert p.frames_at("47, 0,12", 48) == [0, 12, 47]
    assert p.track_frames(ROOT / "scenes" / "seascape.toml") == 48
    assert p.track_frames(ROOT / "scenes" / "zoneplate.toml") == 0


def test_animation_summary_against_the_still():
    p = _power_module()
    row = lambda pj: {"pj_per_pixel": pj, "cycles": 4000, "pixels": 100, "clocks_per_pixel": 40.0,  # noqa: E731
                      "dynamic_w": 0.01, "leakage_w": 1e-6}
    fly = {"frame_0000": dict(row(100.0), frame=0, t=0.0), "frame_0003": dict(row(150.0), frame=3, t=1.0)}
    an = p.animation_summary("seascape", 4, fly, row(100.0))
    assert an["pj_per_pixel_min"] == 100.0 and an["pj_per_pixel_max"] == 150.0 and an["spread"] == 1.5
    assert an["still_pj_per_pixel"] == 100.0 and fly["frame_0003"]["vs_still"] == 1.5
    md = p.animation_markdown(an)
    assert "| 3 | 1.000 | 4000 | 100 |" in md and "spread 1.500x" in md
    assert p.animation_summary("seascape", 4, fly, None)["still_pj_per_pixel"] is None


def test_record_animation_and_its_section(tmp_path):
    from pstlib.docs import power_doc
    p = _power_module()
    row = lambda pj, px: {"pj_per_pixel": pj, "cycles": 4000, "pixels": px, "clocks_per_pixel": 4000 / px,  # noqa: E731
                          "dynamic_w": 0.01, "leakage_w": 1e-6, "blocks_w": {}}
    fly = {"frame_0000": dict(row(100.0, 80), frame=0, t=0.0), "frame_0003": dict(row(150.0, 50), frame=3, t=1.0)}
    doc = {"profile": "reduced", "basis": "b", "window": {"start": 4000, "cycles": 4000, "size": 96, "random_seed": 11},
           "workloads": {"seascape": row(100.0, 80)}}
    doc["animation"] = p.animation_summary("seascape", 4, fly, doc["workloads"]["seascape"])
    power_doc.record_animation(tmp_path, doc, "scripts/power.py reduced --animate seascape")
    md = power_doc.animation_markdown(tmp_path)
    assert "reduced, seascape (4 frames, frame k at t = k / 3; size 96, window cycles 4000 - 8000)" in md
    assert "| still | 0.000 | 4000 | 80 | 50.00 | 100 | 1.000 |" in md
    assert "| frame 3 | 1.000 | 4000 | 50 | 80.00 | 150 | 1.500 |" in md
    rec = power_doc.load_animation(tmp_path)["runs"]["reduced/seascape/96:4000+4000"]
    assert "blocks_w" not in rec["frames_measured"]["frame_0003"] and rec["spread"] == 1.5


def test_recorded_command_names_no_local_file():
    p = _power_module()
    assert p.recorded_command(["reduced", "--work", "/x/reduced.work", "--animate", "seascape", "--out=/tmp/o",
                               "--record-animation", "--pst", "b/pst", "--at", "0,1"]) == \
        "scripts/power.py reduced --animate seascape --at 0,1"
