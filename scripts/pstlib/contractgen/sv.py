"""The SystemVerilog writer: rtl/pst_pkg.sv (package pst_pkg), rtl/pst_profile_checks.svh (the
schema checked at elaboration) and rtl/pst_params.svh (the parameter groups as macros)."""
from __future__ import annotations

import textwrap
import tomllib
from pathlib import Path

from ..contract import BUILTINS, Contract, _names, camel, parameters, translate
from .common import HEADER, _comment, _register_constants, _strip_parens, emit_formula

def sv_package(c: Contract) -> str:
    L = [f"// {HEADER}",
         "// pst_pkg: the hardware contract (rtl/contract.toml) for the RTL: profile enums, the",
         "// register map, port and probe layouts, the fixed step counts and the derived widths and cycle",
         "// counts as functions (pst_pkg::w_width(Log2Clut, WidthFrac)). Referenced as pst_pkg::Name",
         "// (Yosys 0.23 reads no `import`). Every file that uses it includes it first (the guard makes",
         "// that once), so any file order works in Verilator and Yosys.",
         "`ifndef PST_PKG_SV", "`define PST_PKG_SV", "`default_nettype none", "", "package pst_pkg;", "",
         "  // A design uses a few of these facts at a time.", "  /* verilator lint_off UNUSEDPARAM */", ""]
    L.append("  // Profile enums (the values of the int parameters Datapath, NoiseInterp, ...).")
    for k in c.keys:
        if k.kind == "enum":
            p = k.params[0]
            L.append(f"  // {k.field}: {k.doc}")
            for i, e in enumerate(k.enum):
                L.append(f"  localparam int {p}{camel(e)} = {i};")
    L += ["", "  // Profile ranges (model/golden/profile.cpp and scripts/pstlib/contract.py check them)."]
    for k in c.keys:
        if k.kind in ("range", "values"):
            p = k.params[0]
            L.append(f"  localparam int {p}Min = {k.lo};")
            L.append(f"  localparam int {p}Max = {k.hi};")
    if c.defaults:
        root = c.path.parent.parent
        with open(root / c.defaults, "rb") as f:
            dflt = parameters(tomllib.load(f), c)
        L += ["", f"  // Parameter defaults of every module: the profile {Path(c.defaults).stem} ({c.defaults})."]
        enums = c.enum_of_param()
        for name, value in dflt:
            shown = f"{name}{camel(enums[name].enum[value])}" if name in enums else str(value)
            L.append(f"  localparam int {name}Default = {shown};")
    L += ["", "  // Register map (docs/HARDWARE.md).",
          f"  localparam int RegAddrBits = {c.registers['addr_bits']};",
          f"  localparam int RegDataBits = {c.registers['data_bits']};"]
    ab = c.registers["addr_bits"]
    for comment, n, addr, groups in _register_constants(c):
        L.append(f"  // {comment}")
        L.append(f"  localparam logic [{ab - 1}:0] Reg{n} = {ab}'h{addr:04x};")
        L += [f"  localparam int {k} = {v};" for group in groups for k, v in group]
    for name, values in c.enums.items():
        L.append(f"  // {name}")
        for i, v in enumerate(values):
            L.append(f"  localparam int {camel(name)}{camel(v)} = {i};")
    L += ["", "  // Fixed facts of the datapath."]
    for name, (v, doc) in c.constants.items():
        L.append(f"  localparam int {name} = {v};  // {doc}")
    L += ["", "  /* verilator lint_on UNUSEDPARAM */", ""] + sv_functions(c) + ["endpackage", "", "`default_nettype wire",
          "`endif  // PST_PKG_SV", ""]
    return "\n".join(L)


def sv_functions(c: Contract) -> list[str]:
    """The [formula] functions (Verilog-2001 style assignment to the function name: Yosys 0.23
    reads no `return` in a function)."""
    L = _comment("  // ", "Derived widths and cycle counts (rtl/contract.toml [formula]; the same functions are "
                 "constexpr in model/golden/contract.h and Python in scripts/pstlib/formulas.py). Call them as "
                 "pst_pkg::w_width(Log2Clut, WidthFrac).")
    calls = set().union(*(_names(f.tree, "call") for f in c.formulas)) if c.formulas else set()
    for b in sorted(calls & set(BUILTINS) - {"clog2"}):   # clog2: SystemVerilog's own $clog2
        op = ">" if b == "max" else "<"
        L += [f"  function automatic int {b}_int(input int a, input int b);",
              f"    {b}_int = (a {op} b) ? a : b;", "  endfunction"]
    for f in c.formulas:
        L += _comment("  // ", f"{f.name}: {f.doc}") + _comment("  //   = ", f.expr, then="  //     ")
        L += [f"  function automatic int {f.name}({', '.join(f'input int {a}' for a in f.args)});",
              f"    {f.name} = {_strip_parens(emit_formula(f.tree, 'sv', c))};", "  endfunction"]
    return L + [""]


