"""The power flow: activity of the verilated RTL's traces onto the synthesized netlist, OpenSTA's
per-cell power, energy per pixel (scripts/power.py; docs/POWER.md)."""
