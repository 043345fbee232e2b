"""Random textures and scenes for judging profiles on textures they were not tuned on.

    scripts/gen_scenes.py [--seed 1] [--train 16] [--valid 16] [--out out/scenes_random]

Writes OUT/train/train_NNN.toml, OUT/valid/valid_NNN.toml (scene files `pst render` and
`pst regress` read; 512 x 512 unless --size overrides) and OUT/manifest.json (each scene's
features: octave count, matrix kind, lacunarity, quadric kind, filter, wrap, interpolation,
mesh). The same seed gives the same files byte for byte; the training and validation sets come
from separate random streams. What is drawn: scripts/pstlib/validation/scenegen.py. Exit 2 on bad arguments.
"""
import argparse
import pathlib
import sys

from ..validation import scenegen
from ..paths import ROOT


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--train", type=int, default=16, help="training scenes (default 16)")
    ap.add_argument("--valid", type=int, default=16, help="validation scenes (default 16)")
    ap.add_argument("--out", default=str(ROOT / "out" / "scenes_random"))
    a = ap.parse_args(argv)
    for k in ("train", "valid"):
        if not 0 <= getattr(a, k) <= 1000:
            ap.error(f"--{k}: must be in [0, 1000]")
    try:
        scenegen.check_training_seed(a.seed)
    except ValueError as e:
        ap.error(str(e))
    out = pathlib.Path(a.out)
    m = scenegen.write(out, a.seed, {"train": a.train, "valid": a.valid})
    print(f"wrote {len(m['sets']['train'])} training and {len(m['sets']['valid'])} validation scenes "
          f"(seed {a.seed}) to {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
