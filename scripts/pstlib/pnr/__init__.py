"""Place and route of a profile's blocks with Debian's qflow (scripts/pnr.py)."""
