#!/usr/bin/python3
"""Precision sweep: gates against image quality, one knob at a time around a base profile.

The command's code: pstlib/cli/sweep.py (`python3 -m pstlib.cli.sweep` from scripts/ runs it
too); `--help` says everything."""
import sys

from pstlib.cli.sweep import main

if __name__ == "__main__":
    sys.exit(main())
