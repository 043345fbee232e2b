#!/usr/bin/python3
"""Profiles judged on the held-out validation set, scene by scene against full_exact.

The command's code: pstlib/cli/validate.py (`python3 -m pstlib.cli.validate` from scripts/ runs it
too); `--help` says everything."""
import sys

from pstlib.cli.validate import main

if __name__ == "__main__":
    sys.exit(main())
