"""OpenSTA on one routed block: the same netlist (qflow's, with its buffer and clock trees)
timed twice against the project's SDC (scripts/synth/pst.sdc), before layout and after
routing, so the ratio of the two is what layout costs.

- pre-layout: as the synthesis times a profile: no wire, ideal clock with the SDC's
  uncertainty (0.3 ns estimated skew + 0.1 ns jitter for setup).
- post-route: the routed RC trees (SPEF, pstlib/pnr/spef.py). Paths between the block's
  registers are timed with the clock propagated through qflow's clock buffers and wires, so
  the skew is measured, not estimated: the setup uncertainty keeps only the jitter
  (POST_ROUTE_SETUP_UNCERTAINTY), the hold uncertainty stays. Paths from or to the block's pins
  carry the SDC's input and output budgets (2 ns each side of a 10 ns cycle) against the
  ideal clock and its full uncertainty: the block's clock insertion delay is assumed matched
  by its neighbours' (a balanced top-level tree), as a budget at a block pin always assumes.

Fmax (each run) = 1 / (period - worst slack) over both kinds of path. Max transition is OpenSTA's check
against the SDC limit, max capacitance the synthesis' check against the liberty's per-pin
limits (pstlib/synth/sta.cap_check_tcl).
"""
import pathlib
import re

from ..synth import liberty, sta as synth_sta

POST_ROUTE_SETUP_UNCERTAINTY = 0.1   # pst.sdc's jitter; its 0.3 ns skew is measured after routing
REPORTS = ("reg2reg", "in", "out", "hold", "transition")


FIELDS = "-digits 3 -fields {cap slew fanout}"


def report_lines(out: str) -> list:
    """Tcl writing the REPORTS: OUT.reg2reg, OUT.in (from the data inputs), OUT.out (to the
    outputs), OUT.hold, OUT.transition."""
    data_in = "[delete_from_list [all_inputs] [get_ports clk_i]]"
    return [f"report_checks -path_delay max -from [all_registers] -to [all_registers] {FIELDS} > {out}.reg2reg",
            f"report_checks -path_delay max -from {data_in} {FIELDS} > {out}.in",
            f"report_checks -path_delay max -to [all_outputs] {FIELDS} > {out}.out",
            f"report_checks -path_delay min {FIELDS} > {out}.hold",
            f"report_check_types -max_transition -digits 3 > {out}.transition",
            f"report_check_types -max_transition -all_violators -digits 3 >> {out}.transition"]


_PORTS = re.compile(r"\[get_ports\s+([^\]\s]+)\s*\]")


def block_sdc(sdc_text: str, ports: set) -> str:
    """The chip's SDC for a block: a command naming a port the block does not have (a block
    without the reset rst_ni: `set_false_path -from [get_ports rst_ni]`) is dropped, which
    OpenSTA would otherwise fail on; wildcards are left to OpenSTA."""
    out = []
    for line in sdc_text.splitlines(keepends=True):
        named = [n for n in _PORTS.findall(line) if not any(c in n for c in "*?$")]
        if any(n not in ports for n in named):
            out.append("# not a port of this block: " + line)
        else:
            out.append(line)
    return "".join(out)


def netlist_ports(verilog: str) -> set:
    """The ports of a structural netlist's first module (`module NAME (a, b, ...);`)."""
    m = re.search(r"^\s*module\s+\S+\s*\(([^)]*)\)\s*;", verilog, re.M)
    return {p.strip() for p in m.group(1).split(",") if p.strip()} if m else set()


