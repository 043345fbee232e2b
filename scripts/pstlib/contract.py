#!/usr/bin/python3
"""The hardware contract (rtl/contract.toml): profile schema, register map, fixed constants.

One description, read here, is the profile schema of every script and the source of the
generated files each other side uses (rtl/pst_pkg.sv, rtl/pst_profile_checks.svh,
rtl/pst_params.svh, model/golden/contract.h, scripts/pstlib/formulas.py). Its Markdown tables
(register map, cycles per stage, the profile-key reference) are written into the docs by
scripts/gen_docs.py.

API (import as `from pstlib import contract`, with scripts/ on sys.path):
  load(path=None) -> Contract          the description (cached; default rtl/contract.toml)
  ENUMS          {(section, key): [names]}   profile enums, names in index order
  FORMAT_MAX     {format name: max int + frac}
  FORMAT_INT, FORMAT_FRAC   (lo, hi) of a format's int and frac bits
  RANGES         {(section, key): (lo, hi) or tuple of allowed values}
  param_name(section, key[, part])    RTL parameter name: ("noise", "out_frac") -> NoiseOutFrac
  validate(doc) -> [str]               what the golden model and the RTL reject, each
                                       "FIELD: what is wrong" (empty: valid); doc as tomllib loads it
  parameters(doc) -> [(Name, int)]     the RTL parameters of a valid profile (enums as indices)
  read_profile(path) -> dict           tomllib-loaded and validated; raises ProfileError whose str()
                                       is "PATH:LINE: FIELD: what is wrong"
  sv_package(c), sv_checks(c), sv_params(c), cpp_header(c), python_formulas(c)
                                       the generated texts
  stage_cycles(doc) -> {stage: cycles}  cycles per stage and per pixel of a profile (docs table)
  hardware_md_table(c), cycles_md_table(c, root), profile_keys_md(c, root)
                                       the docs' Markdown tables (scripts/gen_docs.py writes them)
  formulas       the [formula] functions (w_width, octave_cycles, ...), generated into
                 scripts/pstlib/formulas.py (also constexpr in contract.h, functions in pst_pkg)
  GENERATED      {relative path: generator} of every generated file

CLI:
  contract.py --write [--root DIR]     regenerate the generated files under DIR (default: the repo)
  contract.py --check                  exit 1 naming each stale generated file (ctest contract_stale)
"""
from __future__ import annotations

import argparse
import functools
import re
import sys
import textwrap
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

try:
    from . import formulas
    from .paths import ROOT
except ImportError:        # run as a script (rtl/CMakeLists.txt): scripts/pstlib/ is sys.path[0]
    import formulas
    from paths import ROOT
DESCRIPTION = ROOT / "rtl" / "contract.toml"
SECTION_PREFIX = {"pipeline": "", "noise": "Noise", "filter": "Filter", "formats": ""}


def camel(key: str) -> str:
    """snake_case -> UpperCamelCase (grad_matrix -> GradMatrix)."""
    return "".join(part[:1].upper() + part[1:] for part in key.split("_"))


def param_name(section: str, key: str, part: str | None = None) -> str:
    """RTL parameter of a profile key; `part` is "int" or "frac" for a format."""
    return SECTION_PREFIX[section] + camel(key) + (camel(part) if part else "")


@dataclass
class Key:
    section: str
    key: str
    kind: str                 # "range" | "values" | "enum" | "format"
    doc: str = ""
    lo: int = 0
    hi: int = 0
    values: tuple = ()
    enum: tuple = ()
    max_width: int = 0
    cpp: str = ""             # enum: the C++ type's name when it is not the RTL parameter's

    @property
    def cpp_type(self) -> str:
        return self.cpp or self.params[0]

    @property
    def field(self) -> str:
        return f"{self.section}.{self.key}"

    @property
    def params(self) -> list[str]:
        if self.kind == "format":
            return [param_name(self.section, self.key, "int"), param_name(self.section, self.key, "frac")]
        return [param_name(self.section, self.key)]


@dataclass
class Constraint:
    expr: str
    field: str
    message: str


@dataclass
class Formula:
    name: str
    args: list[str]
    expr: str
    doc: str
    tree: tuple = ()          # the parsed expression (parse_formula)


