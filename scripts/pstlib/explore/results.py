"""Sweep results: the PSNRs of pst's summary.json, a point's row (means over the scenes, gate
count), the cheapest setting within 1 dB (the rule of acceptance, scene by scene), the points
checked on the RTL."""
import math
import pathlib

from ..validation import acceptance

PSNR_CAP = 100.0        # PSNR of an exact match (rms 0) in the means


def psnr(v):
    """The PSNR of one comparison of a summary.json ({"psnr": dB, "rms": ...}): capped at
    PSNR_CAP, PSNR_CAP for an exact match, None when missing or not a number."""
    if not v:
        return None
    p = v.get("psnr")
    if p is None or (isinstance(p, float) and (math.isinf(p) or math.isnan(p))):
        return PSNR_CAP if v.get("rms") == 0 else None
    return min(p, PSNR_CAP)


def summarize(res: dict, scenes=None) -> dict:
    """Means over the scenes (those named, default all) of one point's result."""
    sc = [v for k, v in res.get("scenes", {}).items() if scenes is None or k in scenes]
    ref = [psnr(s.get("vs_reference")) for s in sc]
    tru = [psnr(s.get("vs_truth")) for s in sc]
    rvt = [psnr(s.get("reference_vs_truth")) for s in sc]

    def mean(xs):
        return (sum(xs) / len(xs)) if xs and None not in xs else None
    return {"psnr_ref": mean(ref), "psnr_ref_min": min(ref) if ref and None not in ref else None,
            "psnr_truth": mean(tru), "ref_vs_truth": mean(rvt)}


def row_of(res: dict, scenes: list, base_res: dict = None) -> dict:
    """One point's row of the tables (a filter point has the base's gate count)."""
    s = summarize(res, scenes)
    if res.get("status") != "ok":
        s = {k: None for k in s}
    syn = res.get("synth") or ((base_res or {}).get("synth") if res.get("knob") == "filter" else None)
    return {"name": res["name"], "knob": res["knob"], "value": res["value"], "status": res.get("status", "failed"),
            "error": res.get("error"), "profile": res.get("profile"), "profile_sha": res.get("profile_sha"),
            "scenes": {k: v for k, v in res.get("scenes", {}).items() if k in scenes},
            "logic_ge": syn and syn.get("logic_ge"), "rom_bits": syn and syn.get("rom_bits"),
            "ram_bits": syn and syn.get("ram_bits"), "flip_flops": syn and syn.get("flip_flops"),
            "yosys_seconds": syn and syn.get("yosys_seconds"), "render_seconds": res.get("render_seconds"), **s}


def image_psnr(a, b) -> float:
    """PSNR (RGB, values in [0, 1]) of two images of the same shape, capped at PSNR_CAP."""
    mse = float(((a[..., :3].astype("float64") - b[..., :3]) ** 2).mean())
    return PSNR_CAP if mse == 0 else min(PSNR_CAP, -10 * math.log10(mse))


def psnr_vs_base(out: pathlib.Path, name: str, base: str, scenes: list):
    """PSNR (RGB) of the point's golden images against the base profile's golden images, the
    worst scene: what the change alone does, whatever the base's own error against the reference."""
    import matplotlib.image as mpimg
    vals = []
    for s in scenes:
        pa = out / "renders" / name / s / "golden.png"
        pb = out / "renders" / base / s / "golden.png"
        if not (pa.exists() and pb.exists()):
            return None
        a, b = mpimg.imread(str(pa)), mpimg.imread(str(pb))
        if a.shape != b.shape:
            return None
        vals.append(image_psnr(a, b))
    return min(vals) if vals else None


def scene_psnrs(row: dict) -> dict:
    """Scene -> PSNR vs reference of one row (its scenes' records)."""
    return {k: psnr(v.get("vs_reference")) for k, v in (row.get("scenes") or {}).items()}


def cheapest_within(rows: list, base: dict, knob: str, db: float = acceptance.TOLERANCE_DB):
    """The cheapest setting of one knob (the base value included) that passes the rule of
    acceptance against the base (every scene's PSNR vs reference within `db` of the base's PSNR
    on that scene); cheapest = lowest logic GE, then ROM bits. None if no GE."""
    cands = [r for r in rows if r["knob"] == knob and r["status"] == "ok" and r["psnr_ref"] is not None]
    cands.append(dict(base, value=base["base_value"].get(knob)))
    ref = scene_psnrs(base)
    ok = [r for r in cands if r["psnr_ref"] is not None and base["psnr_ref"] is not None
          and acceptance.judge(ref, scene_psnrs(r), db)["passed"]]
    if any(r["logic_ge"] is None for r in ok) or not ok:
        return None, ok
    return min(ok, key=lambda r: (r["logic_ge"], r["rom_bits"] or 0, r["ram_bits"] or 0)), ok


def rtl_subset(rows: list, base: dict, knobs: list, n: int) -> list:
    """The names of N points to check on the RTL: each knob's cheapest point within 1 dB (not the
    base), the biggest savings first; too few: any rendered point of another knob."""
    if n <= 0:
        return []
    inf = float("inf")

    def cost(r):
        return (r["logic_ge"] if r["logic_ge"] is not None else inf, r["rom_bits"] or 0)
    per_knob = []
    for k in knobs:
        if k == "filter":
            continue
        _, ok = cheapest_within(rows, base, k)
        ok = sorted((r for r in ok if r["name"] != base["name"]), key=cost)
        if ok:
            per_knob.append(ok[0])
    chosen = [r["name"] for r in sorted(per_knob, key=cost)[:n]]
    byname = {r["name"]: r for r in rows}
    for k in knobs:
        if len(chosen) >= n or k == "filter":
            continue
        if any(byname[c]["knob"] == k for c in chosen):
            continue
        cand = [r for r in rows if r["knob"] == k and r["status"] == "ok"]
        if cand:
            chosen.append(cand[0]["name"])
    return chosen
