"""OpenSTA (Debian's `opensta`, `sta`) scripts and report parsing for scripts/synth.py.

The design's netlist is timed whole (OpenSTA links the hierarchical netlist flat). Every
register data pin is put in a path group named after the top-level instance that holds it
(pipeline registers u_reg_a..d each on their own, a module's lanes together), so one
`report_checks` gives the worst path into each block: the critical path per stage.
"""
import re


def stage_groups_tcl() -> str:
    """Tcl that makes one path group per top-level instance (by module for the lanes of one
    module, by instance for pst_pipe_reg) and prints `group NAME INSTANCE MODULE` lines."""
    return r"""
set pst_groups [dict create]
set pst_modules [dict create]
foreach pin [concat [all_registers -data_pins] [get_pins -hierarchical -quiet */D -filter "direction == input"]] {
  set name [get_full_name $pin]
  set parts [split $name /]
  if {[llength $parts] > 2} {
    set inst [lindex $parts 0]
    set ref [get_property [get_cells $inst] ref_name]
  } else {
    set inst "(top)"
    set ref "pst_top"
  }
  if {![regexp {pst_[A-Za-z0-9_]+} $ref base]} { set base $ref }
  if {[string match "*pst_pipe_reg*" $base] || $inst eq "(top)"} { set key $inst } else { set key $base }
  dict lappend pst_groups $key $pin
  dict set pst_modules $key "$inst $base"
}
set pst_i 0
foreach key [dict keys $pst_groups] {
  set g "pst_g$pst_i"
  incr pst_i
  group_path -name $g -to [dict get $pst_groups $key]
  puts "group $g $key [dict get $pst_modules $key]"
}
"""


def cap_check_tcl(limits: dict, input_limit: float) -> str:
    """Tcl that checks every net against the max_capacitance of the pin driving it (OpenSTA
    2.0.17 does not check the liberty's limit): every leaf output pin with a limit in LIMITS
    ("CELL/PIN" -> pF) and every data input port (driven by the SDC's driving cell, limit
    INPUT_LIMIT). Prints `max_capacitance PIN CELL LOAD LIMIT` per violation and one
    `max_capacitance_worst PIN CELL LOAD LIMIT CHECKED` line (the pin of least slack)."""
    table = " ".join(f"{k} {v:g}" for k, v in sorted(limits.items()))
    return r"""
set pst_limits [dict create %s]
set pst_corner [sta::cmd_corner]
set pst_worst {}
set pst_checked 0
proc pst_cap_check {name cell net limit} {
  global pst_corner pst_worst pst_checked
  if {$net == "NULL"} { return }
  set load [expr {[$net capacitance rise $pst_corner max] * 1e12}]
  set fall [expr {[$net capacitance fall $pst_corner max] * 1e12}]
  if {$fall > $load} { set load $fall }
  incr pst_checked
  set line [format "%%s %%s %%.4f %%.4f" $name $cell $load $limit]
  if {$load > $limit} { puts "max_capacitance $line" }
  if {$pst_worst == {} || $limit - $load < [lindex $pst_worst 0]} { set pst_worst [list [expr {$limit - $load}] $line] }
}
foreach inst [sta::network_leaf_instances] {
  set cell [get_property $inst ref_name]
  foreach pin [get_pins -of_objects $inst -filter "direction == output"] {
    set key "$cell/[get_property $pin lib_pin_name]"
    if {[dict exists $pst_limits $key]} { pst_cap_check [get_full_name $pin] $cell [$pin net] [dict get $pst_limits $key] }
  }
}
foreach port [delete_from_list [all_inputs] [get_ports clk_i]] {
  pst_cap_check [get_full_name $port] port [get_nets -quiet [get_full_name $port]] %g
}
if {$pst_worst != {}} { puts "max_capacitance_worst [lindex $pst_worst 1] $pst_checked" }
""" % (table, input_limit)


