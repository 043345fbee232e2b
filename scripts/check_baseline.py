#!/usr/bin/python3
"""Checks the main job's silicon and quality figures against scripts/synth/baseline.json.

The command's code: pstlib/cli/check_baseline.py (`python3 -m pstlib.cli.check_baseline` from scripts/ runs it
too); `--help` says everything."""
import sys

from pstlib.cli.check_baseline import main

if __name__ == "__main__":
    sys.exit(main())
