"""The C++ writer: model/golden/contract.h (the profile enums and typed ProfileParams, the schema,
the register map and the formulas as constexpr functions)."""
from __future__ import annotations

import tomllib
from pathlib import Path

from ..contract import BUILTINS, Contract, Key, _names, camel, parameters, translate
from .common import HEADER, _comment, _register_constants, _strip_parens, cpp_arg, emit_formula

def cpp_header(c: Contract) -> str:
    L = [f"// {HEADER}",
         "// The hardware contract (rtl/contract.toml) for the golden model, the driver and the harness:",
         "// profile enums and the typed ProfileParams, profile schema, register map, fixed layouts and",
         "// the derived widths and cycle counts as constexpr functions.",
         "#pragma once", "", "#include <cstdint>", "#include <string_view>", ""]
    L += _cpp_types(c)
    L += ["namespace pst::contract {", ""]
    L.append("// RTL parameters of a profile, in description order (index into a value array).")
    L.append("enum Param : int {")
    for p in c.param_names:
        L.append(f"    {p},")
    L += ["    kNumParams", "};", ""]
    L.append("// Profile enums: names in index order.")
    for k in c.keys:
        if k.kind == "enum":
            names = ", ".join(f'"{e}"' for e in k.enum)
            L.append(f"inline constexpr const char* k{k.params[0]}Names[] = {{{names}}};")
    L += ["", "// A profile enum's name (\"?\" out of range) and its value by name (false: unknown name)."]
    for k in c.keys:
        if k.kind == "enum":
            T, n = f"::pst::{k.cpp_type}", f"k{k.params[0]}Names"
            L.append(f"constexpr const char* name({T} v) {{")
            L.append(f"    return int(v) >= 0 && int(v) < {len(k.enum)} ? {n}[int(v)] : \"?\";")
            L.append("}")
            L.append(f"constexpr bool fromName(std::string_view s, {T}* out) {{")
            L.append(f"    for (int i = 0; i < {len(k.enum)}; ++i)")
            L += [f"        if (s == {n}[i]) {{", f"            *out = {T}(i);", "            return true;", "        }"]
            L.append("    return false;")
            L.append("}")
    L.append("")
    L.append("enum class KeyKind { Range, Values, Enum, Format };")
    L.append("struct KeySpec {")
    L.append("    const char* section;")
    L.append("    const char* key;")
    L.append("    KeyKind kind;")
    L.append("    Param param;             // the first (int) parameter of a format")
    L.append("    int lo, hi;              // Range; Values: the smallest and largest")
    L.append("    int values[8];           // Values (nValues of them)")
    L.append("    int nValues;")
    L.append("    const char* const* names;  // Enum (nValues of them)")
    L.append("    int maxWidth;            // Format: int + frac at most")
    L.append("};")
    L.append(f"inline constexpr int kFormatIntMin = {c.format_int[0]}, kFormatIntMax = {c.format_int[1]};")
    L.append(f"inline constexpr int kFormatFracMin = {c.format_frac[0]}, kFormatFracMax = {c.format_frac[1]};")
    for k in c.keys:
        if k.kind in ("range", "values"):
            L.append(f"inline constexpr int k{k.params[0]}Min = {k.lo}, k{k.params[0]}Max = {k.hi};")
    L.append("inline constexpr KeySpec kSchema[] = {")
    for k in c.keys:
        p = k.params[0]
        if k.kind == "enum":
            L.append(f'    {{"{k.section}", "{k.key}", KeyKind::Enum, {p}, 0, {len(k.enum) - 1}, {{}}, {len(k.enum)}, k{p}Names, 0}},')
        elif k.kind == "values":
            vals = ", ".join(map(str, k.values))
            L.append(f'    {{"{k.section}", "{k.key}", KeyKind::Values, {p}, {k.lo}, {k.hi}, {{{vals}}}, {len(k.values)}, nullptr, 0}},')
        elif k.kind == "range":
            L.append(f'    {{"{k.section}", "{k.key}", KeyKind::Range, {p}, {k.lo}, {k.hi}, {{}}, 0, nullptr, 0}},')
        else:
            L.append(f'    {{"{k.section}", "{k.key}", KeyKind::Format, {p}, 0, 0, {{}}, 0, nullptr, {k.max_width}}},')
    L += ["};", ""]
    L.append("// Cross-constraints over the parameter values, checked once every key is in range.")
    L.append("struct Constraint {")
    L.append("    const char* field;")
    L.append("    const char* message;")
    L.append("    bool (*holds)(const int* v);")
    L.append("};")
    L.append("inline constexpr Constraint kConstraints[] = {")
    for con in c.constraints:
        L.append(f'    {{"{con.field}", "{con.message}",')
        L.append(f"     [](const int* v) {{ return {translate(con.expr, 'cpp', c)}; }}}},")
    L += ["};", ""]
    L.append("// Register map (docs/HARDWARE.md).")
    L.append(f"inline constexpr int kRegAddrBits = {c.registers['addr_bits']};")
    L.append(f"inline constexpr int kRegDataBits = {c.registers['data_bits']};")
    for comment, n, addr, groups in _register_constants(c):
        L.append(f"// {comment}")
        L.append(f"inline constexpr uint16_t kReg{n} = 0x{addr:04x};")
        L += ["inline constexpr int " + ", ".join(f"k{k} = {v}" for k, v in group) + ";" for group in groups]
    for name, values in c.enums.items():
        L.append(f"enum class {camel(name)} : int {{ {', '.join(camel(v) for v in values)} }};")
    L += ["", "// Fixed facts of the datapath."]
    for name, (v, doc) in c.constants.items():
        L.append(f"inline constexpr int k{name} = {v};  // {doc}")
    L += [""] + _cpp_params(c) + [""] + _cpp_formulas(c)
    L += ["}  // namespace pst::contract", ""]
    return "\n".join(L)


