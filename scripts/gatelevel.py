#!/usr/bin/python3
"""Gate-level simulation of a profile's synthesized netlist: pstlib.gatelevel (its --help)."""
import sys

from pstlib.gatelevel.__main__ import main

if __name__ == "__main__":
    sys.exit(main())
