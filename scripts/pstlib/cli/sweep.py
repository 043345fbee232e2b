"""Precision sweep: gates against image quality, one knob at a time around a base profile.

    scripts/sweep.py --base full|reduced|FILE [--knobs k1,k2,...] [--values KNOB=v1,v2 ...]
                     [--scenes a,b] [--size 128] [--truth 2] [--jobs 2] [--rtl-subset 2]
                     [--no-synth] [--match-variant] [--retry-failed] [--out out/sweep/<base>]
    scripts/sweep.py --quick        the small default sweep (base reduced, coord_frac 8,10,16,
                                    octaves 2,8, hash; marble and zoneplate at 64 x 64; synthesis
                                    on; no RTL check) -> out/sweep/reduced_quick

Every point is the base profile with ONE change (a knob set to one value; values equal to the
base are skipped, values that make an invalid profile are listed as skipped with the reason).
Per point:
  - out/sweep/<base>/points/<name>.toml, name = <base>_<knob>_<value> (a C identifier);
  - each scene rendered through the golden model of that profile (`pst render SCENE --profile
    POINT.toml --model golden --truth T`): PSNR against the double reference and against the
    T x T supersampled ground truth, from the render's summary.json; and the PSNR of its images
    against the base profile's (`vs base`, worst scene);
  - unless --no-synth, the synthesis flow (pstlib.synth, what scripts/synth.py runs) on the point
    (logic GE, ROM bits, RAM bits), cached as out/synth/<name>.json with a sidecar
    <name>.sweep.json of content hashes (the profile's values; rtl/*.sv, scripts/synth.py,
    scripts/pstlib/synth/ and scripts/synth/ files); --no-synth still uses a valid cache;
  - out/sweep/<base>/results/<name>.json, written through a temporary file and a rename.
    A point with a result is not recomputed (resumable; a result without synthesis gets only
    its synthesis added; other scenes / size / truth re-render it; --retry-failed reruns the
    failed ones).
The knob `basis` sets the noise unit's interp / corner / hash triple (rayshade or perlin2002), or a
worley unit (noise.worley_search octant, the base's worley_points and worley_order), and renders
scene copies whose textures ask for that basis (worley: its variant, F1 where a texture has no
coefficients; a profile runs only its own basis), so PSNR vs reference is against the basis's own
double reference.
The knob `filter` is per texture, not a profile key: its points render copies of the scene
files with every texture's filter replaced, through the base profile (the hardware holds every
filter kind, so the GE of those points is the base's). Its reference images use the same
filter, so PSNR vs reference measures the hardware's filter against the exact one of the same
kind, and PSNR vs truth says which kind looks best.
--match-variant renders scene copies whose textures ask for each point's noise variant and
|grad| norm, so the reference is the same function and PSNR measures precision alone (without
it, a profile whose noise differs from the scenes' Rayshade noise, like reduced, is measured
against Rayshade's texture).

--rtl-subset N verilates N points (the cheapest point within 1 dB of the base of N different
knobs) into build-sweep/ (-DPST_EXTRA_PROFILE_DIR=out/sweep/<base>/rtl_points) and runs
`pst regress --profile rtl_points/NAME.toml --size 64` on each (rtl/NAME.json; a passed check
is kept): the RTL matches the golden model bit for bit there, so the golden figures stand for
the hardware.

Code: scripts/pstlib/explore/ (sweep.py the knobs and points, sweep_run.py the run, evaluate.py
one point, store.py the results and their reuse, rtlcheck.py, local.py the backend).

Outputs in --out: sweep.csv, sweep.md (table, cheapest setting within 1 dB per knob: every scene
within 1 dB of the base's PSNR there, the rule of scripts/pstlib/validation/acceptance.py; failures),
ge_vs_psnr_reference.png, ge_vs_psnr_truth.png, knobs/<knob>.png. Exit status: 0, 1 if any
point (render, synthesis, RTL check) failed, 2 on bad arguments, 130 when interrupted (Ctrl-C,
or SIGTERM in the background; running children are stopped).
"""
import argparse
import sys

from ..explore.sweep import DEFAULT_SCENES, KNOBS
from ..paths import ROOT
from ..explore.sweep_run import run, settings


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--base", help="full, reduced or a profile file (default reduced)")
    ap.add_argument("--knobs", help=f"comma-separated, default all: {','.join(KNOBS)}")
    ap.add_argument("--values", action="append", default=None, metavar="KNOB=V1,V2",
                    help="values of one knob instead of its defaults (repeatable)")
    ap.add_argument("--scenes", help=f"comma-separated scene names or files (default {','.join(DEFAULT_SCENES)})")
    ap.add_argument("--size", type=int, help="image size (default 128)")
    ap.add_argument("--truth", type=int, help="ground truth samples per axis, 0 = none (default 2)")
    ap.add_argument("--jobs", type=int, default=2, help="points in parallel (default 2)")
    ap.add_argument("--rtl-subset", type=int, dest="rtl_subset", help="points checked on the RTL (default 2)")
    ap.add_argument("--no-synth", action="store_true", help="no gate counts (renders only)")
    ap.add_argument("--retry-failed", action="store_true", help="recompute points recorded as failed")
    ap.add_argument("--match-variant", action="store_true",
                    help="render scene copies whose textures ask for the point profile's noise variant and "
                         "|grad| norm, so the reference (and truth) is the same function and PSNR measures "
                         "precision only (default out: out/sweep/<base>_matched)")
    ap.add_argument("--quick", action="store_true",
                    help="small sweep: base reduced, coord_frac 8,10,16, octaves 2,8, hash; marble and zoneplate "
                         "at 64 x 64; synthesis on; no RTL check (explicit options override)")
    ap.add_argument("--out", help="output folder (default out/sweep/<base>, out/sweep/<base>_quick with --quick)")
    ap.add_argument("--pst", default=str(ROOT / "build" / "pst"), help="pst binary for the golden renders")
    try:
        s = settings(**vars(ap.parse_args(argv)))
    except ValueError as e:
        ap.error(str(e))
    return run(s)


if __name__ == "__main__":
    sys.exit(main())
