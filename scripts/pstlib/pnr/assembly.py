"""The whole profile timed from its routed blocks: OpenSTA reads every block's routed netlist
(qflow's, with its buffer and clock trees) and its SPEF under the block's instance
(read_spef -path), the top-level netlist that connects the blocks and the memory macros, and
the project's SDC at the chip's own pins.

- The top-level netlist is the one the cut made (partition.split_script: pst_top with one
  instance of each blk_NAME and the memory stand-ins), written by Yosys as BLIF with its
  net aliases as `.conn` lines, and turned into Verilog here: one net per alias group, block
  port names written as qflow's netlists write them (every character other than a letter, a
  digit or _ made _: `u_reg_d.data_o[68]` -> `u_reg_d_data_o_68_`), each block instance named
  as its block (the SPEF's path).
- The clock is propagated from clk_i through each block's own clock buffers and wires, so the
  skew between blocks (their unequal insertion delays: there is no top-level clock tree) is
  in the paths that cross blocks; the setup uncertainty keeps only the SDC's jitter
  (timing.POST_ROUTE_SETUP_UNCERTAINTY), as in the blocks' own post-route runs.
- Not modelled: wires between blocks (blocks are taken to abut: a block pin's net at the top
  has no parasitics) and a top-level clock driver (clk_i switches ideally into every block's
  first clock buffer, the same for all blocks); a block without a routed layout is timed from
  its netlist before layout as qflow buffers it (no wires), named in the record.
"""
import collections
import pathlib
import re

from ..synth import liberty, sta as synth_sta
from ..synth.tools import run_sta
from . import blif, timing
from .timing import POST_ROUTE_SETUP_UNCERTAINTY

CONSTANTS = ("$true", "$false", "$undef")


def write_script(blif_out) -> list:
    """Yosys lines, after partition.split_script's `design -save split`: the top level alone
    (the blocks as black boxes) as BLIF with `.conn` aliases and `.gate` lines."""
    return ["design -load split", "hierarchy -top pst_top", "blackbox blk_*",
            f"write_blif -conn -gates {blif_out}"]


def _ident(name: str) -> str:
    v = re.sub(r"[^A-Za-z0-9_]", "_", name)
    return "n" + v if v and v[0].isdigit() else v


def to_verilog(blif_text: str, block_prefix: str = "blk_") -> str:
    """Verilog of the BLIF's top model: nets joined by `.conn` become one (named after a port
    when one is in the group), instances of BLOCK_PREFIX modules named after their block,
    other cells CELL_N. Constant nets ($true, $false, $undef and what is joined to them:
    the stand-ins' constant address bits, outputs tied off) connect to nothing: they time
    nothing."""
    model, ins, outs, gates, conns = blif.read_model(blif_text, "the top level", conn=True, covers=(["1"], ["0"]))
    parent = {}

    def find(n):
        parent.setdefault(n, n)
        while parent[n] != n:
            parent[n] = parent[parent[n]]
            n = parent[n]
        return n
    ports = set(ins) | set(outs)
    for a, b in conns:
        parent[find(b)] = find(a)
    groups = collections.defaultdict(list)
    for n in list(parent):
        groups[find(n)].append(n)
    # A group's name: its port (a constant group: none, each port keeps its own undriven
    # net), else its first name.
    name_of, const = {}, set()
    for root, members in groups.items():
        gp = [m for m in members if m in ports]
        if any(m in CONSTANTS for m in members):
            const.update(m for m in members if m not in ports)
            continue
        if len(gp) > 1:
            raise ValueError(f"top-level ports joined by a wire: {' '.join(sorted(gp))}")
        for m in members:
            name_of[m] = gp[0] if gp else root
    names = {}

    def net(n):
        n = name_of.get(n, n)
        v = _ident(n)
        if names.setdefault(v, n) != n:
            raise ValueError(f"net names collide as Verilog identifiers ({v})")
        return v
    port_ids = [net(n) for n in ins + outs]
    count = collections.Counter()
    body, used = [], set()
    for cell, pins in gates:
        if cell.startswith(block_prefix):
            inst = cell[len(block_prefix):]
            if inst in count:
                raise ValueError(f"block {cell} instantiated twice in the top level")
            count[inst] += 1
        else:
            count[cell] += 1
            inst = f"{cell}_{count[cell]}"
        conn = []
        for p, n in pins:
            if n in CONSTANTS or n in const:
                continue
            conn.append(f".{_ident(p)}({net(n)})")
            used.add(net(n))
        body.append(f"{cell} {inst} ( {', '.join(conn)} );")
    out = [f"module {model} ({', '.join(port_ids)});"]
    out += [f"input {net(n)};" for n in ins] + [f"output {net(n)};" for n in outs]
    out += [f"wire {n};" for n in sorted(used - set(port_ids))]
    return "\n".join(out + body + ["endmodule", ""])


