"""Is the synthesis' hand-written fanout step (pstlib/synth/fanout.py: a BUFX4 per sub-module
instance on nets into several instances, fed by a tree of BUFX4) as good as buffering from
the library?

The profile's timed netlist without those buffers is flattened and buffered by qflow's
blifFanout (buffer trees from the liberty's pin capacitances: at most 16 loads and 30 fF per
driver by default, gates resized), then timed by OpenSTA against the same SDC as the
synthesis. The record keeps both Fmax and their ratio.
"""
import re

from .. import procs
from ..synth import sta as synth_sta
from ..synth.fanout import CELL, PREFIX
from ..synth.tools import SDC, run_sta, run_yosys

BLIF_FANOUT = "/usr/lib/qflow/bin/blifFanout"
BLIF2VERILOG = "/usr/lib/qflow/bin/blif2Verilog"


def strip_fanout_buffers(netlist: str) -> tuple:
    """The netlist without fanout.py's buffers (each `_fobN_` wire replaced by its source), and
    how many were removed."""
    out, n = [], 0
    cell = re.compile(rf"^\s*{CELL} {PREFIX}c\d+_ \(\.A\((.*?)\), \.Y\(({PREFIX}\d+_)\)\);\n", re.M)
    for mod in re.split(r"(?m)^(?=module )", netlist):
        src = {w: s for s, w in cell.findall(mod)}
        n += len(src)

        def root(w):
            # The buffers form a tree: a buffer's input may be another buffer's output.
            while w in src:
                w = src[w]
            return w
        mod = cell.sub("", mod)
        mod = re.sub(rf"(?m)^\s*wire {PREFIX}\d+_;\n", "", mod)
        if src:
            mod = re.sub(rf"{PREFIX}\d+_(?!\w)", lambda m: root(m.group(0)), mod)
        out.append(mod)
    return "".join(out), n


def compare(work, netlist_sta, libs: list, top: str, synth_fmax: float) -> dict:
    """blifFanout on the flattened profile, timed; the comparison record."""
    work.mkdir(parents=True, exist_ok=True)
    text, removed = strip_fanout_buffers(netlist_sta.read_text())
    (work / "nofob.v").write_text(text)
    run_yosys("\n".join([*(f"read_liberty -lib {lib}" for lib in libs), f"read_verilog {work / 'nofob.v'}",
                         f"hierarchy -top {top}", "flatten", "opt_clean -purge", "rename -enumerate",
                         f"write_blif -buf BUFX2 A Y {work / 'flat.blif'}", ""]), work, "flatten")
    # blifFanout reads `.gate` lines; '/' (source paths in some flattened names) is no Verilog.
    blif = re.sub(r"(?m)^\.subckt ", ".gate ", (work / "flat.blif").read_text()).replace("/", "_")
    (work / "cur.blif").write_text(blif)
    lib_args = [a for lib in libs for a in ("-p", str(lib))]
    added = 0
    for _ in range(20):     # iterated to convergence, as qflow's synthesize.sh does
        rc, out, err = procs.run([BLIF_FANOUT, "-s", "nullstring", *lib_args, "-b", "BUFX2,CLKBUF1",
                                  "-i", "A,A", "-o", "Y,Y", work / "cur.blif", work / "next.blif"], cwd=work)
        out = out + err          # blifFanout reports on stderr; its exit status is the change count
        m = re.search(r"(\d+) buffers were added", out)
        if rc < 0 or not m or not (work / "next.blif").exists():
            raise RuntimeError(f"blifFanout failed:\n{out[-3000:]}")
        added += int(m.group(1))
        (work / "next.blif").replace(work / "cur.blif")
        if re.search(r"Number of gates changed: 0\b", out):
            break
    rc, verilog, err = procs.run([BLIF2VERILOG, "-c", "-p", "-v", "vdd", "-g", "gnd", work / "cur.blif"], cwd=work)
    if rc != 0:
        raise RuntimeError(f"blif2Verilog failed: {err[-2000:]}")
    (work / "buffered.v").write_text(verilog)
    rep = work / "checks.txt"
    run_sta("\n".join([*(f"read_liberty {lib}" for lib in libs), f"read_verilog {work / 'buffered.v'}",
                       f"link_design {top}", f"read_sdc {SDC}",
                       f"report_checks -path_delay max -digits 3 > {rep}", "exit", ""]), work, "sta")
    paths = [p for p in synth_sta.parse_checks(rep.read_text()) if p["slack"] is not None]
    fmax = synth_sta.fmax_mhz(synth_sta.sdc_period(SDC.read_text()), paths[0]["slack"])
    return {"hand_buffers_removed": removed, "blif_fanout_buffers": added,
            "fmax_mhz_hand_fanout": synth_fmax, "fmax_mhz_blif_fanout": round(fmax, 1),
            "ratio": round(synth_fmax / fmax, 3),
            "within_2_percent": abs(synth_fmax / fmax - 1) <= 0.02}
