#!/usr/bin/python3
"""Proves pst_mul_booth's simulation form equal to its synthesis form for every width used.

The command's code: pstlib/cli/mul_proof.py (`python3 -m pstlib.cli.mul_proof` from scripts/ runs it
too); `--help` says everything."""
import sys

from pstlib.cli.mul_proof import main

if __name__ == "__main__":
    sys.exit(main())