def script(lib, netlist, top: str, sdc, spef, out: str, propagated: bool) -> str:
    """Tcl writing OUT.reg2reg, OUT.in (from the data inputs), OUT.out (to the outputs), OUT.hold
    and OUT.transition; the capacitance check on stdout. PROPAGATED: the clock through its
    buffers (post-route, register-to-register). The SDC is the block's (block_sdc), written
    beside OUT."""
    lib_text = open(lib).read()
    limits = liberty.max_capacitance(lib_text)
    sdc_text = open(sdc).read()
    drive = synth_sta.sdc_driving_cell(sdc_text)
    own = pathlib.Path(f"{out}.sdc")
    own.write_text(block_sdc(sdc_text, netlist_ports(pathlib.Path(netlist).read_text())))
    lines = [f"read_liberty {lib}", f"read_verilog {netlist}", f"link_design {top}", f"read_sdc {own}"]
    if spef:
        lines.append(f"read_spef {spef}")
    if propagated:
        lines += ["set_propagated_clock [all_clocks]",
                  f"set_clock_uncertainty -setup {POST_ROUTE_SETUP_UNCERTAINTY} [all_clocks]"]
    lines += [*report_lines(out), synth_sta.cap_check_tcl(limits, limits[f"{drive}/Y"]), "exit"]
    return "\n".join(lines) + "\n"


def without_fill(verilog: str) -> str:
    """qflow's routed netlist less its filler instances (no pins; OpenSTA would black-box them)."""
    return re.sub(r"^FILL\s+\S+\s*\([^;]*\);\s*$\n?", "", verilog, flags=re.M)


def _worst(text: str, what: str):
    paths = [p for p in synth_sta.parse_checks(text) if p["slack"] is not None]
    if not paths and what != "pin":
        raise RuntimeError(f"OpenSTA: no {what} path reported")
    return paths[0] if paths else None


def _path(p: dict, period: float) -> dict:
    return {"slack_ns": p["slack"], "fmax_mhz": round(synth_sta.fmax_mhz(period, p["slack"]), 1),
            "from": p["startpoint"], "to": p["endpoint"], "arrival_ns": p["arrival"], "cells": len(p["cells"])}


def summary(reports: dict, stdout: str, period: float) -> dict:
    """One run: the worst register-to-register path and the worst path from or to a block pin
    (None when the block has none), worst hold slack, max-transition and max-capacitance
    violations. REPORTS: name (REPORTS) -> text; STDOUT: the run's output (capacitance check)."""
    reg = _worst(reports["reg2reg"], "register-to-register")
    pins = [p for p in (_worst(reports["in"], "pin"), _worst(reports["out"], "pin")) if p]
    pin = min(pins, key=lambda p: p["slack"]) if pins else None
    hold = _worst(reports["hold"], "hold")
    tran = synth_sta.parse_transition(reports["transition"])
    cap = synth_sta.parse_capacitance(stdout)
    if cap["checked"] == 0:
        raise RuntimeError("OpenSTA: the capacitance check saw no driver")
    return {"reg2reg": _path(reg, period), "pin": _path(pin, period) if pin else None,
            "hold_slack_ns": hold["slack"], "max_transition_violations": len(tran["violations"]),
            "worst_transition_slack_ns": tran["worst"]["slack_ns"] if tran["worst"] else None,
            "max_capacitance_violations": len(cap["violations"]), "worst_capacitance": cap["worst"]}


def combine(reg_run: dict, pin_run: dict) -> dict:
    """The block's figure from its register-to-register run and its pin run: the worse path of
    the two is the critical path and gives Fmax; checks are the register run's (hold and the
    electrical checks do not depend on how pins are budgeted, except at the pins: the worse
    count of the two)."""
    paths = [reg_run["reg2reg"]] + ([pin_run["pin"]] if pin_run["pin"] else [])
    worst = min(paths, key=lambda p: p["slack_ns"])
    return {"fmax_mhz": worst["fmax_mhz"], "critical_path": worst,
            "reg2reg": reg_run["reg2reg"], "pin": pin_run["pin"],
            "hold_slack_ns": min(reg_run["hold_slack_ns"], pin_run["hold_slack_ns"]),
            "max_transition_violations": max(reg_run["max_transition_violations"], pin_run["max_transition_violations"]),
            "max_capacitance_violations": max(reg_run["max_capacitance_violations"],
                                              pin_run["max_capacitance_violations"]),
            "worst_capacitance": reg_run["worst_capacitance"]}
