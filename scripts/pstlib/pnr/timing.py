"""OpenSTA on one routed block: the same netlist (qflow's, with its buffer trees) timed
twice against the project's SDC, before layout (no wire) and after routing (the SPEF of
pstlib/pnr/spef.py), so the ratio of the two is the cost of the wires alone.

A block's pins carry the SDC's input and output budgets (2 ns each side of a 10 ns
cycle): a path that leaves the block is timed to its pin, not through its neighbour.
Register-to-register paths inside the block are reported on their own as well.
"""
import re

from ..synth import sta as synth_sta


REPORTS = ("setup", "reg2reg", "hold", "transition")


def script(lib, netlist, top: str, sdc, spef, out: str) -> str:
    """Tcl writing OUT.setup, OUT.reg2reg, OUT.hold and OUT.transition."""
    lines = [f"read_liberty {lib}", f"read_verilog {netlist}", f"link_design {top}", f"read_sdc {sdc}"]
    if spef:
        lines.append(f"read_spef {spef}")
    fields = "-digits 3 -fields {cap slew fanout}"
    lines += [f"report_checks -path_delay max {fields} > {out}.setup",
              f"report_checks -path_delay max -from [all_registers] -to [all_registers] {fields} > {out}.reg2reg",
              f"report_checks -path_delay min {fields} > {out}.hold",
              f"report_check_types -max_transition -all_violators > {out}.transition",
              "exit"]
    return "\n".join(lines) + "\n"


def without_fill(verilog: str) -> str:
    """qflow's routed netlist less its filler instances (no pins; OpenSTA would black-box them)."""
    return re.sub(r"^FILL\s+\S+\s*\([^;]*\);\s*$\n?", "", verilog, flags=re.M)


def _worst(text: str, what: str) -> dict:
    paths = [p for p in synth_sta.parse_checks(text) if p["slack"] is not None]
    if not paths:
        raise RuntimeError(f"OpenSTA: no {what} path reported")
    return paths[0]


def summary(reports: dict, period: float) -> dict:
    """Worst setup path (all paths, and register to register), worst hold slack, max-transition
    violations, Fmax = 1 / (period - worst setup slack). REPORTS: name (REPORTS) -> text."""
    setup = _worst(reports["setup"], "setup")
    reg2reg = _worst(reports["reg2reg"], "register-to-register")
    hold = _worst(reports["hold"], "hold")
    slew = re.findall(r"\(VIOLATED\)", reports["transition"])
    return {"setup_slack_ns": setup["slack"], "fmax_mhz": round(synth_sta.fmax_mhz(period, setup["slack"]), 1),
            "critical_path": {"from": setup["startpoint"], "to": setup["endpoint"],
                              "arrival_ns": setup["arrival"], "cells": len(setup["cells"])},
            "reg2reg_slack_ns": reg2reg["slack"],
            "reg2reg_fmax_mhz": round(synth_sta.fmax_mhz(period, reg2reg["slack"]), 1),
            "hold_slack_ns": hold["slack"], "max_transition_violations": len(slew)}
