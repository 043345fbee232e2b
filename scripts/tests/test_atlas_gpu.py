"""`pst atlas --filler gpu` (issue 42 part 5, docs/ATLAS.md, docs/MULTIPASS.md): the atlas of
Figure 13's sphere (scenes/atlas/fig13_sphere.toml) and of the wood teapot filled by the multipass
noise on OpenGL ES 3 through EGL; every GPU noise value equal to the CPU model's (pst atlas runs
the CPU model on the same coordinate bytes, independent of the GL path, and counts differences:
exit 1 on any); the render from the GPU atlas; and the refusals (exit 2, nothing written).

Run by ctest: multipass_atlas_gpu (-k "not refus"; exit 77, ctest SKIP, only when no EGL device
can be opened or the build has no EGL) and multipass_atlas_refusals (-k refus), PST_BIN set."""
import json
import math
import pathlib
import re

import pytest

from pst_cli import ROOT, needs_pst, run

pytestmark = needs_pst
SPHERE = ROOT / "scenes" / "atlas" / "fig13_sphere.toml"
TEAPOT = ROOT / "scenes" / "wood_teapot.toml"
NO_EGL = re.compile(r"^error: EGL: (no EGL device could be opened|this pst was built without EGL)", re.M)


def pst(*args, env=None):
    r = run(*args, env=env, timeout=600)
    return r.returncode, r.stdout, r.stderr


def gpu_run(scene, out, *extra):
    rc, stdout, err = pst("atlas", scene, "--filler", "gpu", "--size", 128, "--image", 48, "--truth", 1,
                          "-o", out, "-q", *extra)
    if rc == 2 and NO_EGL.search(err):
        pytest.exit("SKIPPED: " + err.strip(), returncode=77)  # ctest SKIP_RETURN_CODE 77
    assert rc == 0, stdout + err
    return json.loads((out / "atlas.json").read_text()), stdout


# Draws per octave run at b_f = 4 (docs/MULTIPASS.md): linear 100 / 335 / 88, SCURVE +12 (not rc).
@pytest.mark.parametrize("scene,variant,interp,draws", [
    (SPHERE, "sgi", "linear", 100), (SPHERE, "rc", "linear", 335), (SPHERE, "xor", "linear", 88),
    (TEAPOT, "sgi", "scurve", 112)])
def test_gpu_fill_equals_cpu_model(tmp_path, scene, variant, interp, draws):
    out = tmp_path / variant
    j, stdout = gpu_run(scene, out, "--variant", variant)
    g = j["gpu"]
    assert g["variant"] == variant and g["interp"] == interp and g["b"] == 8 and g["b_f"] == 4 and g["b_i"] == 4
    octaves = 2 if scene == SPHERE else 1
    assert g["octaves"] == octaves
    assert g["draws_per_octave"] == draws and g["draws"] == draws * octaves
    assert g["texels"] == j["fill"]["texels"] > 0
    # Bit for bit: every octave's noise byte of every texel, GL against the CPU model.
    assert g["cpu_model"]["noise_values"] == g["texels"] * octaves
    assert g["cpu_model"]["mismatches"] == 0
    assert g["texels_per_second"] > 0 and g["texels_per_second_passes"] >= g["texels_per_second"]
    assert j["fill"]["texels_per_second"] > 0
    for k in ["render_bilinear_rms_vs_truth", "render_bilinear_rms_vs_per_pixel"]:
        assert math.isfinite(g[k]) and 0 < g[k] < 1, (k, g[k])
    assert 0 <= g["vs_reference"]["rms"] < 1
    assert g["renderer"] and g["gl_version"].startswith("OpenGL ES")
    assert j["seams"]["nearest"] == 0 and j["seams"]["bilinear"] == 0
    for f in ["atlas.png", "atlas_gpu.png", "render_gpu_bilinear.png", "render_bilinear.png", "atlas.md"]:
        assert (out / f).exists(), f
    assert "Fill on the GPU" in (out / "atlas.md").read_text()
    assert "values differing from the CPU model" in stdout


# The exclusive-or variant computes the sphere's noise (Rayshade's value noise, 8-bit hash,
# linear) pointwise up to 8 bits and the coordinates' 1/16 cell; the SGI lattice is another
# random field: its atlas is far further from the host's.
def test_xor_variant_is_the_reference_noise(tmp_path):
    jx, _ = gpu_run(SPHERE, tmp_path / "xor", "--variant", "xor")
    js, _ = gpu_run(SPHERE, tmp_path / "sgi", "--variant", "sgi")
    assert jx["gpu"]["vs_reference"]["rms"] < 0.5 * js["gpu"]["vs_reference"]["rms"]
    assert jx["gpu"]["render_bilinear_rms_vs_per_pixel"] < js["gpu"]["render_bilinear_rms_vs_per_pixel"]


def refused(args, pattern, out, env=None):
    rc, _, err = pst(*args, env=env)
    assert rc == 2, f"exit {rc}, stderr:\n{err}"
    assert re.search(pattern, err, re.M), f"stderr does not match {pattern!r}:\n{err}"
    assert not pathlib.Path(out).exists(), f"{out} was left behind"


def test_refused_gpu_with_profile(tmp_path):
    out = tmp_path / "out"
    refused(["atlas", SPHERE, "--filler", "gpu", "--profile", "full", "--model", "golden", "-o", out, "-q"],
            r"^error: --filler gpu: refuses --profile", out)


@pytest.mark.parametrize("flag,value", [("--variant", "xor"), ("--bf", "3")])
def test_refused_gpu_option_without_gpu_filler(tmp_path, flag, value):
    out = tmp_path / "out"
    refused(["atlas", SPHERE, flag, value, "-o", out, "-q"], r"^error: " + flag + ": needs --filler gpu", out)
    refused(["atlas", SPHERE, "--filler", "host", flag, value, "-o", out, "-q"], r"^error: " + flag + ": needs --filler gpu", out)


@pytest.mark.parametrize("args", [["--filler", "chip"], ["--filler", "gpu", "--variant", "nv"],
                                  ["--filler", "gpu", "--bf", "8"]])
def test_refused_bad_values(tmp_path, args):
    out = tmp_path / "out"
    refused(["atlas", SPHERE, *args, "-o", out, "-q"], r"--(filler|variant|bf)", out)


def test_refused_basis_the_multipass_cannot_stand_for(tmp_path):
    scene = tmp_path / "worley.toml"
    scene.write_text(SPHERE.read_text().replace('noise = { interp = "linear", corner = "value", hash = "perm256" }',
                                                'noise = { basis = "worley" }'))
    out = tmp_path / "out"
    rc, _, err = pst("atlas", scene, "--filler", "gpu", "--size", 128, "--truth", 1, "-o", out, "-q")
    assert rc == 2, err
    assert re.search(r"^error: --filler gpu: texture 'noise' has noise basis worley", err, re.M), err
    assert not out.exists()


# No EGL vendor for glvnd: "error: EGL: ...", exit 2, nothing written (also without EGL in the build).
def test_refused_without_egl(tmp_path):
    out = tmp_path / "out"
    refused(["atlas", SPHERE, "--filler", "gpu", "--size", 128, "--truth", 1, "-o", out, "-q"], r"^error: EGL: ", out,
            env={"__EGL_VENDOR_LIBRARY_FILENAMES": "/nonexistent"})
