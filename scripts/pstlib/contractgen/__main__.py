"""`python3 -m pstlib.contractgen --check | --write [--root DIR]` (pstlib.contractgen)."""
from __future__ import annotations

import argparse
import sys
import tomllib
from pathlib import Path

from ..paths import ROOT
from .. import contractgen
from . import generate

def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=contractgen.__doc__.split("\n")[0])
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
            print(f"error: {rel}: stale (regenerate: cd scripts && /usr/bin/python3 -m pstlib.contractgen --write)",
                  file=sys.stderr)
        return 1
    for rel in stale:
        print(f"wrote {rel}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
