"""The power flow: activity of the verilated RTL\x27s traces onto the synthesized netlist, OpenSTA\x27s
per-cell power, energy per pixel (scripts/power.py; docs/POWER.md)."""
