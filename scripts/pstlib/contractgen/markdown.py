"""The Markdown writer: the docs' tables made from the contract (docs/HARDWARE.md's register map
and cycles per stage, docs/PROFILES.md's profile keys), written into the docs by scripts/gen_docs.py."""
from __future__ import annotations

import tomllib
from pathlib import Path

from ..contract import Contract, Key, stage_cycles
from .common import _address_text, _regs

def hardware_md_table(c: Contract) -> str:
    """The register map as a Markdown table (docs/HARDWARE.md's register-map section, written by
    scripts/gen_docs.py)."""
    L = ["| address | register |", "|---|---|"]
    for name, r in _regs(c):
        L.append(f"| {_address_text(name, r)} | {r['doc']} |")
    return "\n".join(L) + "\n"


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