def sta_script(libs: list, netlist: str, top: str, sdc: str, reports: dict, cap_limits: dict,
               input_limit: float) -> str:
    """The design's OpenSTA run: setup per stage (REPORTS["setup"]), hold per stage
    (["hold"]), every hold violation (["hold_violators"]), every max-transition violation and
    the pin of least transition slack (["transition"]); the capacitance check goes to stdout
    with the path groups."""
    r = reports
    lines = [f"read_liberty {lib}" for lib in libs]
    lines += [f"read_verilog {netlist}", f"link_design {{{top}}}", f"read_sdc {sdc}",
              stage_groups_tcl(),
              f"report_checks -path_delay max -group_count 1 -endpoint_count 1 -digits 3 -fields {{fanout cap slew}} > {r['setup']}",
              f"report_wns -digits 3 >> {r['setup']}",
              f"report_checks -path_delay min -group_count 1 -endpoint_count 1 -digits 3 -fields {{fanout cap slew}} > {r['hold']}",
              f"report_check_types -min_delay -all_violators -format end -digits 3 > {r['hold_violators']}",
              f"report_check_types -max_transition -digits 3 > {r['transition']}",
              f"report_check_types -max_transition -all_violators -digits 3 >> {r['transition']}",
              cap_check_tcl(cap_limits, input_limit),
              "exit"]
    return "\n".join(lines) + "\n"


_POINT = re.compile(r"^(Startpoint|Endpoint): (\S+)(?: \((.*)\))?\s*$")


def netlist_instances(netlist: str) -> dict:
    """Module -> {instance: (cell or module type, net on its Q pin or None)} of a Yosys
    structural netlist (write_verilog), escaped names unescaped."""
    mods = {}
    cur = None
    inst = None
    for line in netlist.splitlines():
        m = re.match(r"module\s+(\\\S+|[A-Za-z_][\w$]*)", line)
        if m:
            cur = mods.setdefault(m.group(1).lstrip("\\"), {})
            continue
        if cur is None:
            continue
        m = re.match(r"\s+(\\\S+|[A-Za-z_][\w$]*)\s+(\\\S+|[A-Za-z_][\w$]*)\s*\($", line)
        if m and m.group(1) not in ("module", "assign", "wire", "input", "output", "reg"):
            inst = m.group(2).lstrip("\\")
            cur[inst] = (m.group(1).lstrip("\\"), None)
            continue
        m = re.match(r"\s+\.Q\((.+)\)\s*,?\s*$", line)
        if m and inst is not None:
            cur[inst] = (cur[inst][0], m.group(1).strip().lstrip("\\").replace(" [", "["))
    return mods


def register_name(point: str, mods: dict, top: str) -> str:
    """An OpenSTA start/end point (hier/inst path of a flip-flop) -> hier/<its Q net>; ports
    and unknown names are returned as they are."""
    parts = point.split("/")
    module = top
    for p in parts[:-1]:
        cell = mods.get(module, {}).get(p)
        if cell is None:
            return point
        module = cell[0]
    cell = mods.get(module, {}).get(parts[-1])
    if cell is None or cell[1] is None or re.fullmatch(r"_\d+_(\[\d+\])?", cell[1]):
        return point
    return f"{point} ({cell[1]})"


def parse_groups(text: str) -> dict:
    """`group NAME KEY INSTANCE MODULE` lines -> NAME -> {key, instance, module}."""
    out = {}
    for line in text.splitlines():
        parts = line.split()
        if len(parts) >= 5 and parts[0] == "group":
            out[parts[1]] = {"key": parts[2], "instance": parts[3], "module": parts[4]}
    return out


def parse_checks(text: str) -> list:
    """Paths of an OpenSTA `report_checks -path_delay max` or `min` report (full format): one dict per
    path with group, startpoint, endpoint (and their kinds), arrival, required and slack in
    ns, and the cell types of the combinational cells on it (launching and capturing
    registers and ports left out)."""
    paths = []
    cur = None
    section = None
    for line in text.splitlines():
        s = line.strip()
        m = _POINT.match(s)
        if m:
            if m.group(1) == "Startpoint":
                cur = {"startpoint": m.group(2), "start_kind": m.group(3) or "", "endpoint": None,
                       "end_kind": "", "group": None, "cells": [], "through": [], "arrival": None, "required": None,
                       "slack": None}
                paths.append(cur)
                section = None
            else:
                cur["endpoint"] = m.group(2)
                cur["end_kind"] = m.group(3) or ""
            continue
        if cur is None:
            continue
        if s.startswith("Path Group:"):
            cur["group"] = s.split(":", 1)[1].strip()
        elif "Description" in s and cur["arrival"] is None:
            section = "data"
        elif s.endswith("data arrival time") and cur["arrival"] is None:
            cur["arrival"] = float(s.split()[0])
            section = None
        elif s.endswith("data required time") and cur["required"] is None:
            cur["required"] = float(s.split()[0])
        elif re.search(r"slack \((MET|VIOLATED)\)", s):
            cur["slack"] = float(s.split()[0])
        elif section == "data":
            pm = re.search(r"[\^v] (\S+) \((\S+)\)$", s)
            if not pm or pm.group(2) in ("in", "out"):
                continue
            inst = pm.group(1).rsplit("/", 1)[0]
            if inst in (cur["startpoint"], cur["endpoint"]):
                continue
            cur["cells"].append(pm.group(2))
            block = inst.split("/")[0] if "/" in inst else "(top)"
            if block not in cur["through"]:
                cur["through"].append(block)
    return paths


