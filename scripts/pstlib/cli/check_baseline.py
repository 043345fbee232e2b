"""Checks the main job's silicon and quality figures against scripts/synth/baseline.json.

    scripts/check_baseline.py [--out out] [--baseline FILE] [--update]

Reads OUT/synth/<profile>.json (scripts/synth.py) and OUT/regress.json (`pst regress`) for
every profile in the baseline and fails (exit 1) when a figure moved by more than 2 %: logic
GE (total and per block), flip-flops, memory GE, total GE, ROM/RAM bits, clocks per pixel,
Fmax, PSNR per scene, energy per pixel (scripts/power.py's mean over its workloads: OUT/power/
PROFILE.json when this run measured it, else the record docs/data/power.json). A change that moves a figure on purpose updates the file in the same
commit: `scripts/check_baseline.py --update` after the main job (scripts/run.sh);
`--add PROFILE` adds (or replaces) one profile's figures from OUT/synth/PROFILE.json (and its
PSNRs when OUT/regress.json has them), the other profiles' left as they are. Exit 2 when an
input is missing. Also exit 1 when a profile's synthesis fails the sign-off checks (hold, max
transition, max capacitance: scripts/synth.py's), or was made with another Yosys or OpenSTA
than the baseline's (tools in the file): its figures are not comparable, so the check stops
there and says so (re-baseline with --update after checking the new tools' figures).

The baseline also holds digests of every input of the synthesis (pstlib/synth/record.py), and
--update/--add copy OUT/synth/PROFILE.{json,md} into the record scripts/synth/records/:
  --stale     exit 1 naming each input changed since the baseline was written (ctest
              baseline_stale: an RTL, profile or flow change without a new baseline fails the
              default test suite), 0 while the baseline stands
  --restore   the main job without --synth: OUT/synth/PROFILE.{json,md} from the record, after
              the --stale check (exit 1 when it fails: synthesize instead); also writes
              OUT/synth/source.json ({"source": "record", "digest": ...}; {"source": "none", "stale":
              [...]} when the record does not stand), which the report quotes (absent: the figures were
              synthesized in this run)

  --json FILE  the check's result as JSON, written (atomically) on every exit path, the report's
               top line (scripts/report.py): {"schema": 1, "status": "pass"|"fail"|"error",
               "mode", "moved": [{"figure", "baseline", "current", "change"}], "signoff_failures":
               [{"profile", "error"}], "tool_mismatches", "stale": [inputs changed since the
               baseline], "figures_checked": N, "tolerance", "baseline", "messages", "provenance"}
"""
import argparse
import json
import pathlib
import sys
import traceback

from .. import atomic
from ..validation import baseline
from ..report import provenance
from ..paths import ROOT
from ..pstjson import regress_runs
from ..docs import power_doc
from ..synth import record, report

PROFILES = ("reduced", "full", "full_2clk", "full_1clk")
SCHEMA = 1           # of the --json result
STATUS = {0: "pass", 1: "fail"}   # exit status -> status (else "error")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default=str(ROOT / "out"))
    ap.add_argument("--baseline", default=str(ROOT / "scripts" / "synth" / "baseline.json"))
    ap.add_argument("--update", action="store_true", help="write the current figures as the baseline")
    ap.add_argument("--add", metavar="PROFILE", help="add or replace one profile's figures, the others kept")
    ap.add_argument("--stale", action="store_true", help="exit 1 when an input changed since the baseline")
    ap.add_argument("--restore", action="store_true", help="OUT/synth from the record while the baseline stands")
    ap.add_argument("--rom-dir", default=str(ROOT / "build" / "rom"), help="the ROM images (default build/rom)")
    ap.add_argument("--records", default=str(record.RECORDS), help="the silicon record (default scripts/synth/records)")
    ap.add_argument("--json", metavar="FILE", help="also write the result as JSON (on every exit path)")
    args = ap.parse_args()
    res = {"schema": SCHEMA, "status": "error", "mode": ("update" if args.update else "add" if args.add else
                                                       "restore" if args.restore else "stale" if args.stale
                                                       else "check"),
           "baseline": args.baseline, "moved": [], "signoff_failures": [], "tool_mismatches": [], "stale": [],
           "figures_checked": 0, "tolerance": None, "messages": [],
           "provenance": provenance.collect(SCHEMA)}
    rc = 2
    try:
        rc = check(args, res)
    except Exception as e:        # the JSON still says what happened; the traceback on stderr
        traceback.print_exc()
        res["messages"].append(f"error: {type(e).__name__}: {e}")
        rc = 2
    finally:
        res["status"] = STATUS.get(rc, "error")
        res["exit_status"] = rc
        if args.json:
            atomic.write_text(pathlib.Path(args.json), json.dumps(res, indent=2, sort_keys=True, default=str) + "\n")
    return rc


