"""Power of one profile's synthesized netlist from simulated activity (OpenSTA report_power).

Steps (scripts/power.py runs them; docs/POWER.md tells the method and its limits):
1. The RTL of the profile (verilated) renders each workload scene with an FST trace of a window
   of cycles in the middle of the run (`pst render --trace`); gtkwave's fst2vcd makes it a VCD
   and activity.read_vcd counts every bit's transitions per clock and its duty.
2. OpenSTA `report_power -instances` of every leaf cell of the synthesized netlist (the one
   scripts/synth.py times and counts: OSU018 cells, fanout buffers, memory stand-ins) at the
   SDC's clock (10 ns), twice: with every pin at activity 0 and at activity 1 (transitions per
   clock). Debian's OpenSTA (the 2019 snapshot) uses only its global activity in report_power
   (a pin's own activity is not read, and `set_power_activity -pins` is broken), so each cell's
   power is taken as linear in its activity a: P = P(0) + a (P(1) - P(0)), the internal and
   switching tables of the liberty at the cell's real load and slew.
3. Each cell's activity: the measured rate of the net it drives when that net is a module port
   (annotate.py maps the trace's names onto the netlist's: the synthesis keeps every port name),
   else the mean rate of every traced bit of the module instance holding it (its registers,
   wires and ports). Summed per block (the module of the cell's first two levels of hierarchy).
   Dynamic power scales with the clock; leakage does not.
4. Memories: read ports are timing stand-ins without power data. A ROM's power is modelled as
   its read ports' cell area (the synthesis record's, built from the same OSU018 cells) times
   the dynamic power density (W per um^2) this run measures on the design's own combinational
   cells: a stated first-order model, not a memory compiler's figure. The RAMs (the colour
   table, its MIP and SAT copies) likewise by their read multiplexers' area with --ram-reads
   (memarea.ram_read_area_um2; their storage, written only while idle, is not counted);
   without it they are listed as not modelled.
5. The clock network: pre-layout, the clock is ideal; the flops' clock-pin internal power is in
   the sequential group; clock-tree buffers are not (no clock tree before layout).
"""
import dataclasses
import re

from ..synth.tools import SDC, base_name, run_sta
from . import annotate




@dataclasses.dataclass
class Power:
    """Watts at the SDC clock under one workload's activity."""
    groups: dict          # "Sequential", "Combinational", "Total" -> (internal, switching, leakage, total)
    blocks: dict          # block -> (internal, switching, leakage, total)
    comb_area_um2: float  # area of the combinational cells (the memory model's density)
    traced_bits: int      # traced bits of module instances of the netlist (ports, registers, wires)
    missing_bits: int     # of those, bits no leaf cell of their module drives (internal wires the
                          # synthesis purged, ports passed through or driven by a sub-module)
    port_driven_cells: int  # cells whose activity is their own net's measured rate
    cells: int            # leaf cells
    period_ns: float


def sdc_period_ns(sdc_text: str) -> float:
    m = re.search(r"create_clock\b[^\n]*-period\s+([0-9.]+)", sdc_text)
    if not m:
        raise ValueError("no create_clock -period in the SDC")
    return float(m.group(1))


def power_tcl(libs: list, netlist: str, top: str, sdc: str, drivers: str, reports: tuple, areas: dict) -> str:
    """The OpenSTA script: link, constraints, DRIVERS (Tcl, may be empty), `seq CELL`
    for every register, `comb_area A` (um^2 of the combinational cells), and the per-cell power
    at global activity 0 and 1 into REPORTS[0] and REPORTS[1]."""
    area_dict = " ".join(f"{c} {a:g}" for c, a in sorted(areas.items()))
    return "\n".join([*(f"read_liberty {l}" for l in libs), f"read_verilog {netlist}",
                      f"link_design {{{top}}}", f"read_sdc {sdc}", drivers, r"""
set pst_lib [dict create %s]
set pst_leaf {}
set pst_comb_area 0.0
set pst_seq [dict create]
foreach r [all_registers -cells] { dict set pst_seq [get_full_name $r] 1; puts "seq [get_full_name $r]" }
foreach c [get_cells -hierarchical *] {
  set ref [get_property $c ref_name]
  if {![dict exists $pst_lib $ref]} { continue }
  lappend pst_leaf $c
  if {![dict exists $pst_seq [get_full_name $c]]} {
    set pst_comb_area [expr {$pst_comb_area + [dict get $pst_lib $ref]}]
  }
}
puts "comb_area $pst_comb_area"
puts "leaf_cells [llength $pst_leaf]"
""" % area_dict,
                      "set_power_activity -global -activity 0 -duty 0.5",
                      "set_power_activity -input -activity 0 -duty 0.5",
                      f"report_power -instances $pst_leaf > {reports[0]}",
                      "set_power_activity -global -activity 1 -duty 0.5",
                      "set_power_activity -input -activity 1 -duty 0.5",
                      f"report_power -instances $pst_leaf > {reports[1]}", ""])


