"""Bad input to scripts/pnr.py: exit 2, a message naming what is wrong, nothing written."""
import subprocess

from pstlib.paths import PY, ROOT


def run(tmp_path, *args):
    return subprocess.run([PY, str(ROOT / "scripts" / "pnr.py"), *args, "--out", str(tmp_path / "out")],
                          capture_output=True, text=True, timeout=120)


def test_unknown_profile(tmp_path):
    r = run(tmp_path, "no_such_profile")
    assert r.returncode == 2 and "no_such_profile" in r.stderr and "no such profile" in r.stderr
    assert not (tmp_path / "out").exists()


def test_bad_flags(tmp_path):
    r = run(tmp_path, "reduced", "--jobs", "0")
    assert r.returncode == 2 and "--jobs" in r.stderr
    assert not (tmp_path / "out").exists()
