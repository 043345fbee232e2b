"""The ground-truth table of the filter options: stills and animated sequences against the truth.

  scripts/fidelity.py --stills out/fidelity/* --sequences out/fidelity/anim/* [--md FILE] [--json FILE]

--stills: folders (or report.json files) of `pst render SCENE --truth N --variants sat,...`;
--sequences: folders (or flicker.json files) of `pst animate SCENE --truth N --variants ...`.
Prints the Markdown tables and the goals. Bad input: 'error: FILE: what', exit 2."""
import argparse
import json
import sys

from .. import atomic
from ..figures import fidelity, flicker


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--stills", nargs="*", default=[], help="pst render --variants outputs")
    ap.add_argument("--sequences", nargs="*", default=[], help="pst animate --variants outputs")
    ap.add_argument("--md", help="also write the Markdown to this file")
    ap.add_argument("--json", help="also write the figures as JSON")
    a = ap.parse_args(argv)
    if not a.stills and not a.sequences:
        ap.error("give --stills and/or --sequences")
    try:
        stills = [fidelity.load_still(p) for p in a.stills]
        seqs = [fidelity.sequence_figures(flicker.load(p)) for p in a.sequences]
    except (fidelity.FidelityError, flicker.FlickerError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    md = fidelity.markdown(stills, seqs)
    print(md, end="")
    if a.md:
        atomic.write_text(a.md, md)
    if a.json:
        goals = [{"goal": g, "measured": m, "met": ok} for g, m, ok in fidelity.goals(stills, seqs)]
        atomic.write_text(a.json, json.dumps({"stills": stills, "sequences": seqs, "goals": goals}, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
