"""The search strategy: the least logic area subject to worst-scene PSNR >= a target, clocks per
pixel <= a target and Fmax >= a target, over many profile knobs at once.

Algorithm: a greedy walk with backtracking, one walk per clocks-per-pixel class, from a start
profile that meets the targets (full for 1, full with fewer noise units for 4, reduced for 32).
Each step evaluates every one-step-cheaper neighbour (each knob moved one value towards its
cheaper end: fewer fraction bits, a cheaper noise variant or |grad| norm, fewer corners per
cycle), in parallel, and moves to the feasible neighbour that saves the most area per dB of
worst PSNR it costs (the margin above the target is shared by all knobs, as a knapsack's
capacity: the greedy rule of the fractional knapsack). At a point with no
feasible cheaper neighbour (a local minimum) it backtracks to the last point that had other
feasible moves and takes the next one, a bounded number of times. Every evaluated point is
kept (the archive); the Pareto fronts come from the archive.

Why this and not a grid, coordinate descent or a genetic Pareto search: the knobs are ordinal
and close to monotone (a bit less costs area and quality, never buys both), so the cheapest
feasible profile lies on a descending path from a feasible one, and a walk needs about knobs x
steps evaluations where a grid needs the product of the value counts (10^12 here). Coordinate
descent moves one knob at a time in a fixed order and commits to the first knob's cut, which
then blocks a bigger saving elsewhere (the PSNR margin is shared by all knobs); the greedy walk
compares all knobs' cuts at every step and spends the margin where it buys the most area.
Backtracking recovers some of what greediness loses when the best cut exhausts the margin
early. A population (NSGA-II) search would map the whole front but needs thousands of
evaluations; synthesis makes ours minutes each (full, uncached), so the budget is tens to
hundreds of points.

Points and their results: see the command line (scripts/search.py) and search_run.py.
"""
import copy
import dataclasses
import tomllib

from .. import contract, tomledit
from ..validation.acceptance import passes, scene_loss      # the rule of acceptance, one place (scene_loss re-exported)
from .point import Point, values_key
from .sweep import _apply_key, _format_frac, _set_format_frac

CLASSES = (1, 4, 32)


def _fmt_knob(name, formats, values):
    return {"name": name, "values": values, "apply": _set_format_frac(*formats),
            "get": (lambda d, f=formats: _format_frac(d, *f)), "desc": " = ".join(f"formats.{f}.frac" for f in formats)}


def _key_knob(name, section, key, values):
    return {"name": name, "values": values, "apply": _apply_key(section, key),
            "get": (lambda d, s=section, k=key: d[s][k]), "desc": f"{section}.{key}"}


# Every knob: values from the cheapest to the dearest (a move "down" goes one value left).
KNOBS = [
    _fmt_knob("coord_frac", ["coord"], [8, 10, 12, 14, 16, 18, 20]),
    _fmt_knob("jacobian_frac", ["jacobian"], [8, 10, 12, 14, 16, 20, 24]),
    _fmt_knob("matrix_frac", ["matrix", "grad_matrix"], [6, 8, 10, 12, 14, 16]),
    _fmt_knob("amp_frac", ["amplitude"], [6, 8, 10, 12, 14, 16]),
    _fmt_knob("offset_frac", ["offset"], [6, 8, 10, 12, 14, 16]),
    _fmt_knob("quadric_frac", ["quadric"], [6, 8, 10, 12, 14, 16]),
    _fmt_knob("f_frac", ["f"], [8, 10, 12, 14, 16, 20]),
    _fmt_knob("grad_frac", ["grad"], [6, 8, 10, 12, 14, 16]),
    _key_knob("width_frac", "formats", "width_frac", [2, 4, 6, 8]),
    _key_knob("value_frac", "noise", "value_frac", [5, 7, 9, 11, 13, 15]),
    _key_knob("lattice_frac", "noise", "lattice_frac", [6, 8, 10, 12, 14, 16]),
    _key_knob("out_frac", "noise", "out_frac", [6, 8, 10, 12, 14, 16]),
    _key_knob("guard_bits", "noise", "guard_bits", [1, 2, 3, 4]),
    _key_knob("noise_grad_frac", "noise", "grad_frac", [8, 10, 12, 14, 16, 18, 20]),
    _key_knob("recip_frac", "filter", "recip_frac", [10, 12, 14, 16, 18]),
    _key_knob("interp", "noise", "interp", ["linear", "scurve"]),
    _key_knob("corner", "noise", "corner", ["value", "value_gradient"]),
    _key_knob("hash", "noise", "hash", ["perm256", "rayshade"]),
    _key_knob("norm", "filter", "norm", ["l1", "max_half_min", "euclid"]),
]
KNOB_NAMES = [k["name"] for k in KNOBS] + ["structure"]


def cycles_per_pixel(doc: dict) -> int:
    return contract.stage_cycles(doc)["pixel"]


