"""The Python writer: scripts/pstlib/formulas.py (the [formula] functions; pstlib.contract runs the
same text for its own description, stage_cycles)."""
from __future__ import annotations

import textwrap

from ..contract import Contract, _names
from .common import HEADER, _strip_parens, emit_formula

def python_formulas(c: Contract) -> str:
    """scripts/pstlib/formulas.py: the formulas and the constants they read, as Python."""
    L = [f'"""{HEADER}', "", "The [formula] functions of rtl/contract.toml (pstlib.contract.formulas).", '"""', ""]
    used = [n for n in c.constants if any(n in _names(f.tree, "const") for f in c.formulas)]
    L += [f"{n} = {c.constants[n][0]}" for n in used]
    if any("clog2" in _names(f.tree, "call") for f in c.formulas):
        L += ["", "", "def clog2_int(a) -> int:", '    """The least b with 2^b >= a (SystemVerilog\'s $clog2)."""',
              "    return max(a - 1, 0).bit_length()"]
    for f in c.formulas:
        L += ["", "", f"def {f.name}({', '.join(f.args)}) -> int:"]
        if f.doc:
            doc = textwrap.wrap(f.doc[:1].upper() + f.doc[1:] + ".", 92)
            L += [f'    """{doc[0]}'] + [f"    {x}" for x in doc[1:]]
            L[-1] += '"""'
        L.append(f"    return int({_strip_parens(emit_formula(f.tree, 'py', c))})")
    return "\n".join(L) + "\n"
