"""The files generated from the hardware contract (rtl/contract.toml, read by pstlib.contract):
one writer per target language (sv.py, cpp.py, python.py, markdown.py; common.py what they
share). `cd scripts && /usr/bin/python3 -m pstlib.contractgen --check` (ctest contract_stale) exits
1 naming each stale generated file, `--write [--root DIR]` regenerates them (rtl/CMakeLists.txt
does at configure time). The Markdown tables are written into the docs by scripts/gen_docs.py.

  generate(root[, c]) -> {relative path: text}   every generated file's text
  GENERATED      {relative path: writer} of every generated file"""
from __future__ import annotations

from pathlib import Path

from ..contract import Contract, load
from .cpp import cpp_header
from .markdown import cycles_md_table, hardware_md_table, profile_keys_md  # noqa: F401  (the docs' tables)
from .python import python_formulas
from .sv import sv_checks, sv_package, sv_params

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
