#!/usr/bin/python3
"""Simulation speed per verilated profile (RTL cycles/s and pixels/s, the golden model's pixels/s).

The command's code: pstlib/cli/bench.py (`python3 -m pstlib.cli.bench` from scripts/ runs it
too); `--help` says everything."""
import sys

from pstlib.cli.bench import main

if __name__ == "__main__":
    sys.exit(main())
