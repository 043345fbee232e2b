"""Design-space search: the least logic area at a quality, throughput and clock target.

    scripts/search.py [--classes 1,2,3,4,32] [--psnr DB | --psnr 1=50,2=50,3=50,4=45,32=30] [--max-loss DB] [--fmax MHZ]
                      [--start 1=full_1clk,2=full_2clk,3=full,4=full_2clk,32=reduced] [--knobs k1,k2,...] [--budget N]
                      [--backtracks N] [--size 48] [--train 8] [--valid 8] [--seed 1]
                      [--valid-seed 1000001] [--paper]
                      [--jobs 2] [--backend local|slurm] [--rtl N] [--rtl-size 32] [--out out/search]
    scripts/search.py --big        the big run (below); explicit options override its values

Per clocks-per-pixel class C (a point belongs to C when its clocks per pixel are <= C) a greedy
walk with backtracking (scripts/pstlib/explore/search.py says how and why) starts from a profile that
meets the targets and moves, one knob at a time but choosing among all knobs at every step, to
the cheaper neighbour of least logic area that still has worst training PSNR >= the target
(and Fmax >= --fmax when given: scripts/synth.py with OpenSTA on those candidates only, the
Fmax derated by the routed profile's post-route / pre-layout ratio where there is one).
--max-loss DB adds the texture-by-texture rule: every training scene within DB of the
class's start profile (the worst scene alone hides a step colour map or a mod wrap that a
cut spoils); the walk's merit is then GE saved per dB lost on the scene that loses most.
Every front point is judged on the held-out validation set (scripts/pstlib/validation/valset.py, seeds
--valid-seed, apart from the training seeds) by the rule of acceptance
(scripts/pstlib/validation/acceptance.py): every validation scene within 1 dB of the class's start
profile there; front.md gives its largest loss, the scene, and pass / FAIL.
Knobs: the fraction bits of every format (coord, jacobian, matrix, amplitude, offset, quadric,
f, grad, width), the noise unit's value/lattice/out fractions and guard bits, the reciprocal
bits, interpolation, corner, hash, |grad| norm, and `structure` (octaves, noise units, noise
steps, datapath among those within the class's clocks per pixel).

A point is evaluated by golden renders (`pst render --model golden`) of the training scenes
(random scenes of scripts/gen_scenes.py, seed --seed in 0..999,999, plus the paper's scenes
with --paper) at
--size: its worst-scene PSNR against the double reference; clocks per pixel from the contract;
logic GE from a per-module synthesis cache (scripts/pstlib/synth/modules.py: a derived module
is synthesized once per parameter set and source, so a point that changes one format
re-synthesizes only the modules it reaches; cache in out/search_modules/, shared by searches).
Points under --synth-floor dB are not synthesized. Energy per pixel: an estimate, the measured
energy density (docs/data/power.json) of the class's start profile times the point's logic GE and
clocks per pixel (scripts/pstlib/power/estimate.py; its error on the measured profiles is in
docs/POWER.md), and A x C x E, logic GE x clocks per pixel x nJ per pixel, beside the area.

Outputs in --out: points/NAME.toml, results/NAME.json (atomic; a rerun resumes: stored points
are not recomputed), points.csv, front.csv, front.md, front.png (area against worst training
PSNR per class, the validation PSNR of each front point beside), rtl/ (the RTL check of every
front point: verilated into build-search/, `pst regress --size --rtl-size`, 0 mismatches).

--backend slurm submits each batch of points as an sbatch job array (scripts/pstlib/backends/slurm.py:
--partition, --account, --time, --slurm-arg) and collects the same per-point results; a failed
or cancelled task is rerun by the next run of the same command.

--big: all knobs, 32 training + 64 validation scenes plus the paper's at 128 x 128, budget 200
points per class, 4 backtracks, PSNR targets 1=50,4=45,32=30 (hours on a many-core machine or a
cluster: use --backend slurm).
Code: scripts/pstlib/explore/ (search.py the space and the walk, search_run.py the run,
evaluate.py one point, store.py the results and their reuse, rtlcheck.py, local.py and
slurm.py the backends, search_report.py).
Exit status: 0; 1 if a front point fails its RTL check or a point failed; 2 on bad arguments;
130 when interrupted.
"""
import argparse
import pathlib
import sys

from ..explore.search import KNOB_NAMES
from ..explore.search_run import run, settings, worker
from ..backends import slurm
from ..paths import ROOT


def parse_args(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--classes", default="1,2,3,4,32")
    ap.add_argument("--psnr", help="target worst training PSNR, dB (one value or CLASS=DB,...; default 40)")
    ap.add_argument("--max-loss", help="texture by texture: every training scene within this many dB of the "
                    "class's start profile (one value or CLASS=DB,...; default: no such bound)")
    ap.add_argument("--fmax", type=float, default=0.0, help="target Fmax, MHz (0: no constraint); met by the Fmax derated from the routed profile "
                    "(scripts/synth/layout_derate.json) where the silicon flow gives one, else the pre-layout Fmax")
    ap.add_argument("--start", help="start profile per class, CLASS=PROFILE,... (default 1=full_1clk,2=full_2clk,3=full,4=full_2clk,32=reduced)")
    ap.add_argument("--knobs", help=f"comma-separated, default all: {','.join(KNOB_NAMES)}")
    ap.add_argument("--budget", type=int, help="points per class walk (default 40)")
    ap.add_argument("--backtracks", type=int, help="backtracks per walk (default 2)")
    ap.add_argument("--size", type=int, help="image size of the renders (default 48)")
    ap.add_argument("--train", type=int, help="random training scenes (default 8)")
    ap.add_argument("--valid", type=int, help="held-out validation scenes (default 8; --big 64)")
    ap.add_argument("--seed", type=int, default=1, help="training scenes' seed, 0..999999")
    ap.add_argument("--valid-seed", type=int, help="validation set's seed, 1000000..1999999 (default 1000001)")
    ap.add_argument("--paper", action="store_true", default=None, help="the paper's scenes in the training set too")
    ap.add_argument("--synth-floor", type=float, default=None,
                    help="points whose worst training PSNR is below this are not synthesized (default: lowest target - 10)")
    slurm.add_backend_args(ap, "02:00:00")
    ap.add_argument("--rtl", type=int, default=None, help="front points per class checked on the RTL (default all)")
    ap.add_argument("--rtl-size", type=int, default=32)
    ap.add_argument("--retry-failed", action="store_true")
    ap.add_argument("--big", action="store_true", help="the big run (see above)")
    ap.add_argument("--out", default=str(ROOT / "out" / "search"))
    ap.add_argument("--module-cache", default=str(ROOT / "out" / "search_modules"))
    ap.add_argument("--rom-dir", default=str(ROOT / "build" / "rom"))
    ap.add_argument("--pst", default=str(ROOT / "build" / "pst"))
    try:
        return settings(vars(ap.parse_args(argv)))
    except ValueError as e:
        ap.error(str(e))



def main(argv=None) -> int:
    """The command: a SLURM array task (`worker OUT NAMES WHICH`) or the search."""
    argv = sys.argv[1:] if argv is None else list(argv)
    if argv and argv[0] == "worker":      # a SLURM array task: scripts/search.py worker OUT NAMES WHICH
        return worker(pathlib.Path(argv[1]), argv[2], argv[3])
    return run(parse_args(argv))


if __name__ == "__main__":
    sys.exit(main())