def parse_cells(text: str) -> dict:
    """`report_power -instances` -> {cell path: (internal, switching, leakage)}."""
    out = {}
    for line in text.splitlines():
        f = line.split()
        if len(f) != 5:
            continue
        try:
            out[f[4]] = (float(f[0]), float(f[1]), float(f[2]))
        except ValueError:
            continue
    return out


def _block_namer(tree: dict, top: str):
    index = {m: {n: (n, t) for n, t in insts.values()} for m, insts in tree.items()}
    cache = {}

    def block(parent: str) -> str:
        if parent not in cache:
            module, names = top, []
            for p in parent.split("/")[:2] if parent else []:
                inst = index.get(module, {}).get(p)
                if inst is None:
                    break
                module = inst[1]
                names.append(base_name(module))
            cache[parent] = names[-1].removeprefix("pst_") if names else "top"
        return cache[parent]
    return block


def combine(p0: dict, p1: dict, activity_of, seq: set, block_of) -> tuple:
    """Per-cell linear model -> (groups, blocks): P = P(0) + a (P(1) - P(0)) per component."""
    groups = {g: [0.0, 0.0, 0.0] for g in ("Sequential", "Combinational")}
    blocks = {}
    for cell, lo in p0.items():
        hi = p1.get(cell, lo)
        a = activity_of(cell)
        v = [lo[i] + a * (hi[i] - lo[i]) for i in range(2)] + [lo[2]]
        g = groups["Sequential" if cell in seq else "Combinational"]
        parent = cell.rsplit("/", 1)[0] if "/" in cell else ""
        b = blocks.setdefault(block_of(parent), [0.0, 0.0, 0.0])
        for i in range(3):
            g[i] += v[i]
            b[i] += v[i]
    groups["Total"] = [sum(groups[k][i] for k in ("Sequential", "Combinational")) for i in range(3)]
    fin = lambda d: {k: (*v, sum(v)) for k, v in d.items()}      # noqa: E731
    return fin(groups), fin(blocks)


def run(work, act, libs: list, areas: dict, top: str = "pst_top", sta_bin: str = "sta", tag: str = "power") -> Power:
    """Power of the netlist kept by `scripts/synth.py --keep` in WORK (netlist_sta.v,
    standin.lib) under activity ACT (activity.Activity)."""
    netlist_path = work / "netlist_sta.v"
    netlist = netlist_path.read_text()
    tree = annotate.instance_tree(netlist, top)
    nets = annotate.net_activities(act, tree, top)
    scopes = annotate.scope_activity(act, tree, top)
    drivers = annotate.port_drivers(netlist)
    drv = annotate.driven_cells(nets, tree, drivers, top)
    reports = (work / f"{tag}.a0.txt", work / f"{tag}.a1.txt")
    tcl = power_tcl([*libs, str(work / "standin.lib")], str(netlist_path), top, str(SDC),
                    "", tuple(str(r) for r in reports), areas)
    _, out = run_sta(tcl, work, tag, sta_bin)
    seq = {line[4:] for line in out.splitlines() if line.startswith("seq ")}
    vals = {k: int(v) for k, v in re.findall(r"^(leaf_cells) (\d+)$", out, re.M)}
    cache = {}
    undriven = len(nets) - sum(1 for n, _, _ in nets if annotate.has_driver(n, tree, drivers, top, cache))
    comb = float(re.search(r"^comb_area ([0-9.e+]+)$", out, re.M).group(1))
    mean_all = act.mean() or 0.0

    def activity_of(cell: str) -> float:
        if cell in drv:
            return drv[cell]
        parent = cell.rsplit("/", 1)[0] if "/" in cell else ""
        while True:
            if parent in scopes:
                return scopes[parent]
            if not parent:
                return mean_all
            parent = parent.rsplit("/", 1)[0] if "/" in parent else ""
    p0, p1 = parse_cells(reports[0].read_text()), parse_cells(reports[1].read_text())
    groups, blocks = combine(p0, p1, activity_of, seq, _block_namer(tree, top))
    return Power(groups=groups, blocks=blocks, comb_area_um2=comb, traced_bits=len(nets),
                 missing_bits=undriven, port_driven_cells=len(drv),
                 cells=vals.get("leaf_cells", 0), period_ns=sdc_period_ns(SDC.read_text()))