def structures(octaves: int, max_cpp: int, base: dict | None = None) -> list:
    """(octaves, noise_units, noise_steps, datapath) of the given octave count whose clocks per
    pixel are <= MAX_CPP, from the cheapest (fewest noise corners per cycle, serial) to the dearest.
    With `base` (a whole profile) the clocks per pixel are those of base with the structure
    (contract.stage_cycles: base's pipeline registers lengthen a serial schedule); without it,
    the structure's alone (no pipeline registers)."""
    out = []
    for units in range(1, octaves + 1):
        for steps in (1, 2, 4, 8):
            for dp in ("serial", "parallel"):
                if octaves % units and dp == "serial":
                    continue              # parallel: ceil(octaves / units) passes, a lane idle
                doc = {"pipeline": {"octaves": octaves, "noise_units": units, "noise_steps": steps, "datapath": dp}}
                if dp == "serial" and steps < 4:
                    continue
                if base is not None:
                    d = copy.deepcopy(base)
                    d["pipeline"].update(doc["pipeline"])
                    cpp = cycles_per_pixel(d)
                else:
                    cpp = contract.formulas.octave_cycles(octaves, units, steps,
                                                          contract.ENUMS[("pipeline", "datapath")].index(dp), 0, 0)
                if cpp <= max_cpp:
                    out.append(doc["pipeline"])
    return sorted(out, key=lambda p: (p["noise_units"] * 8 // p["noise_steps"], p["datapath"] == "parallel",
                                      p["noise_units"]))


def structure_of(doc: dict) -> dict:
    p = doc["pipeline"]
    return {k: p[k] for k in ("octaves", "noise_units", "noise_steps", "datapath")}


def make_point(base_text: str, base_doc: dict, doc: dict, move: str, prefix="s") -> Point:
    """A point: the base's text with the changed values (comments kept), named by its values."""
    body = tomledit.without_leading_comment(base_text)
    text = tomledit.with_comment("\n" + tomledit.set_values(body, tomledit.changes_between(base_doc, doc)),
                                 f"Search point: {move}.\nWritten by scripts/search.py.\n")
    assert tomllib.loads(text) == doc, "tomledit lost a change"
    key = values_key(doc)
    return Point(f"{prefix}_{key}", doc, text, key, move=move)


def neighbours(doc: dict, knobs: list, structs: list) -> list:
    """(knob, from, to, new doc) of every valid one-step-cheaper move of DOC, the structure move
    first (the largest saving; a walk short of budget evaluates it before the format cuts)."""
    out = []
    for k in KNOBS:
        if k["name"] not in knobs:
            continue
        cur = k["get"](doc)
        vals = k["values"]
        if cur in vals:
            i = vals.index(cur)
            if i == 0:
                continue
            to = vals[i - 1]
        else:                   # between the listed values: the next listed value below it
            lower = [v for v in vals if isinstance(cur, int) and v < cur]
            if not lower:
                continue
            to = lower[-1]
        d = copy.deepcopy(doc)
        k["apply"](d, to)
        if not contract.validate(d):
            out.append((k["name"], cur, to, d))
    if "structure" in knobs:
        cur = structure_of(doc)
        if cur in structs:
            i = structs.index(cur)
            if i > 0:
                d = copy.deepcopy(doc)
                d["pipeline"].update(structs[i - 1])
                if not contract.validate(d):
                    out.insert(0, ("structure", _sdesc(cur), _sdesc(structs[i - 1]), d))
    return out


def _sdesc(s: dict) -> str:
    return f"{s['octaves']}oct/{s['noise_units']}u/{s['noise_steps']}st/{s['datapath']}"


def timing_fmax(r: dict):
    """The Fmax a point's clock target is judged by: the pre-layout Fmax derated by the routed
    profile's post-route / pre-layout ratio (scripts/synth/layout_derate.json) when the silicon
    flow gave one, else the pre-layout Fmax; None when the point was not timed."""
    d = r.get("fmax_derated_mhz")
    return d if d is not None else r.get("fmax_mhz")


def feasible(r: dict, t) -> bool:
    """A result meets the targets (worst PSNR on the training set, clocks per pixel, Fmax when
    asked (the derated Fmax where there is one: timing_fmax), and with t.max_loss every training scene within that many dB of t.ref's PSNR)."""
    if r.get("status") != "ok" or r.get("train_worst") is None:
        return False
    if r["train_worst"] < t.psnr or r["cpp"] > t.cpp:
        return False
    if t.fmax > 0 and (timing_fmax(r) is None or timing_fmax(r) < t.fmax):
        return False
    if t.max_loss is not None and t.ref is not None and not passes(scene_loss(t.ref, r.get("train") or {}), t.max_loss):
        return False
    return True


@dataclasses.dataclass
class Targets:
    psnr: float
    cpp: int
    fmax: float = 0.0
    # Texture by texture (the rule the named profiles were cut by: a step colour map or a nearest
    # MIP level turns a tiny f change into whole colour steps, which the worst scene can hide):
    # every training scene within max_loss dB of ref, the start's PSNR per scene (walk sets it).
    max_loss: float | None = None
    ref: dict | None = None


