"""Energy per pixel of a design point that was never simulated: the measured energy density of a
named profile (docs/data/power.json, scripts/power.py --record) scaled by the point's logic area and
clocks per pixel. What the design search reports beside area (area x clocks/pixel x energy).

The model (one line): a point's energy per pixel

    E = d_ref * GE * C,    d_ref = E_ref / (GE_ref * C_ref)   [pJ per logic GE per clock]

with GE its logic gate equivalents (the search's per-module synthesis), C its clocks per pixel (the
contract's cycle formula) and d_ref the density of the reference profile: the measured profile with
the same clocks per pixel when there is one (the class's start profile in the search), else the one
nearest in log(clocks per pixel). The density carries everything the point does not change: the
activity of the paper scenes and random textures the record was measured on, the share of the
flip-flops and the ROM model, the corner. It does not follow a change of activity (a cut that makes
a unit idle more often) or of the memories (the search counts logic only). How far it is from a
measurement: `leave_one_out` estimates every measured profile from the nearest other one, and the
generated table (docs/POWER.md section energy-estimate) quotes the errors.
"""
import dataclasses
import json
import math
import pathlib

from ..paths import ROOT

POWER_RECORD = pathlib.Path("docs/data/power.json")
SYNTH_RECORDS = pathlib.Path("scripts/synth/records")


@dataclasses.dataclass(frozen=True)
class Reference:
    profile: str
    pj_per_pixel: float        # measured, mean over the record's workloads
    clocks_per_pixel: int
    logic_ge: int              # the synthesis record's logic GE (pre-layout)

    @property
    def density(self) -> float:
        """pJ per logic GE per clock."""
        return self.pj_per_pixel / (self.logic_ge * self.clocks_per_pixel)


def references(root: pathlib.Path = ROOT) -> dict:
    """Every profile with both a power record and a synthesis record: name -> Reference."""
    path = root / POWER_RECORD
    if not path.exists():
        return {}
    power = json.loads(path.read_text()).get("profiles", {})
    out = {}
    for name, p in sorted(power.items()):
        rec = root / SYNTH_RECORDS / f"{name}.json"
        if not rec.exists():
            continue
        syn = json.loads(rec.read_text())
        s = p["summary"]
        cpp = s.get("clocks_per_pixel") or syn.get("clocks_per_pixel")
        if not cpp or not syn.get("logic_ge") or not s.get("pj_per_pixel"):
            continue
        out[name] = Reference(name, float(s["pj_per_pixel"]), int(cpp), int(syn["logic_ge"]))
    return out


def nearest(refs: dict, cpp: int, prefer: str = "", exclude: str = "") -> Reference | None:
    """The reference for a point of CPP clocks per pixel: PREFER when measured and of the same
    clocks per pixel, else the measured profile of least |log(C / C_ref)| (ties: the larger
    logic area, then the name), EXCLUDE left out."""
    cands = [r for n, r in refs.items() if n != exclude]
    if not cands or cpp <= 0:
        return None
    if prefer in refs and prefer != exclude and refs[prefer].clocks_per_pixel == cpp:
        return refs[prefer]
    return min(cands, key=lambda r: (abs(math.log(cpp / r.clocks_per_pixel)), -r.logic_ge, r.profile))


def estimate_pj(logic_ge: float, cpp: int, ref: Reference) -> float:
    """E = d_ref * GE * C (pJ per pixel)."""
    return ref.density * logic_ge * cpp


def figure_of_merit(logic_ge: float, cpp: int, pj: float) -> float:
    """Area x clocks/pixel x energy, in GE x clocks x nJ (lower is better)."""
    return logic_ge * cpp * pj / 1000.0


def leave_one_out(refs: dict) -> list:
    """Every measured profile estimated from the nearest other one: rows of profile, reference,
    measured and estimated pJ/pixel and the relative error."""
    rows = []
    for name, r in refs.items():
        ref = nearest(refs, r.clocks_per_pixel, exclude=name)
        if ref is None:
            continue
        est = estimate_pj(r.logic_ge, r.clocks_per_pixel, ref)
        rows.append({"profile": name, "reference": ref.profile, "clocks_per_pixel": r.clocks_per_pixel,
                     "logic_ge": r.logic_ge, "measured_pj": r.pj_per_pixel, "estimated_pj": est,
                     "error": est / r.pj_per_pixel - 1.0})
    return rows


def markdown(root: pathlib.Path) -> str:
    """docs/POWER.md section energy-estimate: the densities and the leave-one-out errors."""
    refs = references(root)
    if not refs:
        raise ValueError(f"{root / POWER_RECORD}: no profile with both a power and a synthesis record")
    L = ["The design search's energy per pixel is an estimate (scripts/pstlib/power/estimate.py): the "
         "measured energy density of the reference profile (pJ per logic GE per clock, from the table above and "
         "the synthesis record) times the point's logic GE and clocks per pixel. The reference is the measured "
         "profile of the same clocks per pixel (the class's start), else the nearest. Below, each measured "
         "profile estimated from the nearest other one: the model's error where it can be checked.", "",
         "| profile | clocks / pixel | logic GE (pre-layout) | density pJ / GE / clock | measured pJ/pixel | "
         "estimated from | estimate pJ/pixel | error |",
         "|---|---:|---:|---:|---:|---|---:|---:|"]
    loo = {r["profile"]: r for r in leave_one_out(refs)}
    for name, r in refs.items():
        e = loo.get(name)
        L.append(f"| {name} | {r.clocks_per_pixel} | {r.logic_ge:,} | {r.density:.4f} | {r.pj_per_pixel:,.0f} | "
                 + (f"{e['reference']} | {e['estimated_pj']:,.0f} | {100 * e['error']:+.1f} % |" if e else "- | - | - |"))
    return "\n".join(L) + "\n"
