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