@dataclass
class Contract:
    path: Path
    keys: list[Key]
    format_int: tuple[int, int]
    format_frac: tuple[int, int]
    constraints: list[Constraint]
    registers: dict
    enums: dict                 # extra enums (filter_kind ...): name -> [values]
    constants: dict             # name -> (value, doc)
    raw: dict = field(repr=False, default_factory=dict)
    defaults: str = ""          # the profile whose values are the RTL parameter defaults
    formulas: list = field(default_factory=list)   # [Formula], in description order

    def key(self, section: str, key: str) -> Key:
        for k in self.keys:
            if k.section == section and k.key == key:
                return k
        raise KeyError(f"{section}.{key}")

    @property
    def param_names(self) -> list[str]:
        return [p for k in self.keys for p in k.params]

    def enum_of_param(self) -> dict[str, Key]:
        return {k.params[0]: k for k in self.keys if k.kind == "enum"}


@functools.lru_cache(maxsize=None)
def load(path: str | Path | None = None) -> Contract:
    """Reads the description (default rtl/contract.toml)."""
    path = Path(path) if path else DESCRIPTION
    with open(path, "rb") as f:
        raw = tomllib.load(f)
    schema = raw["schema"]
    keys = []
    for section in ("pipeline", "noise", "filter", "formats"):
        for key, spec in schema[section].items():
            doc = spec.get("doc", "")
            if "enum" in spec:
                keys.append(Key(section, key, "enum", doc, enum=tuple(spec["enum"]), cpp=spec.get("cpp", "")))
            elif "values" in spec:
                keys.append(Key(section, key, "values", doc, values=tuple(spec["values"]),
                                lo=min(spec["values"]), hi=max(spec["values"])))
            elif spec.get("format"):
                keys.append(Key(section, key, "format", doc, max_width=spec["max_width"]))
            else:
                keys.append(Key(section, key, "range", doc, lo=spec["min"], hi=spec["max"]))
    constraints = [Constraint(c["expr"], c["field"], c["message"]) for c in raw.get("constraint", [])]
    constants = {}
    for n, v in raw.get("constants", {}).items():
        if "expr" in v:
            if not re.fullmatch(r"[A-Za-z0-9_ +\-*/()<>]+", v["expr"]):
                raise ValueError(f"constants.{n}: expr {v['expr']!r} is not + - * / << >> over names")
            value = eval(v["expr"].replace("/", "//"), {}, {k: x for k, (x, _) in constants.items()})  # noqa: S307
            constants[n] = (value, f"{v.get('doc', '')} (= {v['expr']})")
        else:
            constants[n] = (v["value"], v.get("doc", ""))
    c = Contract(path, keys, tuple(schema["format_int"]), tuple(schema["format_frac"]), constraints,
                 raw["registers"], raw.get("enums", {}), constants, raw,
                 schema.get("defaults", {}).get("profile", ""))
    for n, f in raw.get("formula", {}).items():
        fm = Formula(n, list(f["args"]), f["expr"], f.get("doc", ""))
        try:
            fm.tree = parse_formula(fm.expr, fm.args, c)
        except ValueError as e:
            raise ValueError(f"formula.{n}: {e}") from None
        c.formulas.append(fm)
    return c


# ---------------------------------------------------------------------------------------------
# Formulas ([formula.NAME]): a small C expression language, parsed once and written out as
# SystemVerilog, C++ and Python.
# ---------------------------------------------------------------------------------------------
_FTOKEN = re.compile(r"\s*(?:(\d+)|([A-Za-z_][A-Za-z0-9_]*)|(&&|\|\||==|!=|<=|>=|<<|>>|[-+*/%<>()!?:,.]))")
_BINARY = [["||"], ["&&"], ["==", "!="], ["<", "<=", ">", ">="], ["<<", ">>"], ["+", "-"], ["*", "/", "%"]]
BUILTINS = {"max": 2, "min": 2}