def merit(here: dict, there: dict, per_scene: bool = False) -> float:
    """Logic GE saved per dB of PSNR lost by the move HERE -> THERE: of the worst training scene,
    or with PER_SCENE of the scene that loses most (a move that loses nothing is worth its
    saving / 0.05 dB: PSNR is a noisy measure of a small change)."""
    saved = here["logic_ge"] - there["logic_ge"]
    if per_scene:
        lost = max(0.0, scene_loss(here.get("train") or {}, there.get("train") or {}))
    else:
        lost = max(0.0, here["train_worst"] - there["train_worst"])
    return saved / max(lost, 0.05)


def walk(start: Point, evaluate, targets: Targets, knobs: list, structs: list, base_text, base_doc,
         budget: int, backtracks: int, say=print, fmax_of=None) -> dict:
    """The greedy walk with backtracking from START. evaluate(list of Points) -> {name: result}
    (parallel, cached); fmax_of(point, result) -> result with fmax_mhz (only called on feasible
    candidates when targets.fmax > 0, cheapest first). Returns {"best": name, "path": [...],
    "evaluated": n, "archive": {name: (point, result)}}."""
    archive = {}

    def ev(points):
        todo = [p for p in points if p.name not in archive]
        if todo:
            res = evaluate(todo)
            for p in todo:
                archive[p.name] = (p, res[p.name])
        return [archive[p.name][1] for p in points]

    (r0,) = ev([start])
    if targets.max_loss is not None and targets.ref is None and r0.get("train"):
        targets = dataclasses.replace(targets, ref=dict(r0["train"]))
    if targets.fmax > 0 and fmax_of and feasible(r0, dataclasses.replace(targets, fmax=0)):
        r0 = fmax_of(start, r0)
        archive[start.name] = (start, r0)
    if not feasible(r0, targets):
        say(f"start {start.name} ({start.move}) does not meet the targets: worst training PSNR "
            f"{r0.get('train_worst')}, {r0.get('cpp')} clk/px, Fmax {r0.get('fmax_mhz')}")
        return {"best": None, "path": [start.name], "archive": archive, "backtracks": 0}
    path = [start.name]
    best = start.name
    stack = []          # (point name, remaining feasible alternatives [(area, name)])
    cur = start
    used_bt = 0
    while len(archive) < budget:
        moves = neighbours(cur.doc, knobs, structs)
        pts = []
        for k, a, b, d in moves:
            pts.append(make_point(base_text, base_doc, d, f"{cur.move}; {k} {a}->{b}" if cur.move != "start"
                                  else f"{k} {a}->{b}"))
        room = budget - len(archive)
        pts = [p for p in pts if p.name in archive] + [p for p in pts if p.name not in archive][:max(room, 0)]
        res = ev(pts)
        here = archive[cur.name][1]
        cand = [(r["logic_ge"], p.name) for p, r in zip(pts, res)
                if feasible(r, dataclasses.replace(targets, fmax=0)) and r.get("logic_ge") is not None
                and r["logic_ge"] < here.get("logic_ge", float("inf"))]
        cand.sort(key=lambda c: -merit(here, archive[c[1]][1], per_scene=targets.max_loss is not None))
        if targets.fmax > 0 and fmax_of:
            ok = []
            for area, n in cand:
                p, r = archive[n]
                if r.get("fmax_mhz") is None:
                    r = fmax_of(p, r)
                    archive[n] = (p, r)
                if feasible(r, targets):
                    ok.append((area, n))
            cand = ok
        if cand:
            area, n = cand[0]
            stack.append((cur.name, cand[1:]))
            cur = archive[n][0]
            path.append(n)
            say(f"  -> {n}: {archive[n][0].move.split('; ')[-1]}, {area / 1000:.1f}k GE, worst training PSNR "
                f"{archive[n][1]['train_worst']:.2f} dB")
            if area < archive[best][1]["logic_ge"]:
                best = n
            continue
        # A local minimum: back to the last point with another feasible move.
        say(f"  local minimum at {cur.name} ({archive[cur.name][1]['logic_ge'] / 1000:.1f}k GE)")
        while stack and not stack[-1][1]:
            stack.pop()
        if not stack or used_bt >= backtracks:
            break
        used_bt += 1
        origin, alts = stack[-1]
        area, n = alts.pop(0)
        cur = archive[n][0]
        path.append(n)
        say(f"  backtrack {used_bt}: from {origin} take {n} ({area / 1000:.1f}k GE)")
        if area < archive[best][1]["logic_ge"]:
            best = n
    return {"best": best, "path": path, "archive": archive, "backtracks": used_bt}


PSNR_EPS = 0.05     # dB: PSNR differences below this are noise (merit's floor too)


def pareto(rows: list, area="logic_ge", quality="train_worst", eps=PSNR_EPS) -> list:
    """The rows no other row beats on both (less or equal area and more or equal quality, one
    strictly), sorted by area; a row must beat the cheaper rows' quality by more than EPS dB
    (a 0.001 dB gain for 50k GE is not a trade-off, and each front point costs an RTL build)."""
    ok = [r for r in rows if r.get(area) is not None and r.get(quality) is not None]
    ok.sort(key=lambda r: (r[area], -r[quality]))
    front, best_q = [], float("-inf")
    for r in ok:
        if r[quality] > best_q + eps:
            front.append(r)
            best_q = r[quality]
    return front
