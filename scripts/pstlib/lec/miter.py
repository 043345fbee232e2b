"""RTL against the synthesized netlist, module by module: which modules can be compared, and the
one Yosys script that builds a miter per module and writes it as an AIGER file for ABC.

Gold: the RTL elaborated with the profile's parameters (the same `read_lines` and `hierarchy` as
scripts/synth.py, so every derived module has the same $paramod name as in the netlist), `proc`,
asynchronous resets made synchronous as the synthesis does (`async2sync`). Gate: the netlist
scripts/synth.py times and counts (netlist_sta.v: OSU018 cells, the cross-hierarchy fanout
buffers), each cell replaced by its liberty function (`read_liberty` without -lib).

Hierarchically: in both, the module's sub-module instances are cut out (`expose -evert`: their
outputs become inputs of the module, shared by gold and gate since the instance names match,
their inputs outputs that the miter compares), so each check covers the module's own logic and
each sub-module is checked on its own; a module stands proven when it and every module below it
are. `miter -equiv` compares every output bit; flip-flops start at zero on both sides
(`write_aiger -zinit`).

A module whose own cells include a memory's read or write stand-ins (the netlist has no
contents for them) and the top are left to simulation.
"""
import re

from .. import netlist as netlist_reader

_MODULE = re.compile(r"^module\s+(\\\S+|[A-Za-z_][\w$]*)\s*\(")
# A cell instance's first line: Yosys writes `  TYPE NAME (` and the pins below it,
# pstlib/pnr/blif.py `TYPE NAME ( .A(x), ... );` on one line.
_CELL = re.compile(r"^\s*(\\\S+|[A-Za-z_][\w$]*)\s+(\\\S+|[A-Za-z_][\w$]*)\s*\(")

SEQ_CELLS = ("DFFPOSX1", "DFFNEGX1", "DFFSR", "LATCH")
MEM_CELLS = ("PST_MEMRD", "PST_MEMWR")


def modules(netlist: str) -> dict:
    """{module: {"cells": n own leaf cells, "children": [modules instantiated], "seq": bool,
    "mem": bool}} of a Yosys structural netlist; seq and mem of the module's own cells."""
    mods = netlist_reader.instances(netlist)
    out = {}
    for m, insts in mods.items():
        leaves = [t for t, _, _ in insts if t not in mods]
        out[m] = {"cells": len(leaves), "children": [t for t, _, _ in insts if t in mods],
                  "seq": any(t.startswith(SEQ_CELLS) for t in leaves),
                  "mem": any(t.startswith(MEM_CELLS) for t in leaves)}
    return out


def comparable(mods: dict, top: str = "pst_top") -> list:
    """The modules a miter can decide: not the top, no memory stand-in of their own; by their
    own cells, smallest first."""
    return sorted((m for m, d in mods.items() if m != top and not d["mem"]), key=lambda m: (mods[m]["cells"], m))


def standing(mods: dict, verdicts: dict, m: str) -> bool:
    """Whether M and every module below it are proven (VERDICTS: module -> result)."""
    return verdicts.get(m) == "proven" and all(standing(mods, verdicts, c) for c in mods[m]["children"])


def subtree_cells(mods: dict, m: str) -> int:
    d = mods[m]
    return d["cells"] + sum(subtree_cells(mods, c) for c in d["children"])


def gold_name(module: str) -> str:
    """How a Yosys command names MODULE in the elaborated RTL: as it is (a derived module's
    internal $paramod name, a plain module's public one)."""
    return module


def gate_name(module: str) -> str:
    """How a Yosys command names MODULE read back from the netlist (an escaped identifier)."""
    return "\\" + module if module.startswith("$") else module


def script(gold_read: list, lib: str, standin_lib: str, netlist: str, jobs: list) -> str:
    """The Yosys script: JOBS is [(module, AIGER path)]; a `log PST_LEC MODULE` line before each."""
    L = [*gold_read, "hierarchy -check -top pst_top", "proc", "opt_clean", "design -save pst_gold",
         "design -reset", f"read_liberty {lib}", f"read_liberty -lib {standin_lib}", f"read_verilog {netlist}",
         "design -save pst_gate"]
    for module, aig in jobs:
        L += [f"log PST_LEC {module}",
              "design -load pst_gold", f"hierarchy -top {gold_name(module)}",
              f"expose -evert {gold_name(module)}/t:*pst_*", "flatten", "async2sync", "opt_clean",
              f"rename {gold_name(module)} pst_lec_gold", "design -stash pst_g",
              "design -load pst_gate", f"hierarchy -top {gate_name(module)}",
              f"expose -evert {gate_name(module)}/t:*pst_*", "flatten",
              f"rename {gate_name(module)} pst_lec_gate", "design -stash pst_t",
              "design -reset",
              "design -copy-from pst_g -as pst_lec_gold pst_lec_gold",
              "design -copy-from pst_t -as pst_lec_gate pst_lec_gate",
              "miter -equiv -flatten pst_lec_gold pst_lec_gate pst_lec_miter",
              "hierarchy -top pst_lec_miter", "techmap", "opt -fast", "dffunmap", "aigmap",
              "setundef -zero -init", f"write_aiger -zinit {aig}"]
    return "\n".join(L) + "\n"


# A two-input cell and its dual: one swapped cell is the netlist mutant the checks must catch.
DUALS = {"NAND2X1": "NOR2X1", "NOR2X1": "NAND2X1", "AND2X2": "OR2X2", "OR2X2": "AND2X2",
         "XOR2X1": "XNOR2X1", "XNOR2X1": "XOR2X1", "AND2X1": "OR2X1", "OR2X1": "AND2X1"}


def mutate(netlist: str, module: str) -> tuple:
    """NETLIST with the first two-input cell of MODULE swapped for its dual: (text, "CELL NAME:
    FROM -> TO"); ValueError when the module has no such cell."""
    lines = netlist.splitlines(keepends=True)
    inside = False
    for i, line in enumerate(lines):
        m = _MODULE.match(line)
        if m:
            inside = m.group(1).lstrip("\\") == module
            continue
        if not inside:
            continue
        c = _CELL.match(line)
        if c and c.group(1) in DUALS:
            lines[i] = line.replace(c.group(1), DUALS[c.group(1)], 1)
            return "".join(lines), f"{c.group(2)}: {c.group(1)} -> {DUALS[c.group(1)]}"
    raise ValueError(f"{module}: no two-input cell to swap")
