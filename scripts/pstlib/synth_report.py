"""The side-by-side silicon table of the synthesized profiles (scripts/synth.py's
out/synth/<profile>.json), for the report's gate section."""


def _n(v, fmt="{:,}"):
    return "-" if v is None else fmt.format(v)


def side_by_side(results: list) -> str:
    """Markdown: one column per profile (logic GE, memories, total area, Fmax, Mpixel/s,
    area-time, the paper's gate count, the critical path of each stage)."""
    if not results:
        return ""
    cols = [r["profile"] for r in results]
    rows = []

    def row(label, f):
        rows.append(f"| {label} | " + " | ".join(f(r) for r in results) + " |")

    row("logic GE (OSU018)", lambda r: _n(r.get("logic_ge")))
    row("paper's gate count", lambda r: _n(r.get("paper_gates")))
    row("logic GE, old basis (cells.lib)", lambda r: _n(r.get("logic_ge_cells_lib")))
    row("memories GE (cell-built)", lambda r: _n(r.get("memory_ge")))
    row("ROM / RAM kbit", lambda r: f"{r.get('rom_bits', 0) / 1024:,.1f} / {r.get('ram_bits', 0) / 1024:,.1f}")
    row("total area", lambda r: f"{_n(r.get('total_ge'))} GE, {_n(r.get('total_area_mm2'), '{:.3f}')} mm^2")
    row("flip-flops", lambda r: _n(r.get("flip_flops")))
    row("clocks per pixel", lambda r: _n(r.get("clocks_per_pixel")))
    row("Fmax (OpenSTA)", lambda r: _n((r.get("timing") or {}).get("fmax_mhz"), "{:.1f} MHz"))
    row("Mpixel/s", lambda r: _n((r.get("throughput") or {}).get("mpixel_s"), "{:.2f}"))
    row("640x480 60 Hz depth 2 (36.9 Mpixel/s)",
        lambda r: "-" if not r.get("throughput") else ("meets" if r["throughput"]["meets_realtime"] else "misses"))
    row("area-time (logic GE x clocks/pixel)", lambda r: _n((r.get("throughput") or {}).get("area_time_ge_clocks")))
    row("area-time (total GE x clocks/pixel)",
        lambda r: _n((r.get("throughput") or {}).get("area_time_total_ge_clocks")))
    stages = []
    for r in results:
        for s in (r.get("timing") or {}).get("stages", []):
            if s["stage"] not in stages:
                stages.append(s["stage"])

    def stage_cell(r, name):
        for s in (r.get("timing") or {}).get("stages", []):
            if s["stage"] == name:
                return f"{s['min_period_ns']:.2f} ns"
        return "-"

    for name in stages:
        row(f"critical path: {name}", lambda r, name=name: stage_cell(r, name))
    row("worst path", lambda r: "-" if not r.get("timing") else
        f"{r['timing']['worst']['stage']}: `{r['timing']['worst']['startpoint']}` -> "
        f"`{r['timing']['worst']['endpoint']}`")
    head = ["| figure | " + " | ".join(cols) + " |", "|---|" + "---:|" * len(cols)]
    note = ("Critical path per stage: the clock period the stage needs (OpenSTA, OSU 0.18 um typical, "
            "scripts/synth/pst.sdc); the target is 10 ns (100 MHz). Details per profile below.\n")
    return "\n".join(head + rows) + "\n\n" + note
