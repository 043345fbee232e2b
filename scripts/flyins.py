#!/usr/bin/python3
"""Antialiasing in motion on held-out fly-ins (training and validation sets of seeded fly-ins).

The command's code: pstlib/cli/flyins.py (`python3 -m pstlib.cli.flyins` from scripts/ runs it
too); `--help` says everything."""
import sys

from pstlib.cli.flyins import main

if __name__ == "__main__":
    sys.exit(main())
