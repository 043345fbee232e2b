#!/usr/bin/env python3
"""Flicker table and plots of `pst animate --truth N` runs.

The command's code: pstlib/cli/flicker.py (`python3 -m pstlib.cli.flicker` from scripts/ runs it
too); `--help` says everything."""
import sys

from pstlib.cli.flicker import main

if __name__ == "__main__":
    sys.exit(main())
