"""The report (data: out/ collected once, tables: its tables; md and html: the two renderings), its
provenance, the silicon tables (README, HARDWARE.md, the report) and the simulation benchmark's
table (bench)."""