def _member(k: Key) -> str:
    """The ProfileParams member of a key: lowerCamel of its RTL parameter (of the key for a
    format: coord, gradMatrix)."""
    return cpp_arg(camel(k.key) if k.kind == "format" else k.params[0])


def _defaults(c: Contract) -> dict[str, int]:
    if not c.defaults:
        return {}
    with open(c.path.parent.parent / c.defaults, "rb") as f:
        return dict(parameters(tomllib.load(f), c))


def _cpp_types(c: Contract) -> list[str]:
    """namespace pst: the profile enums as C++ types, FixedFormat and the typed ProfileParams."""
    L = ["namespace pst {", ""]
    L += _comment("// ", "Profile enums (the enum keys of rtl/contract.toml): one enum class per key, named "
                  "after its RTL parameter (or the key's `cpp`), enumerators UpperCamel of the values in the "
                  "contract's order, so that a value's index is the RTL parameter's value.")
    for k in c.keys:
        if k.kind == "enum":
            L.append(f"enum class {k.cpp_type} : int {{ {', '.join(camel(e) for e in k.enum)} }};  // {k.field}")
    L += ["",
          "// A signed two's-complement format: `intBits` integer bits including the sign, `fracBits`",
          "// fraction bits; value = integer / 2^fracBits.",
          "struct FixedFormat {",
          "    int intBits = 0;",
          "    int fracBits = 0;",
          "    constexpr int width() const { return intBits + fracBits; }",
          "};", ""]
    dflt = _defaults(c)
    L += _comment("// ", f"Every key of a profile, typed, in description order; the defaults are the profile "
                  f"{Path(c.defaults).stem}'s ({c.defaults}, as pst_pkg's *Default). contract::paramValue "
                  "and contract::setParam reach a member by RTL parameter.")
    L.append("struct ProfileParams {")
    section = None
    for k in c.keys:
        if k.section != section:
            section = k.section
            L.append(f"    // [{section}]")
        L += _comment("    // ", k.doc)
        m, p = _member(k), k.params[0]
        if k.kind == "enum":
            L.append(f"    {k.cpp_type} {m} = {k.cpp_type}::{camel(k.enum[dflt.get(p, 0)])};")
        elif k.kind == "format":
            L.append(f"    FixedFormat {m} = {{{dflt.get(p, 0)}, {dflt.get(k.params[1], 0)}}};")
        else:
            L.append(f"    int {m} = {dflt.get(p, k.lo)};")
    L += ["};", "", "}  // namespace pst", ""]
    return L


def _cpp_params(c: Contract) -> list[str]:
    """Parameter names and the by-parameter access to ProfileParams."""
    L = ["// RTL parameter names, indexed by Param.",
         "inline constexpr const char* kParamNames[kNumParams] = {"]
    L += [f'    "{p}",' for p in c.param_names] + ["};", ""]
    get, put = [], []
    for k in c.keys:
        m = _member(k)
        if k.kind == "format":
            for p, part in zip(k.params, ("intBits", "fracBits")):
                get.append(f"        case {p}: return p.{m}.{part};")
                put.append(f"        case {p}: p.{m}.{part} = v; break;")
        elif k.kind == "enum":
            get.append(f"        case {k.params[0]}: return int(p.{m});")
            put.append(f"        case {k.params[0]}: p.{m} = ::pst::{k.cpp_type}(v); break;")
        else:
            get.append(f"        case {k.params[0]}: return p.{m};")
            put.append(f"        case {k.params[0]}: p.{m} = v; break;")
    L += ["// A ProfileParams member by RTL parameter (enums as their index).",
          "constexpr int paramValue(const ProfileParams& p, Param k) {", "    switch (k) {"] + get
    L += ["        case kNumParams: break;", "    }", "    return 0;", "}",
          "constexpr void setParam(ProfileParams& p, Param k, int v) {", "    switch (k) {"] + put
    L += ["        case kNumParams: break;", "    }", "}"]
    return L


def _cpp_formulas(c: Contract) -> list[str]:
    L = _comment("// ", "Derived widths and cycle counts (rtl/contract.toml [formula]; the same functions are in "
                 "pst_pkg and scripts/pstlib/formulas.py).")
    calls = set().union(*(_names(f.tree, "call") for f in c.formulas)) if c.formulas else set()
    for b in sorted(calls & set(BUILTINS)):
        if b == "clog2":
            L.append("constexpr int clog2_int(int a) { int b = 0; while ((1 << b) < a) ++b; return b; }")
        else:
            L.append(f"constexpr int {b}_int(int a, int b) {{ return a {'>' if b == 'max' else '<'} b ? a : b; }}")
    for f in c.formulas:
        L += _comment("// ", f"{f.name}: {f.doc}") + _comment("//   = ", f.expr, then="//     ")
        args = ", ".join(f"int {cpp_arg(a)}" for a in f.args)
        L += [f"constexpr int {f.name}({args}) {{", f"    return {_strip_parens(emit_formula(f.tree, 'cpp', c))};", "}"]
    return L + [""]
