"""Place and route of one hardware profile, block by block, with Debian's qflow (OSU 0.18 µm).

    scripts/pnr.py PROFILE [--out DIR] [--jobs N] [--limit CELLS] [--group NAME=PATH[+PATH...] ...]
                           [--block NAME ...] [--blocks-only] [--resume] [--update-derate]

Writes DIR/PROFILE.json and DIR/PROFILE.md (default DIR: out/pnr) and, per block,
DIR/PROFILE/BLOCK.{def,gds,spef,png}; the qflow projects stay in DIR/PROFILE/work/. Exit 2
on bad input (no such profile, no ROM images, qflow not installed: scripts/setup.sh --pnr),
1 when a tool fails.

Method:
- Synthesis: the profile's own (scripts/synth.py, the same netlist the silicon figures count).
- Blocks (scripts/pstlib/pnr/partition.py): the flattened netlist is cut by instance path into
  blocks of at most --limit cells (25k: graywolf places 20k cells in about 10 minutes here and
  the whole reduced profile, 64k cells, does not place in an hour); the top's glue, pipeline
  registers and small units are the block `top`. Memories are macros outside every block:
  their pins are block pins, their area and timing the synthesis record's memory model.
- Each block (pstlib/pnr/qflow.py): qflow's blifFanout buffers it from the liberty's limits
  (buffer and clock trees), graywolf places it at 0.7 initial density, qrouter routes it
  (stages 1-2 on 6 metal layers), magic checks DRC (against the LEF cell views) and writes the
  GDS (cell references: Debian's OSU018 has LEF abstracts, no cell GDS), netgen compares the
  extracted layout with the netlist (LVS). KLayout draws the PNG.
- Timing (pstlib/pnr/spef.py, timing.py): qrouter's routed RC trees rewritten as SPEF (wire
  capacitance with both fringe edges, pin capacitance from the liberty), OpenSTA with the
  project's SDC (scripts/synth/pst.sdc) before layout and after routing on the same netlist;
  block pins get the SDC's 2 ns input and output budgets. Typical corner only (the one the
  library has); no coupling capacitance; the clock is qflow's buffered clock net (no CTS).
- A block qrouter cannot finish is placed again 0.1 less dense (down to 0.4), with its pins
  placed from the cells on their nets (pstlib/pnr/pins.py: graywolf alone places pins with no
  regard to their cells). A first placement whose pins graywolf put far from their cells
  (median over 5 % of the die's half perimeter, or ringed outside them) is placed again at once so.
- A block that does not finish (qrouter leaves nets unrouted at the least density, a tool
  fails) is reported with its error and left out of the figures; the others are kept.
- The profile: area = the blocks' dies + the memories; post-route Fmax = the slowest block's;
  the derate for the whole design (and for profiles too large to route here) = the worst
  block's post-route / pre-layout Fmax ratio.
"""
import argparse
import pathlib
import sys

from .. import procs
from ..paths import ROOT, profile_path
from ..pnr import flow, partition, qflow, report
from ..synth import flow as synth_flow, report as synth_report


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("profile")
    ap.add_argument("--out", default=str(ROOT / "out" / "pnr"))
    ap.add_argument("--rom-dir", default=str(ROOT / "build" / "rom"))
    ap.add_argument("--jobs", type=int, default=1, help="blocks placed and routed at once")
    ap.add_argument("--limit", type=int, default=partition.LIMIT, help="largest block, in cells")
    ap.add_argument("--block", action="append", default=[], help="run only this block (repeatable)")
    ap.add_argument("--update-derate", action="store_true",
                    help="write the worst block's post-route / pre-layout Fmax ratio to "
                         "scripts/synth/layout_derate.json (every synthesis then reports its Fmax derated by it)")
    ap.add_argument("--resume", action="store_true",
                    help="keep the synthesis netlist and the qflow steps a previous run finished")
    ap.add_argument("--group", action="append", default=[], metavar="NAME=PATH[+PATH...]",
                    help="a block NAME made of these instance paths, before the cut (repeatable): a "
                         "critical path from one instance's registers into another's then lies inside one block")
    ap.add_argument("--blocks-only", action="store_true",
                    help="place, route and time the blocks only: no whole-chip assembly, no blifFanout check "
                         "of the whole profile (hours for full)")
    args = ap.parse_args(argv)
    try:
        groups = dict(partition.parse_group(g) for g in args.group)
    except ValueError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    if args.jobs < 1 or args.limit < 100:
        print("error: --jobs must be >= 1 and --limit >= 100", file=sys.stderr)
        return 2
    opts = flow.Options(out=pathlib.Path(args.out), rom_dir=pathlib.Path(args.rom_dir), jobs=args.jobs,
                        limit=args.limit, only=tuple(args.block), resume=args.resume,
                        groups=groups, whole=not args.blocks_only)
    profile = profile_path(args.profile)
    try:
        result, rc = synth_flow.run_command(lambda: flow.place_and_route(profile, opts), profile,
                                            (RuntimeError, qflow.FlowError))
    except KeyboardInterrupt:
        procs.stop_children()
        return 130
    if rc:
        return rc
    print(report.markdown(result))
    if args.update_derate:
        report.write_derate(result, synth_report.DERATE_FILE)
        print(f"derate {result['fmax_ratio_post_over_pre']} -> {synth_report.DERATE_FILE}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
