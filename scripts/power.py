#!/usr/bin/python3
"""Power and energy per pixel of one hardware profile from simulated activity.

The command's code: pstlib/cli/power.py (`python3 -m pstlib.cli.power` from scripts/ runs it
too); `--help` says everything."""
import sys

from pstlib.cli.power import main

if __name__ == "__main__":
    sys.exit(main())
