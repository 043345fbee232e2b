#!/usr/bin/python3
"""Silicon figures of one hardware profile: Yosys 0.23 synthesis of pst_top to the OSU 0.18 um
standard cells (Debian's qflow-tech-osu018), OpenSTA timing, memory area, throughput.

    scripts/synth.py PROFILE [--out DIR] [--rom-dir DIR] [--no-sta] [--no-old-basis] [--jobs N]

PROFILE is a name (rtl/configs/NAME.toml) or a profile file. Writes DIR/NAME.json and
DIR/NAME.md (default DIR: out/synth) and prints the Markdown. Exit 2 on bad input (no such
profile, no ROM images, no OSU018 library: run scripts/setup.sh), 1 when a tool fails or the
design fails a sign-off check (a hold violation, a max-transition or max-capacitance violation:
the message names the worst offender; the JSON and Markdown are written all the same).

Method (the Markdown repeats it beside the figures):
- Code: scripts/pstlib/synth/ (flow.py the steps below, blocks.py the report's blocks,
  report.py the record and its Markdown).
- Blocks: read off the elaborated hierarchy (scripts/pstlib/synth/blocks.py): the top's
  children and theirs (stages and their units: quadric, noise, worley, octave fade, ...) are
  the rows; building blocks used by several modules count in the block holding them.
- Hierarchical synthesis: every module is synthesized once per parameter set and counted once
  per instance, so the eight identical noise units of `full` cost one synthesis.
- Mapping: one netlist for area and timing. ABC maps each module's logic for area (`map -a`),
  then buffers fanout (`buffer -p`: an unbuffered netlist cannot be timed, one gate would
  drive picofarads) and sizes gates against the 10 ns target (`upsize`, `dnsize`; ABC sees
  module ports as driven by BUFX2 and loaded by 0.02 pF). The area includes those buffers.
- Fanout buffers across the hierarchy (scripts/pstlib/synth/fanout.py): ABC buffers the nets inside
  one module only, so a net leaving a module into many sub-module instances (the octave
  stage's stall enable into 32 sub-modules and on to their registers) would be one gate
  driving picofarads. Standing in for a back end's high-fanout repair (repair_design), every
  net of a module into the input ports of >= fanout.MIN_INSTANCES sub-module instances gets
  one fanout.CELL (BUFX4) in front of each such instance, in the netlist that is timed and
  counted (area in the module holding it; the report has a row with their number).
  Flip-flops: asynchronous resets become logic (`async2sync`), every flop a DFFPOSX1.
- GE = cell area / NAND2X1 area (24 um^2). The old basis (scripts/synth/cells.lib, a
  21-cell generic library written by hand, ABC's fast delay mapping) is kept as a second
  column for one release; its GE are not comparable with a real library's.
- Memories stay memories (`memory -nomap`), outside the logic. Each distinct ROM is
  synthesized alone to OSU018 cells with one read port (cached by content in
  out/synth/memories/, --mem-cache)
  and counted once per read port (replication); OpenSTA gives its address-to-data delay
  (inputs driven by BUFX2, outputs loaded with 0.02 pF). RAMs: a per-bit SRAM-macro model per
  read port (scripts/pstlib/synth/memarea.py says where its numbers come from).
- Timing: in the design's netlist every memory read bit is a stand-in cell with that delay
  (scripts/synth/mem_standin_map.v), every memory write bit a capture cell with a setup
  check; OpenSTA 2.0.17 links the hierarchical netlist flat and reads scripts/synth/pst.sdc
  (10 ns clock, ideal clock network with clock uncertainty 0.4 ns setup / 0.1 ns hold and a
  0.35 ns clock transition for qflow's buffered clock fanout, BUFX2-driven inputs with a
  0.2 ns input transition, max transition 1.2 ns; where each number comes from is in the file).
  Every register is in the path group of its top-level block: the worst path per block is
  the critical path of that stage. Fmax = 1 / (period - worst setup slack), a pre-layout
  figure (typical corner, no wire load; JSON fmax_basis "pre-layout").
- Sign-off checks (scripts/pstlib/synth/sta.py): hold per stage and every violated hold
  endpoint, every max-transition violation (report_check_types), and every net's load against
  the liberty's max_capacitance of the pin driving it (OpenSTA 2.0.17 has no such check: a
  Tcl loop over the leaf drivers and the data input ports). Any violation fails the run.
- Logic depth: `ltp -noff` per module on the mapped netlist (cells on the longest
  combinational path; a sub-module instance counts as one cell).
- Yosys runs with -e "implicitly declared|has no driver" so a silent mis-build fails.
"""
import argparse
import pathlib
import sys

from pstlib.paths import ROOT, profile_path
from pstlib.synth import flow, report


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("profile")
    ap.add_argument("--out", default=str(ROOT / "out" / "synth"))
    ap.add_argument("--rom-dir", default=str(ROOT / "build" / "rom"))
    ap.add_argument("--regress", default=str(ROOT / "out" / "regress.json"),
                    help="pst regress output for the measured clocks per pixel")
    ap.add_argument("--yosys", default="yosys")
    ap.add_argument("--sta", default="sta")
    ap.add_argument("--no-sta", action="store_true", help="area only (no OpenSTA run)")
    ap.add_argument("--no-old-basis", action="store_true",
                    help="skip the cells.lib column (only the named profiles rtl/configs/*.toml get it)")
    ap.add_argument("--jobs", type=int, default=1, help="memory syntheses in parallel")
    ap.add_argument("--mem-cache", default=str(ROOT / "out" / "synth" / "memories"),
                    help="cache of the stand-alone memory syntheses (by content)")
    ap.add_argument("--keep", action="store_true", help="keep the netlists and tool logs in DIR/NAME.work/")
    ap.add_argument("--reuse", action="store_true",
                    help="with --keep: skip Yosys when DIR/NAME.work holds a netlist made from the current inputs "
                         "(the RTL, profile, flow, library and ROM digests in NAME.work/inputs.json); "
                         "synthesize again otherwise, naming what changed")
    ap.add_argument("--quiet", action="store_true")
    args = ap.parse_args(argv)
    opts = flow.Options(out=pathlib.Path(args.out), rom_dir=pathlib.Path(args.rom_dir),
                        regress=pathlib.Path(args.regress), yosys=args.yosys, sta=args.sta, no_sta=args.no_sta,
                        old_basis=not args.no_old_basis, jobs=args.jobs, mem_cache=pathlib.Path(args.mem_cache),
                        keep=args.keep, reuse=args.reuse)
    profile = profile_path(args.profile)
    result, rc = flow.run_command(lambda: flow.synthesize(profile, opts), profile)
    if rc:
        return rc
    if not args.quiet:
        print(report.markdown(result))
    errors = report.signoff_errors(result)
    if errors:
        print(f"error: {profile}: sign-off checks failed (scripts/synth/pst.sdc; "
              f"{pathlib.Path(args.out) / (result['profile'] + '.sta_signoff.txt')}):", file=sys.stderr)
        for e in errors:
            print(f"  {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
