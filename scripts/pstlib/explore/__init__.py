"""Exploring the design space: one Point (point), one result store with one reuse rule (store),
the evaluation of a point by golden renders and area (evaluate), the RTL check of chosen points
(rtlcheck), the local and SLURM backends (local, slurm), and two strategies over them: the sweep,
one knob at a time (sweep, sweep_run, sweep_report), and the search, the greedy walk (search,
search_run, search_report)."""