def sv_checks(c: Contract) -> str:
    """The profile's ranges and cross-constraints as elaboration-time assertions over pst_top's
    parameters (included by pst_top outside synthesis)."""
    L = [f"// {HEADER}",
         "// The profile schema's ranges and cross-constraints (rtl/contract.toml) over pst_top's",
         "// parameters, checked at elaboration. Included by pst_top (`ifndef SYNTHESIS).",
         "initial begin"]
    for k in c.keys:
        if k.kind == "enum":
            p = k.params[0]
            L.append(f'  assert ({p} >= 0 && {p} < {len(k.enum)}) else $fatal(1, "{k.field}: unknown value");')
        elif k.kind == "values":
            p = k.params[0]
            cond = " || ".join(f"{p} == {v}" for v in k.values)
            L.append(f'  assert ({cond}) else $fatal(1, "{k.field}: must be one of {", ".join(map(str, k.values))}");')
        elif k.kind == "range":
            p = k.params[0]
            L.append(f'  assert ({p} >= {k.lo} && {p} <= {k.hi}) else $fatal(1, "{k.field}: must be in [{k.lo}, {k.hi}]");')
        else:
            i, f = k.params
            L.append(f"  assert ({i} >= {c.format_int[0]} && {i} <= {c.format_int[1]} && {f} >= {c.format_frac[0]} && "
                     f"{f} <= {c.format_frac[1]} && {i} + {f} <= {k.max_width})")
            L.append(f'    else $fatal(1, "{k.field}: int in [{c.format_int[0]}, {c.format_int[1]}], frac in '
                     f'[{c.format_frac[0]}, {c.format_frac[1]}], int + frac <= {k.max_width}");')
    for con in c.constraints:
        L.append(f"  assert ({translate(con.expr, 'sv', c)})")
        L.append(f'    else $fatal(1, "{con.field}: {con.message}");')
    L += ["end", ""]
    return "\n".join(L)


def param_groups(c: Contract) -> list[tuple[str, str, list[str]]]:
    """(NAME, doc, [parameter]) per [rtl_params] group, then PROFILE (every parameter).

    A group is the union of the groups it names (`groups`, each defined above it) and the
    parameters it lists (`params`), in the order written, each parameter once (at its first
    place). Groups may overlap: a module takes the one group that is its parameter set, or
    several disjoint ones. A ValueError names a parameter the schema lacks, a group named before
    it is defined (or not at all), a group that names neither, or a parameter listed twice in
    one group's `params` or listed there and also brought by one of its `groups`."""
    known, defined, out = set(c.param_names), {}, []
    for g, spec in c.raw.get("rtl_params", {}).items():
        unknown = set(spec) - {"doc", "groups", "params"}
        if unknown:
            raise ValueError(f"rtl_params.{g}: unknown key {sorted(unknown)[0]}")
        if not spec.get("groups") and not spec.get("params"):
            raise ValueError(f"rtl_params.{g}: names no groups and no params")
        members: list[str] = []
        for sub in spec.get("groups", []):
            if sub not in defined:
                raise ValueError(f"rtl_params.{g}: group {sub} is not defined above it")
            members += [p for p in defined[sub] if p not in members]
        brought = set(members)
        for p in spec.get("params", []):
            if p not in known:
                raise ValueError(f"rtl_params.{g}: {p} is not a profile parameter")
            if p in members:
                where = "its groups bring it" if p in brought else "it is listed twice"
                raise ValueError(f"rtl_params.{g}: {p}: {where}")
            members.append(p)
        defined[g] = members
        out.append((g.upper(), spec.get("doc", ""), members))
    return out + [("PROFILE", "every profile parameter, in schema order (pst_top; declaration only)",
                   c.param_names)]


def sv_params(c: Contract) -> str:
    """rtl/pst_params.svh: per parameter group, a declaration macro and a pass-through macro
    (Yosys 0.23 takes no struct parameter, so a group travels as a list)."""
    L = [f"// {HEADER}",
         "// pst_params: the profile's parameter groups (rtl/contract.toml [rtl_params]) as macros, so that",
         "// a module declares its profile parameters once: `PST_<GROUP>_PARAMS in its #( ... ) declares",
         "// `parameter int P = pst_pkg::PDefault` per parameter, `PST_<GROUP>_PASS in an instance's",
         "// #( ... ) passes `.P(P)`; add a comma when more parameters follow. Include after pst_pkg.sv.",
         "// A group may contain other groups and overlap them: a module takes the one group that is its",
         "// parameter set (or several disjoint ones), and passes a sub-module's group on whole.",
         "// Read by the Verilator lint and build and by Yosys 0.23 (read_verilog -sv), which takes no",
         "// struct parameter that could otherwise carry a group.",
         "`ifndef PST_PARAMS_SVH", "`define PST_PARAMS_SVH", ""]
    for name, doc, params in param_groups(c):
        L += _comment("// ", f"{name}: {doc}.")
        decl = [f"  parameter int {p} = pst_pkg::{p}Default" for p in params]
        L.append(f"`define PST_{name}_PARAMS \\")
        L += [d + (", \\" if i + 1 < len(decl) else "") for i, d in enumerate(decl)]
        if name != "PROFILE":   # pst_top passes groups on, not the whole profile
            rows = textwrap.wrap(", ".join(f".{p}({p})" for p in params), 92, break_on_hyphens=False)
            L.append(f"`define PST_{name}_PASS \\")
            L += [f"  {r}" + (" \\" if i + 1 < len(rows) else "") for i, r in enumerate(rows)]
        L.append("")
    L += ["`endif  // PST_PARAMS_SVH", ""]
    return "\n".join(L)
