"""The fly-in table (docs/VERIFICATION.md section flyins-table) from docs/data/flyins.json, which
`scripts/flyins.py --record` writes (every figure measured by that run, none typed)."""
import json
from pathlib import Path

from ..validation import flyin_table

SOURCE = Path("docs/data/flyins.json")


def load(root: Path) -> dict:
    path = root / SOURCE
    if not path.exists():
        raise ValueError(f"{SOURCE}: missing (scripts/flyins.py --record)")
    d = json.loads(path.read_text())
    if not isinstance(d.get("splits"), dict) or not d["splits"]:
        raise ValueError(f"{SOURCE}: splits: missing")
    return d


def markdown(root: Path) -> str:
    d = load(root)
    L = [f"Measured by `{d['command']} --record` (commit {d.get('commit', '?')}). {flyin_table.CELLS}", ""]
    for c in d["splits"].values():
        L += [f"{flyin_table.heading(c)}:", "", flyin_table.main_table(c)]
    return "\n".join(L)
