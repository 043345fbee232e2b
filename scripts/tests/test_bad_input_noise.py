"""Bad input to the `pst` tool about the noise bases (test_bad_input.py's classes 11, 12 and 44):
the subband basis's keys and bandlimit, what a hardware profile's subband, worley and filter units
cannot do, and the MIP filters refused on a ramp; each refusal names the scene's line and field,
exits 2 and leaves no output behind. Run by ctest (cli_bad_input) with PST_BIN set to the built
tool; skipped without it."""
import re

import pytest

from pstlib.paths import ROOT
from pst_cli import needs_pst, profile_copy, pst, refused, scene

pytestmark = needs_pst


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


# 44 part 2, the filter-width cap (docs/HARDWARE.md unit 5; model/texture.h widthCapOf): the scene key
# width_cap ("on" / "off") and --width-cap; a profile without the unit (filter.width_cap = "off")
# refuses a texture that asks for it, naming the scene's line; a bad value is refused; a profile
# with the unit renders it.
def cap_scene(tmp, value):
    s = subband_scene(tmp, '{ basis = "rayshade" }')
    s.write_text(s.read_text().replace('filter = "sat"\n', f'filter = "sat"\nwidth_cap = "{value}"\n'))
    return s


def test_44_width_cap_bad_value(tmp_path):
    s = cap_scene(tmp_path, "yes")
    out = tmp_path / "out"
    refused(["render", s, "--size", 8, "-o", out, "-q"],
            re.escape(str(s)) + r":\d+: textures\.t\.width_cap: unknown value 'yes' \(expected on or off\)", [out])
    rc, err = pst("render", scene(tmp_path), "--width-cap", "yes", "--size", 8, "-o", out, "-q")
    assert rc == 2 and "--width-cap: yes not in {on,off}" in err and not out.exists(), err
    refused(["render", scene(tmp_path), "--variants", "sat+cup", "--size", 8, "-o", out, "-q"],
            r"--variants: 'cup' is not a bandlimit", [out])


def test_44_width_cap_needs_the_unit(tmp_path):
    s = cap_scene(tmp_path, "on")
    out = tmp_path / "out"
    refused(["render", s, "--profile", "reduced", "--model", "golden", "--size", 8, "-o", out, "-q"],
            re.escape(str(s)) + r":\d+: textures\.t\.width_cap: profile 'reduced' has no width-cap unit "
            r"\(filter\.width_cap = \"off\"\)", [out])
    refused(["render", scene(tmp_path), "--width-cap", "on", "--profile", "reduced", "--model", "golden",
             "--size", 8, "-o", out, "-q"],
            r"texture 't': width_cap: profile 'reduced' has no width-cap unit", [out])


def test_44_width_cap_renders_on_its_unit(tmp_path):
    out = tmp_path / "out"
    rc, err = pst("render", cap_scene(tmp_path, "on"), "--profile",
                  ROOT / "sim" / "test_profiles" / "reduced_bandlimit.toml", "--model", "golden", "--size", 8,
                  "-o", out, "-q")
    assert rc == 0, err
    assert out.is_dir() and any(out.iterdir())
    rc, err = pst("render", scene(tmp_path), "--variants", "sat+cap,sat+isotropic+cap", "--size", 8,
                  "-o", tmp_path / "ref", "-q")
    assert rc == 0, err
