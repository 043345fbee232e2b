"""Antialiasing in motion on held-out fly-ins: the training and validation sets of seeded fly-ins
through every filter option the reference and the hardware offer, flicker and RMS against the truth.

    scripts/flyins.py [--split both|validation|training] [--count 20] [--train-count 8]
                      [--seed 1000001] [--train-seed 1] [--frames 16] [--size 48] [--truth 8]
                      [--model rtl|golden] [--jobs 1] [--out out/flyins] [--pst build/pst] [--fresh]
                      [--check] [--record]
    scripts/flyins.py --scenes-only [...]      the sets alone: OUT/SPLIT/scenes/

The sets (scripts/pstlib/validation/flyins.py): a camera over a textured ground plane, every noise
basis a hardware profile computes (rayshade, perlin2002, worley, subband), every path kind
(forward, sideways, orbit, zoom, grazing), every colour-map kind (ramp or step, clamp or mod);
validation seeds 1,000,000..1,999,999, training seeds 0..999,999. Choose on the training set,
judge once on the validation set.

Per sequence (scripts/pstlib/validation/flyin_table.py): `pst animate --truth N` once per hardware
option group (filter mip, mip_linear, sat x the bandlimit the basis's profiles compute), the
profiles of the basis through their verilated RTL, scoreboarded against the golden model (--model
golden: the golden model alone), the reference's options as --variants. Writes OUT/flyins.md and
OUT/flyins.json (each split apart: per sequence and option RMS, flicker, the ratio against
unfiltered and against the reference's exact filter, and the flags below4x, over10, worse_rms),
OUT/SPLIT/scenes/ and OUT/SPLIT/runs/ (a run whose scene, arguments, pst binary and profile files are unchanged is reused
unless --fresh); with --record also docs/data/flyins.json, the source of docs/VERIFICATION.md's
generated fly-in table (scripts/gen_docs.py --write).

Exit status: 0 the table was written (flags are findings); 1 a pst run failed, or with --check a
flag was raised; 2 bad input (a seed outside its split's range, --count, --frames, --size, --truth
out of range, no pst), nothing written.
"""
import argparse
import json
import math
import pathlib
import subprocess
import sys

from . import check_pst
from .. import atomic
from ..paths import ROOT
from ..docs import flyins_doc
from ..validation import flyins, flyin_table


