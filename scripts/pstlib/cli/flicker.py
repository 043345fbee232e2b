"""Flicker table and plots of `pst animate --truth N` runs.

  scripts/flicker.py out/anim/seascape out/anim/fire ... [--md out/flicker.md] [--no-plot]

Prints the Markdown table (flicker per stream, the unfiltered / filtered ratio, hardware
mismatches) and writes flicker.png beside each flicker.json. Bad input: 'error: FILE: what', exit 2."""
import argparse
import sys
from pathlib import Path

from .. import atomic
from ..figures import flicker


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("runs", nargs="+", help="flicker.json files or the folders holding them")
    ap.add_argument("--md", help="also write the table to this file")
    ap.add_argument("--no-plot", action="store_true", help="no flicker.png")
    a = ap.parse_args(argv)
    try:
        docs = [flicker.load(p) for p in a.runs]
    except flicker.FlickerError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    table = flicker.markdown_table(docs)
    print(table, end="")
    if a.md:
        atomic.write_text(a.md, table)
    if not a.no_plot:
        for p, d in zip(a.runs, docs):
            out = (Path(p) if Path(p).is_dir() else Path(p).parent) / "flicker.png"
            flicker.plot(d, out)
            print(f"plot: {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
