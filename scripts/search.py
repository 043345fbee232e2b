#!/usr/bin/python3
"""Design-space search: the least logic area at a quality, throughput and clock target.

The command's code: pstlib/cli/search.py (`python3 -m pstlib.cli.search` from scripts/ runs it
too); `--help` says everything."""
import sys

from pstlib.cli.search import main

if __name__ == "__main__":
    sys.exit(main())
