"""Logic equivalence of the RTL and its synthesized netlist (scripts/lec.py): miters built by
Yosys (miter.py), decided by ABC (prove.py)."""
