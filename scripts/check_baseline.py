#!/usr/bin/python3
"""Checks the main job's silicon and quality figures against scripts/synth/baseline.json.

    scripts/check_baseline.py [--out out] [--baseline FILE] [--update]

Reads OUT/synth/<profile>.json (scripts/synth.py) and OUT/regress.json (`pst regress`) for
every profile in the baseline and fails (exit 1) when a figure moved by more than 2 %: logic
GE (total and per block), flip-flops, memory GE, total GE, ROM/RAM bits, clocks per pixel,
Fmax, PSNR per scene. A change that moves a figure on purpose updates the file in the same
commit: `scripts/check_baseline.py --update` after the main job (scripts/run.sh);
`--add PROFILE` adds (or replaces) one profile's figures from OUT/synth/PROFILE.json (and its
PSNRs when OUT/regress.json has them), the other profiles' left as they are. Exit 2 when an
input is missing. Also exit 1 when a profile's synthesis fails the sign-off checks (hold, max
transition, max capacitance: scripts/synth.py's), or was made with another Yosys or OpenSTA
than the baseline's (tools in the file): its figures are not comparable, so the check stops
there and says so (re-baseline with --update after checking the new tools' figures).
"""
import argparse
import json
import pathlib
import sys

from pstlib import baseline
from pstlib.paths import ROOT
from pstlib.provenance import regress_runs
from pstlib.synth import report

PROFILES = ("reduced", "full", "full_2clk", "full_1clk")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default=str(ROOT / "out"))
    ap.add_argument("--baseline", default=str(ROOT / "scripts" / "synth" / "baseline.json"))
    ap.add_argument("--update", action="store_true", help="write the current figures as the baseline")
    ap.add_argument("--add", metavar="PROFILE", help="add or replace one profile's figures, the others kept")
    args = ap.parse_args()
    out = pathlib.Path(args.out)
    path = pathlib.Path(args.baseline)
    base = json.loads(path.read_text()) if path.exists() else None
    if base is None and not args.update:
        print(f"error: {path}: no baseline (write one with --update)", file=sys.stderr)
        return 2
    if args.add:
        return add_profile(base, path, out, args.add)
    names = PROFILES if args.update or base is None else tuple(base["profiles"])
    synth, tools = {}, {}
    for n in names:
        f = out / "synth" / f"{n}.json"
        if not f.exists():
            print(f"error: {f}: missing (run scripts/synth.py {n})", file=sys.stderr)
            return 2
        synth[n] = json.loads(f.read_text())
        tools = synth[n].get("tools", tools)
        if not synth[n].get("timing"):
            print(f"error: {f}: no timing (scripts/synth.py ran with --no-sta)", file=sys.stderr)
            return 2
    reg_path = out / "regress.json"
    if not reg_path.exists():
        print(f"error: {reg_path}: missing (run pst regress)", file=sys.stderr)
        return 2
    current = baseline.collect(synth, regress_runs(json.loads(reg_path.read_text())))
    if args.update:
        path.write_text(json.dumps({"tolerance": baseline.TOLERANCE, "tools": tools, "profiles": current},
                                   indent=2, sort_keys=True) + "\n")
        print(f"baseline: wrote {path}")
        return 0
    failed = [(n, e) for n in names for e in report.signoff_errors(synth[n])]
    for n, e in failed:
        print(f"baseline: {n}: sign-off check failed: {e}")
    other = baseline.tool_mismatches(base.get("tools"), synth)
    if other:
        for n, t in other:
            print(f"baseline: {n}: synthesized with {t}, the baseline with {base.get('tools')}: its figures are not "
                  f"comparable (check them, then rewrite {path} with --update)")
        return 1
    moved = baseline.compare(base["profiles"], current, base.get("tolerance", baseline.TOLERANCE))
    if not moved:
        n = len(baseline._flatten(current))
        print(f"baseline: {n} figures within {100 * base.get('tolerance', baseline.TOLERANCE):g} % of {path.name}")
        return 1 if failed else 0
    print(f"baseline: {len(moved)} figures moved beyond {100 * base.get('tolerance', baseline.TOLERANCE):g} % "
          f"(update {path} with --update if the change is intended):")
    for key, old, new, rel in moved:
        change = f"{100 * rel:+.1f} %" if rel is not None else "added/removed/changed"
        print(f"  {key}: {old} -> {new} ({change})")
    return 1


def add_profile(base: dict, path: pathlib.Path, out: pathlib.Path, name: str) -> int:
    """--add NAME: NAME's figures from OUT/synth/NAME.json (and OUT/regress.json's PSNRs when
    present, else the baseline's own) into the baseline, which must have been made with the
    same tools."""
    f = out / "synth" / f"{name}.json"
    if not f.exists():
        print(f"error: {f}: missing (run scripts/synth.py {name})", file=sys.stderr)
        return 2
    synth = {name: json.loads(f.read_text())}
    if not synth[name].get("timing"):
        print(f"error: {f}: no timing (scripts/synth.py ran with --no-sta)", file=sys.stderr)
        return 2
    errors = report.signoff_errors(synth[name])
    other = baseline.tool_mismatches(base.get("tools"), synth)
    if errors or other:
        for e in errors:
            print(f"error: {name}: sign-off check failed: {e}", file=sys.stderr)
        for n, t in other:
            print(f"error: {n}: synthesized with {t}, the baseline with {base.get('tools')}", file=sys.stderr)
        return 1
    reg_path = out / "regress.json"
    regress = regress_runs(json.loads(reg_path.read_text())) if reg_path.exists() else []
    new = baseline.collect(synth, regress)
    # The PSNRs come from the regression, not the synthesis: kept when this run has none.
    for k in ("psnr_db", "regress_size"):
        if k not in new[name] and k in base["profiles"].get(name, {}):
            new[name][k] = base["profiles"][name][k]
    base["profiles"].update(new)
    path.write_text(json.dumps(base, indent=2, sort_keys=True) + "\n")
    print(f"baseline: {name} added to {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