def parse_formula(expr: str, args: list[str], c: Contract) -> tuple:
    """The expression tree: ("num", n) | ("arg", name) | ("const", name) | ("enum", param, member)
    | ("call", name, [trees]) | ("un", op, t) | ("bin", op, a, b) | ("cond", c, a, b). Names are
    the args, the constants, enum values and earlier formulas (ValueError otherwise)."""
    toks, pos, s = [], 0, expr.strip()
    while pos < len(s):
        m = _FTOKEN.match(s, pos)
        if not m or m.end() == pos:
            raise ValueError(f"cannot read {s[pos:]!r}")
        toks.append(m.groups())
        pos = m.end()
    i = 0
    enums = c.enum_of_param()
    known = {f.name: len(f.args) for f in c.formulas}

    def peek(op=None):
        if i >= len(toks):
            return None if op else (None, None, None)
        return toks[i][2] if op else toks[i]

    def take(op):
        nonlocal i
        if peek(True) != op:
            raise ValueError(f"{expr!r}: expected {op!r}")
        i += 1

    def primary():
        nonlocal i
        num, name, op = peek()
        if num:
            i += 1
            return ("num", int(num))
        if op == "(":
            i += 1
            t = cond()
            take(")")
            return t
        if op in ("!", "-"):
            i += 1
            return ("un", op, primary())
        if not name:
            raise ValueError(f"{expr!r}: unexpected {op!r}")
        i += 1
        if peek(True) == ".":
            i += 1
            member = peek()[1]
            i += 1
            if name not in enums or member not in enums[name].enum:
                raise ValueError(f"{expr!r}: unknown enum value {name}.{member}")
            return ("enum", name, member)
        if peek(True) == "(":
            i += 1
            actual = [cond()]
            while peek(True) == ",":
                i += 1
                actual.append(cond())
            take(")")
            want = known.get(name, BUILTINS.get(name))
            if want is None:
                raise ValueError(f"{expr!r}: unknown function {name} (a formula must come before its uses)")
            if want != len(actual):
                raise ValueError(f"{expr!r}: {name} takes {want} arguments")
            return ("call", name, actual)
        if name in args:
            return ("arg", name)
        if name in c.constants:
            return ("const", name)
        raise ValueError(f"{expr!r}: unknown name {name}")

    def binary(level):
        if level == len(_BINARY):
            return primary()
        t = binary(level + 1)
        while peek(True) in _BINARY[level]:
            op = peek(True)
            take(op)
            t = ("bin", op, t, binary(level + 1))
        return t

    def cond():
        t = binary(0)
        if peek(True) == "?":
            take("?")
            a = cond()
            take(":")
            return ("cond", t, a, cond())
        return t

    tree = cond()
    if i != len(toks):
        raise ValueError(f"{expr!r}: unexpected {toks[i]}")
    return tree


def cpp_arg(name: str) -> str:
    """A formula argument as a C++ name: lowerCamel (Log2Clut -> log2Clut), all-caps lowered (QW -> qw)."""
    return name.lower() if name.isupper() else name[:1].lower() + name[1:]


def emit_formula(t: tuple, lang: str, c: Contract) -> str:
    """A formula tree as "sv" (inside pst_pkg), "cpp" (inside pst::contract) or "py" text,
    every operation in parentheses (the three languages' precedences differ)."""
    kind = t[0]
    if kind == "num":
        return str(t[1])
    if kind == "arg":
        return cpp_arg(t[1]) if lang == "cpp" else t[1]
    if kind == "const":
        return {"sv": t[1], "cpp": f"k{t[1]}", "py": t[1]}[lang]
    if kind == "enum":
        idx = c.enum_of_param()[t[1]].enum.index(t[2])
        return f"{t[1]}{camel(t[2])}" if lang == "sv" else str(idx)
    if kind == "call":
        name = {"sv": {"max": "max_int", "min": "min_int"}, "cpp": {"max": "max_int", "min": "min_int"}}.get(lang, {}).get(t[1], t[1])
        return f"{name}({', '.join(emit_formula(a, lang, c) for a in t[2])})"
    if kind == "un":
        op = "not " if lang == "py" and t[1] == "!" else t[1]
        return f"({op}{emit_formula(t[2], lang, c)})"
    if kind == "bin":
        op = {"&&": "and", "||": "or", "/": "//"}.get(t[1], t[1]) if lang == "py" else t[1]
        return f"({emit_formula(t[2], lang, c)} {op} {emit_formula(t[3], lang, c)})"
    cnd, a, b = (emit_formula(x, lang, c) for x in t[1:])
    return f"({a} if {cnd} else {b})" if lang == "py" else f"({cnd} ? {a} : {b})"


