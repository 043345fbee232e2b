#!/usr/bin/env python3
"""The ground-truth table of the filter options: stills and animated sequences against the truth.

The command's code: pstlib/cli/fidelity.py (`python3 -m pstlib.cli.fidelity` from scripts/ runs it
too); `--help` says everything."""
import sys

from pstlib.cli.fidelity import main

if __name__ == "__main__":
    sys.exit(main())
