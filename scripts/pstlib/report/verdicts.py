"""The verdicts at the top of the report (pstlib.report.data collects them): the baseline check,
the regression and the silicon, each PASSED, FAILED, ERROR or not run, with why."""
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Optional

if TYPE_CHECKING:
    from .data import Report


@dataclass
class Verdict:
    """One line of the report's top: `label`: `status` (PASSED, FAILED, ERROR, not run, or a
    source), `detail` in parentheses, `items` listed under it (the moved figures)."""
    label: str
    status: str
    detail: str = ""
    items: list = field(default_factory=list)

    @property
    def ok(self):
        """True (passed), False (failed or error), None (neither: not run, a source)."""
        return {"PASSED": True, "FAILED": False, "ERROR": False}.get(self.status)


def _fmt_value(v) -> str:
    return f"{v:g}" if isinstance(v, float) else str(v)


def baseline_verdict(bc: Optional[dict]) -> Verdict:
    """The baseline check's line from its --json result (None: not run)."""
    if bc is None:
        return Verdict("Baseline", "not run")
    tol = bc.get("tolerance")
    tol_text = f"{100 * tol:g} %" if isinstance(tol, (int, float)) else "the tolerance"
    status = bc.get("status")
    if status == "pass":
        return Verdict("Baseline", "PASSED", f"{bc.get('figures_checked', 0)} figures within {tol_text}")
    if status != "fail":
        msgs = [m for m in bc.get("messages", []) if m.startswith("error")] or bc.get("messages", [])
        return Verdict("Baseline", "ERROR", msgs[-1] if msgs else "the check did not finish")
    parts, items = [], []
    moved = bc.get("moved", [])
    if moved:
        parts.append(f"{len(moved)} figures moved beyond {tol_text}")
        for m in moved:
            ch = m.get("change")
            change = f"{100 * ch:+.1f} %" if isinstance(ch, (int, float)) else "added/removed/changed"
            items.append(f"{m.get('figure')}: {_fmt_value(m.get('baseline'))} -> {_fmt_value(m.get('current'))} "
                         f"({change})")
    fails = bc.get("signoff_failures", [])
    if fails:
        parts.append(f"{len(fails)} sign-off failures")
        items += [f"{f.get('profile')}: sign-off check failed: {f.get('error')}" for f in fails]
    other = bc.get("tool_mismatches", [])
    if other:
        parts.append(f"{len(other)} profiles synthesized with other tools than the baseline's")
        items += [f"{t.get('profile')}: synthesized with {t.get('tools')}, the baseline with "
                  f"{t.get('baseline_tools')}" for t in other]
    if not parts and bc.get("stale"):
        parts.append(f"{len(bc['stale'])} inputs changed since the baseline")
        items += list(bc["stale"])
    return Verdict("Baseline", "FAILED", "; ".join(parts) or "see the main job's log", items)


def regression_verdict(rep: "Report") -> Verdict:
    if not rep.regress_ran:
        return Verdict("Regression", "not run")
    failed = rep.failed_runs
    if failed:
        return Verdict("Regression", "FAILED", f"{len(failed)} of {len(rep.runs)} runs with mismatches")
    return Verdict("Regression", "PASSED", f"{len(rep.runs)} runs")


def silicon_verdict(rep: "Report") -> Verdict:
    """Where the silicon figures came from: the record (out/synth/source.json of
    `check_baseline.py --restore`), this run's synthesis (no source.json), or nowhere."""
    src = rep.silicon_source
    if src and src.get("source") == "record":
        return Verdict("Silicon figures", "from the silicon record",
                       f"inputs unchanged since the baseline, digest {src.get('digest', '?')}")
    if src and src.get("source") == "none":
        stale = src.get("stale") or []
        return Verdict("Silicon figures", "not from the record",
                       "the inputs changed since the baseline: " + "; ".join(stale[:5])
                       + (f" (and {len(stale) - 5} more)" if len(stale) > 5 else "")
                       + "; synthesize again: scripts/run.sh --synth")
    if any(g.data for g in rep.gates):
        return Verdict("Silicon figures", "synthesized in this run")
    return Verdict("Silicon figures", "none", "not synthesized")


def verdicts(rep: "Report") -> list:
    """The report's top: the regression's and the baseline check's results side by side, then
    where the silicon figures came from."""
    return [regression_verdict(rep), baseline_verdict(rep.baseline_check), silicon_verdict(rep)]


def verdict_text(v: Verdict) -> str:
    return f"{v.label}: {v.status}" + (f" ({v.detail})" if v.detail else "")