def _strip_parens(s: str) -> str:
    """Drops one pair of parentheses around the whole text."""
    if not (s.startswith("(") and s.endswith(")")):
        return s
    depth = 0
    for n, ch in enumerate(s):
        depth += {"(": 1, ")": -1}.get(ch, 0)
        if depth == 0 and n < len(s) - 1:
            return s
    return s[1:-1]


def python_formulas(c: Contract) -> str:
    """scripts/pstlib/formulas.py: the formulas and the constants they read, as Python."""
    L = [f'"""{HEADER}', "", "The [formula] functions of rtl/contract.toml (pstlib.contract.formulas).", '"""', ""]
    used = [n for n in c.constants if any(n in _names(f.tree, "const") for f in c.formulas)]
    L += [f"{n} = {c.constants[n][0]}" for n in used]
    for f in c.formulas:
        L += ["", "", f"def {f.name}({', '.join(f.args)}) -> int:"]
        if f.doc:
            doc = textwrap.wrap(f.doc[:1].upper() + f.doc[1:] + ".", 92)
            L += [f'    """{doc[0]}'] + [f"    {x}" for x in doc[1:]]
            L[-1] += '"""'
        L.append(f"    return int({_strip_parens(emit_formula(f.tree, 'py', c))})")
    return "\n".join(L) + "\n"


def _formula_functions(c: Contract):
    """The formulas of a description as Python functions (python_formulas' text, executed once
    per description)."""
    if "_functions" not in c.__dict__:
        ns: dict = {}
        exec(compile(python_formulas(c), f"{c.path} [formula]", "exec"), ns)  # noqa: S102 (our own generator)
        c.__dict__["_functions"] = argparse.Namespace(**{f.name: ns[f.name] for f in c.formulas})
    return c.__dict__["_functions"]


def _names(t: tuple, kind: str) -> set[str]:
    """The names of `kind` ("const", "call", ...) a tree reads."""
    out = {t[1]} if t[0] == kind else set()
    for x in t[1:]:
        for y in (x if isinstance(x, list) else [x]):
            if isinstance(y, tuple):
                out |= _names(y, kind)
    return out


def _tables():
    c = load()
    enums = {(k.section, k.key): list(k.enum) for k in c.keys if k.kind == "enum"}
    fmax = {k.key: k.max_width for k in c.keys if k.kind == "format"}
    ranges = {(k.section, k.key): (k.values if k.kind == "values" else (k.lo, k.hi))
              for k in c.keys if k.kind in ("range", "values")}
    return enums, fmax, ranges, c.format_int, c.format_frac


ENUMS, FORMAT_MAX, RANGES, FORMAT_INT, FORMAT_FRAC = _tables()


# ---------------------------------------------------------------------------------------------
# Constraint expressions: C operators over parameter names and Enum.value.
# ---------------------------------------------------------------------------------------------
_TOKEN = re.compile(r"\s*(?:(\d+)|([A-Za-z_][A-Za-z0-9_]*)(?:\.([A-Za-z_][A-Za-z0-9_]*))?|(&&|\|\||==|!=|<=|>=|[-+*/%<>()!]))")


def _tokens(expr: str):
    pos, out = 0, []
    expr = expr.strip()
    while pos < len(expr):
        m = _TOKEN.match(expr, pos)
        if not m or m.end() == pos:
            raise ValueError(f"constraint {expr!r}: cannot read at {expr[pos:]!r}")
        out.append(m.groups())
        pos = m.end()
    return out


