#!/usr/bin/python3
"""Logic equivalence of a profile's RTL and its synthesized netlist, module by module.

The command's code: pstlib/cli/lec.py (`python3 -m pstlib.cli.lec` from scripts/ runs it
too); `--help` says everything."""
import sys

from pstlib.cli.lec import main

if __name__ == "__main__":
    sys.exit(main())