def parse_args(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--split", choices=["both", "validation", "training"], default="both")
    ap.add_argument("--count", type=int, default=flyins.VALIDATION.default_count, help="validation sequences (default 20)")
    ap.add_argument("--train-count", type=int, default=flyins.TRAINING.default_count, help="training sequences (default 8)")
    ap.add_argument("--seed", type=int, default=flyins.VALIDATION.default_seed)
    ap.add_argument("--train-seed", type=int, default=flyins.TRAINING.default_seed)
    ap.add_argument("--frames", type=int, default=flyins.DEFAULT_FRAMES)
    ap.add_argument("--size", type=int, default=flyins.DEFAULT_SIZE)
    ap.add_argument("--truth", type=int, default=8, help="N x N ground truth per pixel (default 8)")
    ap.add_argument("--model", choices=["rtl", "golden"], default="rtl")
    ap.add_argument("--jobs", type=int, default=1, help="sequences in parallel (default 1; each pst run -j 2/jobs)")
    ap.add_argument("--out", default=str(ROOT / "out" / "flyins"))
    ap.add_argument("--pst", default=str(ROOT / "build" / "pst"))
    ap.add_argument("--fresh", action="store_true", help="render every run again")
    ap.add_argument("--check", action="store_true", help="exit 1 when a flag is raised")
    ap.add_argument("--record", action="store_true",
                    help="also write the main tables' figures to docs/data/flyins.json (docs/VERIFICATION.md's "
                         "generated table: scripts/gen_docs.py --write)")
    ap.add_argument("--scenes-only", action="store_true", help="write the sets to OUT/SPLIT/scenes and stop")
    a = ap.parse_args(argv)
    a.splits = [(flyins.VALIDATION, a.seed, a.count), (flyins.TRAINING, a.train_seed, a.train_count)]
    if a.split != "both":
        a.splits = [s for s in a.splits if s[0].name == a.split]
    try:
        for split, seed, count in a.splits:
            flag = "--seed" if split is flyins.VALIDATION else "--train-seed"
            flyins.check_seed(seed, split, flag)
            if split is flyins.TRAINING and not 1 <= count <= flyins.MAX_COUNT:
                raise ValueError(f"--train-count: 1..{flyins.MAX_COUNT} sequences, got {count}")
            flyins.check(seed, count, a.frames, a.size, split)
        if not 1 <= a.truth <= 64:
            raise ValueError(f"--truth: 1..64 samples per pixel edge, got {a.truth}")
        if not 1 <= a.jobs <= 2:
            raise ValueError(f"--jobs: 1 or 2, got {a.jobs}")
        check_pst(a)
    except ValueError as e:
        ap.error(str(e))
    return a


def command(a) -> str:
    parts = ["scripts/flyins.py", f"--split {a.split}"]
    if a.split != "training":
        parts.append(f"--count {a.count} --seed {a.seed}")
    if a.split != "validation":
        parts.append(f"--train-count {a.train_count} --train-seed {a.train_seed}")
    parts.append(f"--frames {a.frames} --size {a.size} --truth {a.truth} --model {a.model}")
    return " ".join(parts)


def _commit() -> str:
    r = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"], capture_output=True, text=True)
    return r.stdout.strip() or "?"


def _finite(v):
    """The document with every infinite or NaN number as null (strict JSON)."""
    if isinstance(v, dict):
        return {k: _finite(x) for k, x in v.items()}
    if isinstance(v, list):
        return [_finite(x) for x in v]
    if isinstance(v, float) and not math.isfinite(v):
        return None
    return v


def main(argv=None) -> int:
    a = parse_args(sys.argv[1:] if argv is None else argv)
    out = pathlib.Path(a.out)
    if a.scenes_only:
        for split, seed, count in a.splits:
            m = flyins.write(out / split.name / "scenes", seed, count, a.frames, a.size, split)
            print(f"wrote {len(m['sequences'])} {split.name} fly-ins (seed {seed}) to {out / split.name / 'scenes'}")
        return 0
    docs = {}
    for split, seed, count in a.splits:
        print(f"flyins: {count} {split.name} sequences (seed {seed}), {a.frames} frames at {a.size} x {a.size}, "
              f"{a.truth} x {a.truth} truth -> {out / split.name}", flush=True)
        docs[split.name] = flyin_table.run_split(a.pst, split, seed, count, a.frames, a.size, a.truth,
                                                 out / split.name, a.model, a.jobs, a.fresh,
                                                 say=lambda m: print(m, flush=True))
    cmd = command(a)
    md = "".join(flyin_table.markdown(d, cmd) for d in docs.values())
    atomic.write_text(out / "flyins.md", md)
    summ = {n: flyin_table.summary(d) for n, d in docs.items()}
    atomic.write_text(out / "flyins.json", json.dumps(_finite({"command": cmd, "summary": summ, "splits": docs}),
                                                      indent=1) + "\n")
    errors = [e for d in docs.values() for e in d["errors"]]
    if a.record and not errors:
        rec = {"command": cmd, "commit": _commit(), "splits": {n: flyin_table.compact(d) for n, d in docs.items()}}
        atomic.write_text(ROOT / flyins_doc.SOURCE, json.dumps(_finite(rec), indent=1) + "\n")
        print(f"recorded {flyins_doc.SOURCE} (scripts/gen_docs.py --write puts it in docs/VERIFICATION.md)")
    for n, s in summ.items():
        print(f"{n}: {s['sequences']} sequences; below4x {len(s['below4x'])}, over10 {len(s['over10'])}, "
              f"worse_rms {len(s['worse_rms'])}; hardware mismatches {s['mismatches']}")
    print(f"wrote {out / 'flyins.md'} and flyins.json")
    if errors:
        print("FAILED: " + errors[0], file=sys.stderr)
        return 1
    if a.check and any(s[f] for s in summ.values() for f in ("below4x", "over10", "worse_rms")):
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
