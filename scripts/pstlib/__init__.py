"""pst's Python library: small modules shared by the scripts (contract: the hardware contract
and profile schema of rtl/contract.toml; report_*: the report; flicker: the flicker table and
plot of `pst animate` runs; the sweep's and the figures' modules: docs/ARCHITECTURE.md). Put
scripts/ on sys.path and `from pstlib import contract`."""