_SLACK = r"(-?[0-9.]+) \((MET|VIOLATED)\)"
_TRANSITION_ROW = re.compile(rf"^(\S+)\s+(-?[0-9.]+)\s+(-?[0-9.]+)\s+{_SLACK}$")
_END_ROW = re.compile(rf"^(\S+) \((\S+)\)\s+(-?[0-9.]+)\s+(-?[0-9.]+)\s+{_SLACK}$")


def parse_transition(text: str) -> dict:
    """`report_check_types -max_transition` (the pin of least slack) and its `-all_violators`
    form: {worst: {pin, limit_ns, transition_ns, slack_ns} or None, violations: [the same, one
    per pin]}."""
    rows = {}
    for line in text.splitlines():
        m = _TRANSITION_ROW.match(line.strip())
        if m:
            rows[m.group(1)] = {"pin": m.group(1), "limit_ns": float(m.group(2)),
                                "transition_ns": float(m.group(3)), "slack_ns": float(m.group(4))}
    worst = min(rows.values(), key=lambda r: r["slack_ns"], default=None)
    return {"worst": worst, "violations": [r for r in rows.values() if r["slack_ns"] < 0]}


def parse_hold_violators(text: str) -> list:
    """`report_check_types -min_delay -all_violators -format end`: one {endpoint, cell,
    slack_ns} per violated endpoint."""
    out = []
    for line in text.splitlines():
        m = _END_ROW.match(line.strip())
        if m and m.group(6) == "VIOLATED":
            out.append({"endpoint": m.group(1), "cell": m.group(2), "slack_ns": float(m.group(5))})
    return out


def parse_capacitance(text: str) -> dict:
    """The lines of cap_check_tcl: {worst: {pin, cell, load_pf, limit_pf} or None, checked:
    drivers checked, violations: [the same per violating driver]}."""
    def row(parts):
        return {"pin": parts[1], "cell": parts[2], "load_pf": float(parts[3]), "limit_pf": float(parts[4])}
    out = {"worst": None, "checked": 0, "violations": []}
    for line in text.splitlines():
        parts = line.split()
        if len(parts) == 5 and parts[0] == "max_capacitance":
            out["violations"].append(row(parts))
        elif len(parts) == 6 and parts[0] == "max_capacitance_worst":
            out["worst"] = row(parts)
            out["checked"] = int(parts[5])
    return out


def sdc_driving_cell(text: str) -> str:
    """The library cell the SDC drives the data inputs with."""
    m = re.search(r"set_driving_cell\b[^\n]*-lib_cell\s+(\S+)", text)
    if not m:
        raise ValueError("SDC has no set_driving_cell -lib_cell")
    return m.group(1)


def fmax_mhz(period_ns: float, worst_slack_ns: float) -> float:
    """The clock the design reaches: the target period less the worst slack."""
    need = period_ns - worst_slack_ns
    if need <= 0:
        raise ValueError(f"period {period_ns} ns less slack {worst_slack_ns} ns is not positive")
    return 1000.0 / need


def sdc_constraints(text: str) -> dict:
    """The SDC's clock uncertainty (setup, hold), clock transition, data input transition and
    max transition in ns (None where the SDC sets none)."""
    def num(pattern):
        m = re.search(pattern, text)
        return float(m.group(1)) if m else None
    return {"period_ns": sdc_period(text),
            "setup_uncertainty_ns": num(r"set_clock_uncertainty\s+-setup\s+([0-9.]+)"),
            "hold_uncertainty_ns": num(r"set_clock_uncertainty\s+-hold\s+([0-9.]+)"),
            "clock_transition_ns": num(r"set_clock_transition\s+([0-9.]+)"),
            "input_transition_ns": num(r"-input_transition_rise\s+([0-9.]+)"),
            "max_transition_ns": num(r"set_max_transition\s+([0-9.]+)")}


def sdc_period(text: str) -> float:
    m = re.search(r"create_clock\b[^\n]*-period\s+([0-9.]+)", text)
    if not m:
        raise ValueError("SDC has no create_clock -period")
    return float(m.group(1))