def signed(old, new, rel):
    """REL (a relative change's size, or None) with the sign of NEW - OLD."""
    if rel is None or not isinstance(old, (int, float)) or not isinstance(new, (int, float)):
        return rel
    return -rel if new < old else rel


def say(res: dict, text: str, err: bool = False) -> None:
    """Prints TEXT (stderr when ERR) and keeps it in the JSON result's messages."""
    print(text, file=sys.stderr if err else sys.stdout)
    res["messages"].append(text)


def check(args, res: dict) -> int:
    out = pathlib.Path(args.out)
    path = pathlib.Path(args.baseline)
    rom_dir = pathlib.Path(args.rom_dir)
    records = pathlib.Path(args.records)
    if (args.update or args.add) and not list(rom_dir.glob("*.memh")):
        say(res, f"error: {rom_dir}: no ROM images (build first)", err=True)
        return 2
    base = json.loads(path.read_text()) if path.exists() else None
    if base is None and not args.update:
        say(res, f"error: {path}: no baseline (write one with --update)", err=True)
        return 2
    if args.stale or args.restore:
        return check_stale(base, path, out, rom_dir if rom_dir.is_dir() else None, args.restore, res, records)
    if args.add:
        return add_profile(base, path, out, args.add, rom_dir, res, records)
    names = PROFILES if args.update or base is None else tuple(base["profiles"])
    synth, tools = {}, {}
    for n in names:
        f = out / "synth" / f"{n}.json"
        if not f.exists():
            say(res, f"error: {f}: missing (run scripts/synth.py {n})", err=True)
            return 2
        synth[n] = json.loads(f.read_text())
        tools = synth[n].get("tools", tools)
        if not synth[n].get("timing"):
            say(res, f"error: {f}: no timing (scripts/synth.py ran with --no-sta)", err=True)
            return 2
    reg_path = out / "regress.json"
    if not reg_path.exists():
        say(res, f"error: {reg_path}: missing (run pst regress)", err=True)
        return 2
    current = baseline.collect(synth, regress_runs(json.loads(reg_path.read_text())), power_summaries(out, names, res))
    if args.update:
        path.write_text(json.dumps({"tolerance": baseline.TOLERANCE, "tools": tools, "profiles": current,
                                    "inputs": record.inputs(rom_dir)}, indent=2, sort_keys=True) + "\n")
        record.save(out / "synth", names, records)
        say(res, f"baseline: wrote {path} and the record {records}")
        return 0
    tol = base.get("tolerance", baseline.TOLERANCE)
    res["tolerance"] = tol
    # Informational here (--stale fails on it): inputs changed since the baseline was written.
    res["stale"] = record.stale(base, rom_dir if rom_dir.is_dir() else None)
    failed = [(n, e) for n in names for e in report.signoff_errors(synth[n])]
    res["signoff_failures"] = [{"profile": n, "error": e} for n, e in failed]
    for n, e in failed:
        say(res, f"baseline: {n}: sign-off check failed: {e}")
    other = baseline.tool_mismatches(base.get("tools"), synth)
    res["tool_mismatches"] = [{"profile": n, "tools": t, "baseline_tools": base.get("tools")} for n, t in other]
    if other:
        for n, t in other:
            say(res, f"baseline: {n}: synthesized with {t}, the baseline with {base.get('tools')}: its figures are not "
                     f"comparable (check them, then rewrite {path} with --update)")
        return 1
    moved = baseline.compare(base["profiles"], current, tol)
    res["figures_checked"] = len(baseline._flatten(current))
    # The change signed (compare's is its size): a fall in Fmax reads as one.
    moved = [(k, old, new, signed(old, new, rel)) for k, old, new, rel in moved]
    res["moved"] = [{"figure": k, "baseline": old, "current": new, "change": rel} for k, old, new, rel in moved]
    if not moved:
        n = len(baseline._flatten(current))
        say(res, f"baseline: {n} figures within {100 * base.get('tolerance', baseline.TOLERANCE):g} % of {path.name}")
        return 1 if failed else 0
    say(res, f"baseline: {len(moved)} figures moved beyond {100 * base.get('tolerance', baseline.TOLERANCE):g} % "
             f"(update {path} with --update if the change is intended):")
    for key, old, new, rel in moved:
        change = f"{100 * rel:+.1f} %" if rel is not None else "added/removed/changed"
        say(res, f"  {key}: {old} -> {new} ({change})")
    return 1


