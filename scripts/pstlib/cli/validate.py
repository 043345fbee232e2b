"""Profiles judged on the held-out validation set, scene by scene against full_exact.

    scripts/validate.py PROFILE... [--count 64] [--size 128] [--seed 1000001] [--jobs 1]
                        [--out out/validate] [--pst build/pst]
    scripts/validate.py --scenes-only [--count --size --seed --out]   the set alone: OUT/scenes/
    scripts/validate.py --train PROFILE... [--seed 1]   the same strata on training seeds

PROFILE: a name (rtl/configs/NAME.toml: full_exact, full, balanced, reduced, ...) or a profile
file. The set (scripts/pstlib/validation/valset.py): COUNT scenes in eight strata (step-sensitive colour
maps, a full quadric under a step map, planes to the horizon, rotated marble with a clamped map,
general affine octaves with a full quadric, axis-aligned octaves at non-power-of-two
frequencies, clamped step maps, plain draws), every filter kind, both wraps, seeds
1,000,000..1,999,999 (training takes 0..999,999). Each scene goes once through `pst render
--model golden` with every profile and full_exact (the golden model only: no RTL build needed);
PSNR against the double reference.

The rule (scripts/pstlib/validation/acceptance.py): a profile passes when on every scene its PSNR is within
1 dB of full_exact's on that scene. Writes OUT/validate.md and OUT/validate.json (per profile
worst and median PSNR, worst loss against full_exact with the scene and its features, per
stratum worst loss, every scene's PSNR), OUT/scenes/ and OUT/renders/.

--train draws the same strata on training seeds (0..999,999; scenes trn_NNN, default seed 1,
default out out/validate_train): the set to choose formats and structures on; the choice is then
judged once on the held-out set (no --train).

Exit status: 0 every profile passes; 1 one fails the rule (or a render failed); 2 bad input
(unknown profile, --count outside 1..4096, --size outside 16..2048, a seed outside the validation range, no
pst), nothing written.
"""
import argparse
import pathlib
import sys

from . import check_pst
from ..validation import valset, validate as validation
from ..paths import ROOT


def parse_args(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("profiles", nargs="*", metavar="PROFILE")
    ap.add_argument("--count", type=int, default=valset.DEFAULT_COUNT, help="scenes (default 64)")
    ap.add_argument("--size", type=int, default=valset.DEFAULT_SIZE, help="image size (default 128)")
    ap.add_argument("--seed", type=int, default=None,
                    help=f"default {valset.DEFAULT_SEED} ({valset.TRAIN_DEFAULT_SEED} with --train)")
    ap.add_argument("--jobs", type=int, default=1, help="scenes rendered in parallel (default 1)")
    ap.add_argument("--out", default=None, help="default out/validate (out/validate_train with --train)")
    ap.add_argument("--train", action="store_true", help="the strata on training seeds, for choosing")
    ap.add_argument("--pst", default=str(ROOT / "build" / "pst"))
    ap.add_argument("--scenes-only", action="store_true", help="write the set to OUT/scenes and stop (no render)")
    a = ap.parse_args(argv)
    a.split = valset.TRAINING if a.train else valset.HOLDOUT
    if a.seed is None:
        a.seed = valset.TRAIN_DEFAULT_SEED if a.train else valset.DEFAULT_SEED
    if a.out is None:
        a.out = str(ROOT / "out" / ("validate_train" if a.train else "validate"))
    try:
        if not a.profiles and not a.scenes_only:
            raise ValueError("name at least one PROFILE (full_exact is always rendered as the reference)")
        validation.resolve_profiles(a.profiles)
        valset.check(a.seed, a.count, a.size, a.split)
        if a.jobs < 1:
            raise ValueError(f"--jobs: at least 1, got {a.jobs}")
        check_pst(a)
    except ValueError as e:
        ap.error(str(e))
    return a


def main(argv=None) -> int:
    a = parse_args(sys.argv[1:] if argv is None else argv)
    if a.scenes_only:
        m = valset.write(pathlib.Path(a.out) / "scenes", a.seed, a.count, a.size, a.split)
        print(f"wrote {len(m['scenes'])} {a.split.name} scenes (seed {a.seed}) to {pathlib.Path(a.out) / 'scenes'}")
        return 0
    return validation.run(a.profiles, a.count, a.size, a.seed, pathlib.Path(a.out), a.pst, a.jobs, split=a.split)


if __name__ == "__main__":
    sys.exit(main())
