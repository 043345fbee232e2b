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


def sta_script(libs: list, netlist: str, top: str, sdc: str, report: str) -> str:
    lines = [f"read_liberty {lib}" for lib in libs]
    lines += [f"read_verilog {netlist}", f"link_design {{{top}}}", f"read_sdc {sdc}",
              stage_groups_tcl(),
              f"report_checks -path_delay max -group_count 1 -endpoint_count 1 -digits 3 -fields {{fanout cap slew}} > {report}",
              f"report_wns -digits 3 >> {report}",
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
    """Paths of an OpenSTA `report_checks -path_delay max` report (full format): one dict per
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


def fmax_mhz(period_ns: float, worst_slack_ns: float) -> float:
    """The clock the design reaches: the target period less the worst slack."""
    need = period_ns - worst_slack_ns
    if need <= 0:
        raise ValueError(f"period {period_ns} ns less slack {worst_slack_ns} ns is not positive")
    return 1000.0 / need


def sdc_period(text: str) -> float:
    m = re.search(r"create_clock\b[^\n]*-period\s+([0-9.]+)", text)
    if not m:
        raise ValueError("SDC has no create_clock -period")
    return float(m.group(1))
