"""Is a profile good enough: the held-out validation set (valset) from the scene generator
(scenegen), the rule of acceptance (acceptance), the set through every profile (validate,
scripts/validate.py), the silicon and quality baseline (baseline) and the Verilator coverage
summary (coverage)."""
