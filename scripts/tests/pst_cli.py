"""What the tests of the built `pst` tool share (ctest sets PST_BIN; without it they are skipped):
the tool run and the check of a refusal (`error: ...`, exit 2, nothing left behind); for the
bad-input tests (test_bad_input.py, test_bad_input_noise.py) a tiny scene and a copy of a profile."""
import os
import pathlib
import re
import subprocess

import pytest

from pstlib.paths import ROOT

PST = os.environ.get("PST_BIN", "")
# The tests need the built tool (ctest sets PST_BIN): `pytestmark = needs_pst` in each module.
needs_pst = pytest.mark.skipif(not PST or not os.path.exists(PST), reason="PST_BIN not set")

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


def run(*args, cwd=None, env=None, timeout=300) -> subprocess.CompletedProcess:
    """The tool with ARGS (str() each) on this checkout's sources (PST_SOURCE_DIR), ENV added."""
    return subprocess.run([PST, *map(str, args)], capture_output=True, text=True, cwd=cwd, timeout=timeout,
                          env=dict(os.environ, PST_SOURCE_DIR=str(ROOT), **(env or {})))


def pst(*args, cwd=None):
    r = run(*args, cwd=cwd)
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
