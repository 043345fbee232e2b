"""The paper's Figures 10 and 11 from the simulator's images.

    /usr/bin/python3 scripts/figures.py fig11 --out out
        Needs `build/pst regress --size 512 -o out/regress.json --images out` first. Writes
        out/figures/fig11_<scene>.png (reference | full | reduced over |full - reference| and
        |reduced - reference|, differences x8), out/figures/fig11.png (every scene, one row
        each) and out/figures/fig11.md (captions, PSNR of full and reduced against the reference).

    /usr/bin/python3 scripts/figures.py fig10 --out out [--bits 4,6,8,10,12,16]
        Writes out/figures/fig10/coord_frac_<b>.toml (rtl/configs/full.toml with
        formats.coord.frac = b), renders scenes/precision.toml through the golden model of each
        (build/pst render --model golden), and builds out/figures/fig10.png (each precision over
        a zoomed crop) and out/figures/fig10.md (captions, PSNR per precision).

Inputs missing: a message naming the command to run first, exit status 2. Every output file is
written to a temporary name in its folder and renamed into place.
"""
import argparse
import sys

from ..figures.fig10 import fig10, parse_bits, parse_crop
from ..figures.fig11 import fig11
from ..figures.figdata import InputMissing
from ..paths import ROOT, profile_path


def main(argv=None):
    ap = argparse.ArgumentParser(description="Figures 10 and 11 of Hart et al. 1999 from the simulator's images.")
    sub = ap.add_subparsers(dest="cmd", required=True)
    a11 = sub.add_parser("fig11", help="reference | full | reduced of every regressed scene")
    a11.add_argument("--out", default="out", help="output folder of the regression (default out)")
    a10 = sub.add_parser("fig10", help="texture-coordinate precision sweep through the golden model")
    a10.add_argument("--out", default="out", help="output folder (default out)")
    a10.add_argument("--bits", type=parse_bits, default=parse_bits("4,6,8,10,12,16"),
                     help="coord fraction bits to render (default 4,6,8,10,12,16)")
    a10.add_argument("--scene", default=str(ROOT / "scenes" / "precision.toml"))
    a10.add_argument("--base", default=str(profile_path("full")), help="base profile")
    a10.add_argument("--pst", default=str(ROOT / "build" / "pst"))
    a10.add_argument("--threads", type=int, default=2, help="threads of each render (default 2)")
    a10.add_argument("--crop", type=parse_crop, action="append",
                     help="X,Y,W,H region to enlarge, in pixels of a 512 x 512 image (repeatable)")
    a10.add_argument("--tile", type=int, default=320, help="panel width in pixels (default 320)")
    a10.add_argument("--columns", type=int, default=4, help="panels per row (default 4)")
    args = ap.parse_args(argv)
    if args.cmd == "fig10" and not args.crop:
        # The 40 x 40 windows of largest error at 8 and 10 bits: a ring edge on the teapot's body
        # and marble veins on the slab's top.
        args.crop = [[132, 210, 40, 40], [228, 390, 40, 40]]
    try:
        return fig11(args) if args.cmd == "fig11" else fig10(args)
    except InputMissing as e:
        print(f"error: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