def translate(expr: str, lang: str, contract: Contract | None = None) -> str:
    """A constraint expression in Python ("py": names looked up in `v`), C++ ("cpp": v[Name])
    or SystemVerilog ("sv": parameter names, enums as pst_pkg::EnumValue)."""
    c = contract or load()
    enums = c.enum_of_param()
    names = set(c.param_names)
    out = []
    for num, name, member, op in _tokens(expr):
        if num:
            out.append(num)
        elif name and member:
            if name not in enums or member not in enums[name].enum:
                raise ValueError(f"constraint {expr!r}: unknown enum value {name}.{member}")
            idx = enums[name].enum.index(member)
            out.append({"py": str(idx), "cpp": str(idx), "sv": f"pst_pkg::{name}{camel(member)}"}[lang])
        elif name:
            if name not in names:
                raise ValueError(f"constraint {expr!r}: unknown parameter {name}")
            out.append({"py": f"v[{name!r}]", "cpp": f"v[{name}]", "sv": name}[lang])
        elif lang == "py":
            out.append({"&&": "and", "||": "or", "!": "not", "/": "//"}.get(op, op))
        else:
            out.append(op)
    return " ".join(out)


# ---------------------------------------------------------------------------------------------
# Profiles
# ---------------------------------------------------------------------------------------------
def _is_int(v) -> bool:
    return isinstance(v, int) and not isinstance(v, bool)


def validate(doc: dict, contract: Contract | None = None) -> list[str]:
    """Everything model/golden/profile.cpp and the RTL's assertions reject, as
    "FIELD: what is wrong" strings (empty list: the profile is valid)."""
    c = contract or load()
    bad = []
    for k in c.keys:
        sec = doc.get(k.section)
        if not isinstance(sec, dict):
            bad.append(f"{k.section}: missing table")
            continue
        if k.key not in sec:
            bad.append(f"{k.field}: missing")
            continue
        v = sec[k.key]
        if k.kind == "enum":
            if v not in k.enum:
                bad.append(f"{k.field}: unknown value {v!r} (expected {', '.join(k.enum)})")
        elif k.kind == "values":
            if not _is_int(v) or v not in k.values:
                bad.append(f"{k.field}: must be {', '.join(map(str, k.values[:-1]))} or {k.values[-1]} (is {v!r})")
        elif k.kind == "range":
            if not _is_int(v) or not k.lo <= v <= k.hi:
                bad.append(f"{k.field}: must be an integer in [{k.lo}, {k.hi}] (is {v!r})")
        else:
            if not isinstance(v, dict):
                bad.append(f"{k.field}: expected {{ int = I, frac = F }}")
                continue
            i, fr = v.get("int"), v.get("frac")
            if not _is_int(i) or not c.format_int[0] <= i <= c.format_int[1]:
                bad.append(f"{k.field}.int: must be an integer in [{c.format_int[0]}, {c.format_int[1]}] (is {i!r})")
            elif not _is_int(fr) or not c.format_frac[0] <= fr <= c.format_frac[1]:
                bad.append(f"{k.field}.frac: must be an integer in [{c.format_frac[0]}, {c.format_frac[1]}] (is {fr!r})")
            elif i + fr > k.max_width:
                bad.append(f"{k.field}: int + frac must be at most {k.max_width} (is {i + fr})")
    if bad:
        return bad
    v = dict(parameters(doc, c))
    for con in c.constraints:
        if not eval(translate(con.expr, "py", c), {}, {"v": v}):  # noqa: S307 (our own grammar)
            bad.append(f"{con.field}: {con.message}")
    return bad


def parameters(doc: dict, contract: Contract | None = None) -> list[tuple[str, int]]:
    """The RTL parameters of a (valid) profile in description order; enums as their index."""
    c = contract or load()
    out = []
    for k in c.keys:
        v = doc[k.section][k.key]
        if k.kind == "enum":
            out.append((k.params[0], k.enum.index(v)))
        elif k.kind == "format":
            out += [(k.params[0], v["int"]), (k.params[1], v["frac"])]
        else:
            out.append((k.params[0], v))
    return out


class ProfileError(ValueError):
    """str(): "PATH:LINE: FIELD: what is wrong" (LINE left out when unknown)."""

    def __init__(self, path, field, what, line=None):
        self.path, self.field, self.what, self.line = str(path), field, what, line
        super().__init__(f"{self.path}{f':{line}' if line else ''}: {field}: {what}")


