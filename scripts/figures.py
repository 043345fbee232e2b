#!/usr/bin/python3
"""The paper's Figures 10 and 11 from the simulator's images.

The command's code: pstlib/cli/figures.py (`python3 -m pstlib.cli.figures` from scripts/ runs it
too); `--help` says everything."""
import sys

from pstlib.cli.figures import main

if __name__ == "__main__":
    sys.exit(main())
