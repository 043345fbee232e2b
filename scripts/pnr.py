#!/usr/bin/env python3
"""Place and route of one hardware profile, block by block, with Debian's qflow (OSU 0.18 µm).

The command's code: pstlib/cli/pnr.py (`python3 -m pstlib.cli.pnr` from scripts/ runs it
too); `--help` says everything."""
import sys

from pstlib.cli.pnr import main

if __name__ == "__main__":
    sys.exit(main())
