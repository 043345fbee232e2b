"""Markdown renderer of the report's data (report_data.Report): out/report.md."""
from .data import Report, Table


def table(t: Table) -> str:
    lines = ["| " + " | ".join(t.columns) + " |", "|" + "---|" * len(t.columns)]
    for r in range(len(t.rows)):
        cells = []
        for c, name in enumerate(t.columns):
            links = t.links[r].get(name) if r < len(t.links) else None
            text = t.cell(r, c)
            if links:
                extra = " ".join(f"[{label}]({path})" for label, path in links)
                text = f"{text} {extra}".strip() if text not in ("", "-") else extra
            cells.append(text)
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def included(inc) -> str:
    out = f"## {inc.title}\n\n"
    if inc.text is None:
        return out + (f"({inc.missing})\n\n" if inc.missing else "")
    return out + inc.text + "\n\n"


def top(rep: Report) -> str:
    """The main job's verdicts (the regression's and the baseline check's side by side, the
    baseline's moved figures under them, where the silicon figures came from) and the
    provenance."""
    from .verdicts import verdicts
    from . import provenance
    out = []
    if rep.main_job:
        reg, base, silicon = verdicts(rep)
        out.append(" · ".join(f"**{v.label}: {v.status}**" + (f" ({v.detail})" if v.detail else "")
                              for v in (reg, base)) + "\n")
        if base.items:
            out.append("\n".join(f"- {i}" for i in base.items) + "\n")
        out.append(f"{silicon.label}: {silicon.status}" + (f" ({silicon.detail})" if silicon.detail else "") + ".\n")
    if rep.provenance:
        out.append(f"Provenance: {provenance.line(rep.provenance)}.\n")
    return "\n".join(out)


def render(rep: Report, image_links) -> str:
    """`image_links(run)`: the (label, path) image links of a regression row."""
    from .data import regress_table, gate_summary
    out = [f"# {rep.title}\n", top(rep),
           "Contents: RTL regression (bit-exact against the golden model, error against the double "
           "reference), gate counts (Yosys), Figure 11 (reference | full | reduced), Figure 10 "
           "(texture-coordinate precision), the default precision sweep, the reference renders. "
           "The same data with image viewers: [report.html](report.html).\n"]
    out.append("## RTL regression\n")
    if not rep.regress_ran:
        out.append("(not run)\n")
    else:
        failed = rep.failed_runs
        out.append(f"**{'FAILED' if failed else 'PASSED'}**: {len(rep.runs)} runs, {len(failed)} with mismatches "
                   "against the golden model. Error figures: RTL image against the double reference over RGB. "
                   "Failures first.\n")
        out.append(table(regress_table(rep.runs, image_links)))
        if rep.notes:
            out.append("Driver notes (what the hardware does differently from the scene's request):\n")
            out.append("\n".join(f"- {n}" for n in rep.notes) + "\n")
    summary = gate_summary(rep.gates, rep.root, rep.runs)
    if summary is not None:
        out.append("## Gates and timing: summary\n")
        out.append(table(summary))
    for g in rep.gates:
        out.append(included(g))
    for f in rep.figures + rep.sweeps + rep.extras:
        out.append(included(f))
    out.append("## Reference renders\n")
    if rep.references is None:
        out.append("(none)\n")
    else:
        out.append("Ground truth: n x n jittered, unfiltered samples per pixel. RMS over RGB in [0, 1].\n")
        out.append(table(rep.references))
    return "\n".join(out)