def _line_of(text: str, field: str) -> int | None:
    """Line of a profile key ("noise.out_frac", "formats.coord.int") in the TOML text."""
    parts = field.split(".")
    section, key = parts[0], parts[1] if len(parts) > 1 else None
    current = None
    for n, line in enumerate(text.splitlines(), 1):
        s = line.split("#", 1)[0].strip()
        m = re.fullmatch(r"\[\s*([A-Za-z0-9_]+)\s*\]", s)
        if m:
            current = m.group(1)
            if key is None and current == section:
                return n
        elif current == section and key and re.match(rf"{re.escape(key)}\s*=", s):
            return n
    return None


def read_profile(path: str | Path, contract: Contract | None = None) -> dict:
    """Loads and validates a profile; raises ProfileError at its first problem."""
    try:
        text = Path(path).read_text()
    except OSError as e:
        raise ProfileError(path, "file", e.strerror or str(e)) from None
    try:
        doc = tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise ProfileError(path, "syntax", str(e)) from None
    bad = validate(doc, contract)
    if bad:
        field, what = bad[0].split(": ", 1)
        raise ProfileError(path, field, what, _line_of(text, field))
    return doc


# ---------------------------------------------------------------------------------------------
# Generators
# ---------------------------------------------------------------------------------------------
HEADER = "GENERATED by scripts/pstlib/contract.py from rtl/contract.toml: do not edit."


def _regs(c: Contract) -> list[tuple[str, dict]]:
    return [(n, r) for n, r in c.registers.items() if isinstance(r, dict)]


def _register_constants(c: Contract):
    """Per register, what both the SV package and the C++ header declare: (comment, CamelName,
    address, groups), a group being the (name, value) constants that C++ puts on one line."""
    for name, r in _regs(c):
        n = camel(name)
        groups = [[(f"Reg{n}{k.capitalize()}", r[k])] for k in ("count", "stride", "bits") if k in r]
        for f in r.get("fields", []):
            fn = camel(f["name"])
            if "lsb" in f:
                groups.append([(f"Reg{n}{fn}Lsb", f["lsb"]), (f"Reg{n}{fn}Width", f["width"])])
            else:
                groups.append([(f"Reg{n}{fn}", f["offset"]), (f"Reg{n}{fn}Count", f["count"])])
        yield f"{_address_text(name, r)}: {r['doc']}", n, r["addr"], groups


def _address_text(name: str, r: dict) -> str:
    a = f"0x{r['addr']:04x}"
    if name == "quadric":
        return f"{a} + k"
    if name == "octave":
        return f"{a} + {r['stride']} i + k"
    if name == "sat":
        return f"{a} + {r['stride']} e + c"
    if name in ("clut", "mip"):
        return f"{a} + e"
    return a


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


def _comment(prefix: str, text: str, width: int = 100, then: str | None = None) -> list[str]:
    return textwrap.wrap(text, width, initial_indent=prefix, subsequent_indent=prefix if then is None else then)


def sv_functions(c: Contract) -> list[str]:
    """The [formula] functions (Verilog-2001 style assignment to the function name: Yosys 0.23
    reads no `return` in a function)."""
    L = _comment("  // ", "Derived widths and cycle counts (rtl/contract.toml [formula]; the same functions are "
                 "constexpr in model/golden/contract.h and Python in scripts/pstlib/formulas.py). Call them as "
                 "pst_pkg::w_width(Log2Clut, WidthFrac).")
    calls = set().union(*(_names(f.tree, "call") for f in c.formulas)) if c.formulas else set()
    for b in sorted(calls & set(BUILTINS)):
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
    """(NAME, doc, [parameter]) per [rtl_params] group, then PROFILE (every parameter); a
    ValueError names a parameter the schema lacks or one two groups share."""
    known, seen, out = set(c.param_names), {}, []
    for g, spec in c.raw.get("rtl_params", {}).items():
        for p in spec["params"]:
            if p not in known:
                raise ValueError(f"rtl_params.{g}: {p} is not a profile parameter")
            if p in seen:
                raise ValueError(f"rtl_params.{g}: {p} is in rtl_params.{seen[p]} too")
            seen[p] = g
        out.append((g.upper(), spec.get("doc", ""), list(spec["params"])))
    return out + [("PROFILE", "every profile parameter, in schema order (pst_top; declaration only)",
                   c.param_names)]


