#!/usr/bin/python3
"""The main job's report, and the page of one hardware run.

The command's code: pstlib/cli/report.py (`python3 -m pstlib.cli.report` from scripts/ runs it
too); `--help` says everything."""
import sys

from pstlib.cli.report import main

if __name__ == "__main__":
    sys.exit(main())
