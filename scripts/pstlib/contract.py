"""The hardware contract (rtl/contract.toml), read: profile schema, register map, fixed constants.

One description, read here, is the profile schema of every script and the source of the
generated files each other side uses (rtl/pst_pkg.sv, rtl/pst_profile_checks.svh,
rtl/pst_params.svh, model/golden/contract.h, scripts/pstlib/formulas.py), which the writers of
pstlib.contractgen make from it (one per target language: sv, cpp, python, markdown). This
module is the parser; the silicon baseline and the multiplier proof digest it (their records
name scripts/pstlib/contract.py), the writers they do not.

API (`from pstlib import contract`, with scripts/ on sys.path):
  load(path=None) -> Contract          the description (cached; default rtl/contract.toml)
  ENUMS          {(section, key): [names]}   profile enums, names in index order
  FORMAT_MAX     {format name: max int + frac}
  FORMAT_INT, FORMAT_FRAC   (lo, hi) of a format's int and frac bits
  RANGES         {(section, key): (lo, hi) or tuple of allowed values}
  param_name(section, key[, part])    RTL parameter name: ("noise", "out_frac") -> NoiseOutFrac
  parse_formula(expr, args, c)         a [formula] expression as a tree (pstlib.contractgen.common
                                       emit_formula writes it as SystemVerilog, C++ or Python)
  translate(expr, lang[, c])           a constraint expression as "py", "cpp" or "sv" text
  validate(doc) -> [str]               what the golden model and the RTL reject, each
                                       "FIELD: what is wrong" (empty: valid); doc as tomllib loads it
  parameters(doc) -> [(Name, int)]     the RTL parameters of a valid profile (enums as indices)
  read_profile(path) -> dict           tomllib-loaded and validated; raises ProfileError whose str()
                                       is "PATH:LINE: FIELD: what is wrong"
  stage_cycles(doc) -> {stage: cycles}  cycles per stage and per pixel of a profile (docs table)
  formulas       the [formula] functions (w_width, octave_cycles, ...), generated into
                 scripts/pstlib/formulas.py (also constexpr in contract.h, functions in pst_pkg)

The generated files: `cd scripts && /usr/bin/python3 -m pstlib.contractgen --check | --write`
(ctest contract_stale; rtl/CMakeLists.txt PST_CONTRACT_GEN).
"""
from __future__ import annotations

import argparse
import functools
import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

from . import formulas  # noqa: F401  (contract.formulas: the generated functions)
from .paths import ROOT

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
# Built-in functions and their argument counts: max(a, b), min(a, b), and clog2(a) = the least b
# with 2^b >= a (SystemVerilog's $clog2; clog2(Octaves + 1): the bits of a count 0..Octaves).
BUILTINS = {"max": 2, "min": 2, "clog2": 1}


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


def _formula_functions(c: Contract):
    """The formulas of a description as Python functions (python_formulas' text, executed once
    per description)."""
    if "_functions" not in c.__dict__:
        from .contractgen.python import python_formulas   # the Python writer (it imports this module)
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