def sv_params(c: Contract) -> str:
    """rtl/pst_params.svh: per parameter group, a declaration macro and a pass-through macro
    (Yosys 0.23 takes no struct parameter, so a group travels as a list)."""
    L = [f"// {HEADER}",
         "// pst_params: the profile's parameter groups (rtl/contract.toml [rtl_params]) as macros, so that",
         "// a module passing a group on declares it once: `PST_<GROUP>_PARAMS in its #( ... ) declares",
         "// `parameter int P = pst_pkg::PDefault` per parameter, `PST_<GROUP>_PASS in an instance's",
         "// #( ... ) passes `.P(P)`; add a comma when more parameters follow. Include after pst_pkg.sv.",
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
        L.append(f"constexpr int {b}_int(int a, int b) {{ return a {'>' if b == 'max' else '<'} b ? a : b; }}")
    for f in c.formulas:
        L += _comment("// ", f"{f.name}: {f.doc}") + _comment("//   = ", f.expr, then="//     ")
        args = ", ".join(f"int {cpp_arg(a)}" for a in f.args)
        L += [f"constexpr int {f.name}({args}) {{", f"    return {_strip_parens(emit_formula(f.tree, 'cpp', c))};", "}"]
    return L + [""]


def hardware_md_table(c: Contract) -> str:
    """The register map as a Markdown table (docs/HARDWARE.md's register-map section, written by
    scripts/gen_docs.py)."""
    L = ["| address | register |", "|---|---|"]
    for name, r in _regs(c):
        L.append(f"| {_address_text(name, r)} | {r['doc']} |")
    return "\n".join(L) + "\n"


def stage_cycles(doc: dict, c: Contract | None = None) -> dict[str, int]:
    """Cycles a fragment spends in each stage of a (valid) profile, from the contract's
    [formula] functions (scripts/pstlib/formulas.py; the golden model and pst_pkg have the same).
    The pipeline's clocks per pixel is the largest of them."""
    c = c or load()
    v = dict(parameters(doc, c))
    # The description's own formulas (not the generated file, which may be stale while
    # --write regenerates it).
    f = _formula_functions(c)
    qw, cw = v["QuadricInt"] + v["QuadricFrac"], v["CoordInt"] + v["CoordFrac"]
    dp = v["Datapath"]
    out = {"octave": f.octave_cycles(v["Octaves"], v["NoiseUnits"], v["NoiseSteps"], dp, v["NoiseRegs"],
                                            v["OctaveRegs"]),
           "quadric": f.quadric_cycles(dp, qw, cw, v["OctaveRegs"]),
           "width": f.width_cycles(dp, v["FilterNorm"], v["Log2Clut"], v["WidthFrac"]),
           "colour": f.colour_cycles(dp, v["ColourRegs"])}
    out["pixel"] = f.clocks_per_pixel(v["Octaves"], v["NoiseUnits"], v["NoiseSteps"], dp, v["NoiseRegs"],
                                             v["OctaveRegs"], qw, cw, v["FilterNorm"], v["Log2Clut"],
                                             v["WidthFrac"], v["ColourRegs"])
    return out


def cycles_md_table(c: Contract, root: Path) -> str:
    """Cycles per stage and per pixel of every profile in rtl/configs as a Markdown table
    (docs/HARDWARE.md's cycles section, written by scripts/gen_docs.py)."""
    L = ["| profile | octave stage [A] | serial quadric (in [A]) | filter width [B] | colour filter [C] | clocks per pixel |",
         "|---|---|---|---|---|---|"]
    for path in sorted((root / "rtl" / "configs").glob("*.toml")):
        with open(path, "rb") as f:
            n = stage_cycles(tomllib.load(f), c)
        L.append(f"| {path.stem} | {n['octave']} | {n['quadric'] if n['quadric'] > 1 else '-'} | {n['width']} | "
                 f"{n['colour']} | {n['pixel']} |")
    return "\n".join(L) + "\n"


def _key_type(c: Contract, k: Key) -> str:
    """A key's type and allowed values, as the profile reference shows them."""
    if k.kind == "enum":
        return "string: " + ", ".join(f"`{v}`" for v in k.enum)
    if k.kind == "values":
        return "integer: " + ", ".join(map(str, k.values))
    if k.kind == "range":
        return f"integer, {k.lo} .. {k.hi}"
    return (f"format `{{ int = I, frac = F }}`: I in {c.format_int[0]} .. {c.format_int[1]}, "
            f"F in {c.format_frac[0]} .. {c.format_frac[1]}, I + F <= {k.max_width}")


def _key_default(c: Contract, k: Key, doc: dict) -> str:
    v = doc.get(k.section, {}).get(k.key)
    if v is None:
        return "-"
    if k.kind == "format":
        return f"`{{ int = {v.get('int')}, frac = {v.get('frac')} }}`"
    return f"`{v}`" if isinstance(v, str) else str(v)


def profile_keys_md(c: Contract, root: Path) -> str:
    """Every key a profile file (rtl/configs/*.toml) holds: section, key, RTL parameter(s), type and
    allowed values, the value of the defaults profile (the RTL parameters' defaults) and what it
    means; then the cross-constraints. docs/PROFILES.md's profile-keys section, written by
    scripts/gen_docs.py."""
    dflt = {}
    if c.defaults:
        with open(root / c.defaults, "rb") as f:
            dflt = tomllib.load(f)
    L = []
    for section in ("pipeline", "noise", "filter", "formats"):
        L += [f"### [{section}]", "",
              f"| key | RTL parameter | type and range | {Path(c.defaults).stem if c.defaults else 'default'} | meaning |",
              "|---|---|---|---|---|"]
        for k in c.keys:
            if k.section != section:
                continue
            params = ", ".join(f"`{p}`" for p in k.params)
            L.append(f"| `{k.key}` | {params} | {_cell(_key_type(c, k))} | {_key_default(c, k, dflt)} | "
                     f"{_cell(k.doc)} |")
        L.append("")
    L += ["### Cross-constraints", "",
          "Checked after every key is in its range; the error names the key in the first column.", "",
          "| key | rule | message |", "|---|---|---|"]
    for con in c.constraints:
        L.append(f"| `{con.field}` | `{_cell(con.expr)}` | {_cell(con.message)} |")
    return "\n".join(L) + "\n"


def _cell(text: str) -> str:
    return " ".join(text.split()).replace("|", "\\|")


GENERATED = {
    "rtl/pst_pkg.sv": lambda c, cur, root: sv_package(c),
    "rtl/pst_profile_checks.svh": lambda c, cur, root: sv_checks(c),
    "rtl/pst_params.svh": lambda c, cur, root: sv_params(c),
    "model/golden/contract.h": lambda c, cur, root: cpp_header(c),
    "scripts/pstlib/formulas.py": lambda c, cur, root: python_formulas(c),
}


def generate(root: Path, contract: Contract | None = None) -> dict[str, str]:
    """{relative path: text it should have} for every generated file under `root`."""
    c = contract or load(root / "rtl" / "contract.toml")
    out = {}
    for rel, gen in GENERATED.items():
        p = root / rel
        cur = p.read_text() if p.exists() else ""
        out[rel] = gen(c, cur, root)
    return out


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--root", type=Path, default=ROOT, help="repository root (default: this one)")
    g = ap.add_mutually_exclusive_group(required=True)
    g.add_argument("--write", action="store_true", help="regenerate the generated files")
    g.add_argument("--check", action="store_true", help="exit 1 if a generated file is stale")
    a = ap.parse_args(argv)
    try:
        texts = generate(a.root)
    except (OSError, ValueError, KeyError, tomllib.TOMLDecodeError) as e:
        print(f"error: {a.root / 'rtl/contract.toml'}: {e}", file=sys.stderr)
        return 2
    stale = []
    for rel, text in texts.items():
        p = a.root / rel
        if (p.read_text() if p.exists() else None) != text:
            stale.append(rel)
            if a.write:
                p.write_text(text)
    if a.check and stale:
        for rel in stale:
            print(f"error: {rel}: stale (regenerate: /usr/bin/python3 scripts/pstlib/contract.py --write)",
                  file=sys.stderr)
        return 1
    for rel in stale:
        print(f"wrote {rel}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
