#!/usr/bin/python3
"""Every generated section of the docs, and the check that no figure is typed by hand.

The command's code: pstlib/cli/gen_docs.py (`python3 -m pstlib.cli.gen_docs` from scripts/ runs it
too); `--help` says everything."""
import sys

from pstlib.cli.gen_docs import main

if __name__ == "__main__":
    sys.exit(main())