def power_summaries(out: pathlib.Path, names, res: dict) -> dict:
    """Energy per pixel of each profile: OUT/power/NAME.json (scripts/power.py, measured in this
    run) when present, else the record docs/data/power.json (scripts/power.py --record). A
    profile in neither has no energy figure (compare() then reports it as removed)."""
    out_power, rec = {}, {}
    try:
        rec = power_doc.load(ROOT)["profiles"]
    except ValueError as e:
        say(res, f"baseline: no energy record ({e})")
    def rams(s: dict) -> bool:      # the RAMs' read ports modelled (scripts/power.py --ram-reads)
        return "rams_modelled" in s

    for n in names:
        f = out / "power" / f"{n}.json"
        if f.exists():
            s = json.loads(f.read_text()).get("summary")
            if s and n in rec and rams(s) != rams(rec[n]["summary"]):
                # Another model than the record's: not the same figure (reduced: 140,190 pJ with
                # the RAMs' reads, 77,782 without); the record is compared.
                say(res, f"baseline: {f} was measured {'with' if rams(s) else 'without'} the RAMs' read ports "
                         f"(--ram-reads), the record {'with' if rams(rec[n]['summary']) else 'without'}: "
                         "the record's energy is used")
            elif s:
                out_power[n] = s
                continue
        if n in rec:
            out_power[n] = rec[n]["summary"]
    return out_power


def check_stale(base: dict, path: pathlib.Path, out: pathlib.Path, rom_dir, restore: bool, res: dict,
                records: pathlib.Path) -> int:
    """--stale and --restore: does the baseline (and its record) stand for the tree?"""
    why = record.stale(base, rom_dir)
    gone = record.missing(base["profiles"], records)
    if gone:
        why.append(f"no record of {', '.join(gone)} in {records}")
    res["stale"] = why
    source = out / "synth" / "source.json"
    if why:
        if restore:       # the report must not quote a previous run's restore
            atomic.write_text(source, json.dumps({"schema": SCHEMA, "source": "none", "stale": why}, indent=2) + "\n")
        say(res, f"baseline: {path.name} does not stand for this tree: " + "; ".join(why[:8]) +
                 (f" (and {len(why) - 8} more)" if len(why) > 8 else ""))
        say(res, "  synthesize the baseline's profiles again (scripts/run.sh --synth, or scripts/synth.py PROFILE), "
                 "then scripts/check_baseline.py --update")
        return 1
    if restore:
        record.restore(out / "synth", base["profiles"], records)
        res["digest"] = record.digest.summary(base["inputs"], {})
        atomic.write_text(source, json.dumps({"schema": SCHEMA, "source": "record", "digest": res["digest"],
                                              "baseline": str(path), "profiles": sorted(base["profiles"]),
                                              "inputs": len(base["inputs"])}, indent=2) + "\n")
        say(res, f"baseline: inputs unchanged since {path.name} (digest {record.digest.summary(base['inputs'], {})}): "
                 f"silicon figures of {', '.join(base['profiles'])} from {records}")
    else:
        say(res, f"baseline: {path.name} stands for this tree ({len(base['inputs'])} inputs unchanged)")
    return 0


def add_profile(base: dict, path: pathlib.Path, out: pathlib.Path, name: str, rom_dir: pathlib.Path, res: dict,
                records: pathlib.Path) -> int:
    """--add NAME: NAME's figures from OUT/synth/NAME.json (and OUT/regress.json's PSNRs when
    present, else the baseline's own) into the baseline, which must have been made with the
    same tools."""
    f = out / "synth" / f"{name}.json"
    if not f.exists():
        say(res, f"error: {f}: missing (run scripts/synth.py {name})", err=True)
        return 2
    synth = {name: json.loads(f.read_text())}
    if not synth[name].get("timing"):
        say(res, f"error: {f}: no timing (scripts/synth.py ran with --no-sta)", err=True)
        return 2
    errors = report.signoff_errors(synth[name])
    other = baseline.tool_mismatches(base.get("tools"), synth)
    if errors or other:
        for e in errors:
            say(res, f"error: {name}: sign-off check failed: {e}", err=True)
        for n, t in other:
            say(res, f"error: {n}: synthesized with {t}, the baseline with {base.get('tools')}", err=True)
        return 1
    reg_path = out / "regress.json"
    regress = regress_runs(json.loads(reg_path.read_text())) if reg_path.exists() else []
    new = baseline.collect(synth, regress, power_summaries(out, [name], res))
    # The PSNRs come from the regression, not the synthesis: kept when this run has none.
    for k in ("psnr_db", "regress_size", "energy_pj_per_pixel"):
        if k not in new[name] and k in base["profiles"].get(name, {}):
            new[name][k] = base["profiles"][name][k]
    # The digest stands for every profile of the baseline: a profile is added only while the
    # inputs are those the others were synthesized from (else every profile again, --update).
    why = record.stale(base, rom_dir)
    if why:
        say(res, f"error: the inputs changed since {path.name} ({'; '.join(why[:5])}): synthesize every profile "
                 f"and rewrite it with --update", err=True)
        return 1
    base["profiles"].update(new)
    md = out / "synth" / f"{name}.md"
    if not md.exists():
        say(res, f"error: {md}: missing (run scripts/synth.py {name})", err=True)
        return 2
    path.write_text(json.dumps(base, indent=2, sort_keys=True) + "\n")
    record.save(out / "synth", [name], records)
    say(res, f"baseline: {name} added to {path} and the record")
    return 0


if __name__ == "__main__":
    sys.exit(main())
