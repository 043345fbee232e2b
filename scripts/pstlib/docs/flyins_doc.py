"""The fly-in table (docs/VERIFICATION.md section flyins-table) from docs/data/flyins.json, which
`scripts/flyins.py --record` writes (every figure measured by that run, none typed)."""
from pathlib import Path

from ..validation import flyin_table
from . import docgen

SOURCE = Path("docs/data/flyins.json")


def load(root: Path) -> dict:
    return docgen.load_record(root, SOURCE, "splits", "scripts/flyins.py --record")


def markdown(root: Path) -> str:
    d = load(root)
    L = [f"Measured by `{d['command']} --record` (commit {d.get('commit', '?')}). {flyin_table.CELLS}", ""]
    for c in d["splits"].values():
        L += [f"{flyin_table.heading(c)}:", "", flyin_table.main_table(c)]
    return "\n".join(L)
