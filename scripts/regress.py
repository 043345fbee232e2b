#!/usr/bin/python3
"""`pst regress` in shards, on local workers or as a SLURM job array, merged into one result.

The command's code: pstlib/cli/regress.py (`python3 -m pstlib.cli.regress` from scripts/ runs it
too); `--help` says everything."""
import sys

from pstlib.cli.regress import main

if __name__ == "__main__":
    sys.exit(main())
