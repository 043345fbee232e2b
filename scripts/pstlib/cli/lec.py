"""Logic equivalence of a profile's RTL and its synthesized netlist, module by module (Yosys
miters, ABC's iprove and dprove).

    scripts/lec.py PROFILE [--work DIR] [--out DIR] [--module NAME ...] [--max-cells N]
                   [--timeout S] [--mutate MODULE]

Writes DIR/PROFILE.json and DIR/PROFILE.md (default DIR: out/lec): per module, its cells, whether
it holds flip-flops, the verdict (proven, differs, undecided, timeout) and seconds. The netlist is
the profile's synthesis (scripts/synth.py --keep, the one the silicon figures count), made in
DIR/synth/ unless --work names a kept synthesis folder. Modules holding a memory (the netlist has
its timing stand-ins, not its contents) and the top are listed as left to simulation.
--module: only modules whose name (or base name, pst_x) is given. --mutate MODULE: the netlist
with the first two-input cell of MODULE (a base name: its smallest parameter set) swapped for its
dual (NAND2 <-> NOR2, AND2 <-> OR2, XOR2 <-> XNOR2), only that module checked: the mutant must
come out "differs".

Exit 0 when every module checked is proven (with --mutate: when the mutant differs), 1
otherwise, 2 on bad input. Method: scripts/pstlib/lec/miter.py.
"""
import argparse
import json
import pathlib
import shutil
import sys
import time

from .. import atomic, contract, kept
from ..lec import miter, prove
from ..paths import ROOT, profile_path
from ..synth import liberty
from ..synth.tools import base_name, read_lines, run_yosys


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("profile")
    ap.add_argument("--work", help="a kept synthesis folder (scripts/synth.py --keep: OUT/NAME.work)")
    ap.add_argument("--out", default=str(ROOT / "out" / "lec"))
    ap.add_argument("--module", nargs="*", default=[], help="only these modules (full or base names)")
    ap.add_argument("--timeout", type=float, default=120.0, help="seconds ABC may take per module (default 120)")
    ap.add_argument("--max-cells", type=int, default=0, help="only modules of at most this many cells (0: any)")
    ap.add_argument("--mutate", metavar="MODULE", help="swap one cell of MODULE and check only it")
    ap.add_argument("--rom-dir", default=str(ROOT / "build" / "rom"))
    a = ap.parse_args(argv)
    if not 1 <= a.timeout <= 86400:
        ap.error("--timeout: must be in [1, 86400]")
    if not 0 <= a.max_cells <= 1 << 30:
        ap.error("--max-cells: must be in [0, 2^30]")
    for tool in ("yosys", prove.ABC):
        if not shutil.which(tool):
            print(f"error: {tool} not found (scripts/setup.sh installs yosys)", file=sys.stderr)
            return 2
    name = profile_path(a.profile).stem
    out = pathlib.Path(a.out)
    try:
        if not profile_path(a.profile).exists():
            raise kept.InputError(f"{a.profile}: no such profile ({profile_path(a.profile)})")
        if a.work and not (pathlib.Path(a.work) / "netlist_sta.v").exists():
            raise kept.InputError(f"--work: {a.work}: not a kept synthesis (no netlist_sta.v)")
        work, _ = kept.synthesis(a.profile, out, a.work)
    except kept.InputError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    netlist = (work / "netlist_sta.v").read_text()
    mods = miter.modules(netlist)
    wanted = set(a.module) | ({a.mutate} if a.mutate else set())
    pick = [m for m in miter.comparable(mods) if (not wanted or m in wanted or base_name(m) in wanted)
            and (not a.max_cells or mods[m]["cells"] <= a.max_cells)]
    if wanted and not pick:
        print(f"error: no comparable module named {' '.join(sorted(wanted))} in {name}'s netlist", file=sys.stderr)
        return 2
    tmp = out / f"{name}.lec"
    tmp.mkdir(parents=True, exist_ok=True)
    netlist_path = work / "netlist_sta.v"
    mutation = None
    if a.mutate:
        pick = pick[:1]             # a base name matches every parameter set: the smallest
        try:
            text, mutation = miter.mutate(netlist, pick[0])
        except ValueError as e:
            print(f"error: --mutate: {e}", file=sys.stderr)
            return 2
        netlist_path = tmp / "mutant.v"
        netlist_path.write_text(text)
    doc = contract.read_profile(profile_path(a.profile))
    lib = liberty.osu018_lib()
    jobs = [(m, tmp / f"m{i}.aig") for i, m in enumerate(pick)]
    t0 = time.time()
    run_yosys(miter.script(read_lines(doc, a.rom_dir, lib), str(lib), str(work / "standin.lib"), str(netlist_path),
                           [(m, str(p)) for m, p in jobs]), tmp, "miters")
    rows = []
    for m, aig in jobs:
        verdict, secs, last = prove.prove(aig, mods[m]["seq"], a.timeout)
        rows.append({"module": m, "base": base_name(m), "cells": mods[m]["cells"],
                     "cells_below": miter.subtree_cells(mods, m) - mods[m]["cells"],
                     "sequential": mods[m]["seq"], "result": verdict, "seconds": round(secs, 2), "abc": last})
        print(f"{base_name(m):24s} {rows[-1]['cells']:7d} cells {'seq ' if mods[m]['seq'] else 'comb'} "
              f"{verdict:9s} {secs:6.1f} s", flush=True)
    skipped = sorted(m for m in mods if m not in pick and (not wanted or m in wanted or base_name(m) in wanted))
    res = {"profile": name, "netlist": str(netlist_path), "mutation": mutation, "modules": rows,
           "left_to_simulation": [{"module": m, "why": "the top" if m == "pst_top" else "holds a memory"}
                                  for m in skipped if m == "pst_top" or mods[m]["mem"]],
           "seconds": round(time.time() - t0, 1)}
    counts = {k: sum(r["result"] == k for r in rows) for k in ("proven", "differs", "undecided", "timeout")}
    verdicts = {r["module"]: r["result"] for r in rows}
    for r in rows:
        r["standing"] = miter.standing(mods, verdicts, r["module"])
    res["counts"] = counts
    res["standing"] = sum(r["standing"] for r in rows)
    atomic.write_text(out / f"{name}.json", json.dumps(res, indent=2) + "\n")
    md = [f"# Equivalence of {name}'s RTL and netlist" + (f" (mutant: {mutation})" if mutation else ""), "",
          "| module | own cells | cells below | kind | own logic | with all below | seconds |",
          "|---|---:|---:|---|---|---|---:|"]
    md += [f"| {r['module']} | {r['cells']} | {r['cells_below']} | {'sequential' if r['sequential'] else 'combinational'} | "
           f"{r['result']} | {'proven' if r['standing'] else '-'} | {r['seconds']} |" for r in rows]
    md += ["", f"Left to simulation: {len(res['left_to_simulation'])} modules (the top and those holding a memory).",
           "", " ".join(f"{k}: {v}" for k, v in counts.items())]
    atomic.write_text(out / f"{name}.md", "\n".join(md) + "\n")
    print(f"lec {name}: " + ", ".join(f"{v} {k}" for k, v in counts.items())
          + f"; {res['standing']} of {len(rows)} proven with every module below them"
          + (f"; mutant {mutation}" if mutation else ""))
    if mutation:
        return 0 if counts["differs"] == 1 else 1
    return 0 if counts["proven"] == len(rows) else 1


if __name__ == "__main__":
    sys.exit(main())