def sta_script(libs: list, netlists: list, top: str, sdc, spefs: dict, out: str, cap_check: str = "") -> str:
    """Tcl: the assembled design, each block's SPEF under its instance (SPEFS: instance ->
    file), the clock propagated; OUT.setup (the worst path with its clock paths), OUT.reg2reg,
    OUT.in, OUT.out, OUT.hold, OUT.transition; then CAP_CHECK (pstlib/synth/sta.cap_check_tcl)."""
    lines = [f"read_liberty {lib}" for lib in libs]
    lines += [f"read_verilog {n}" for n in netlists]
    lines += [f"link_design {top}", f"read_sdc {sdc}"]
    lines += [f"read_spef -path {inst} {f}" for inst, f in spefs.items()]
    lines += ["set_propagated_clock [all_clocks]",
              f"set_clock_uncertainty -setup {POST_ROUTE_SETUP_UNCERTAINTY} [all_clocks]"]
    lines += [f"report_checks -path_delay max -format full_clock_expanded {timing.FIELDS} > {out}.setup",
              *timing.report_lines(out), cap_check, "exit"]
    return "\n".join(lines) + "\n"


def time_design(work: pathlib.Path, top_blif: pathlib.Path, routed: dict, unrouted: dict, libs: list,
                sdc: pathlib.Path) -> dict:
    """The assembled design timed in WORK: ROUTED maps an instance to (its routed netlist, its
    SPEF), UNROUTED an instance to its block's BLIF before layout. The record: Fmax and the
    critical path over every path of the chip, hold, transition and capacitance checks."""
    work.mkdir(parents=True, exist_ok=True)
    top_v = work / "assembly.v"
    top_v.write_text(to_verilog(pathlib.Path(top_blif).read_text()))
    netlists = [str(v) for v, _ in routed.values()]
    for name, b in unrouted.items():
        v = work / f"{name}_pre_layout.v"
        v.write_text(timing.without_fill(blif.to_verilog(pathlib.Path(b).read_text())))
        netlists.append(str(v))
    netlists.append(str(top_v))
    lib_text = pathlib.Path(libs[0]).read_text()
    limits = liberty.max_capacitance(lib_text)
    drive = synth_sta.sdc_driving_cell(pathlib.Path(sdc).read_text())
    out = str(work / "assembled")
    script = sta_script(libs, netlists, "pst_top", sdc, {k: s for k, (_, s) in routed.items()}, out,
                        synth_sta.cap_check_tcl(limits, limits[f"{drive}/Y"]))
    seconds, stdout = run_sta(script, work, "assembled")
    (work / "assembled.log").write_text(stdout)
    unmatched = [l for l in stdout.splitlines() if "not connected to net" in l or "not found" in l]
    if unmatched:
        raise RuntimeError(f"assembled STA: {len(unmatched)} parasitics not matched to the netlist "
                           f"(first: {unmatched[0]}; log {work / 'assembled.log'})")
    period = synth_sta.sdc_period(pathlib.Path(sdc).read_text())
    run = timing.summary({k: pathlib.Path(f"{out}.{k}").read_text() for k in timing.REPORTS}, stdout, period)
    crit = min([run["reg2reg"]] + ([run["pin"]] if run["pin"] else []), key=lambda p: p["slack_ns"])
    return {"fmax_mhz": crit["fmax_mhz"], "critical_path": crit, "reg2reg": run["reg2reg"], "pin": run["pin"],
            "hold_slack_ns": run["hold_slack_ns"], "max_transition_violations": run["max_transition_violations"],
            "max_capacitance_violations": run["max_capacitance_violations"],
            "routed_blocks": sorted(routed), "blocks_without_layout": sorted(unrouted),
            "report": str(pathlib.Path(f"{out}.setup")), "command": f"sta -no_init -exit {work / 'assembled.tcl'}",
            "seconds": round(seconds, 1)}
