"""The silicon tables: one column per named profile. The summary a designer reads first has
the same rows in docs/HARDWARE.md (generated from scripts/synth/baseline.json
and scripts/synth/layout_derate.json: `scripts/gen_docs.py --write`) and in the report (from
out/synth/PROFILE.json and out/pnr/PROFILE.json); docs/HARDWARE.md also has the logic per
block (`blocks_markdown`) and the critical path per stage (`stages_markdown`).

Each profile is normalized to one dict (`from_baseline`, `from_synth`) and `rows` turns the
dicts into the table; the raw JSON stays one link away.

The clock a profile is quoted at after layout (`layout_clock`: post-route for the routed
profile, else the pre-layout Fmax derated, else pre-layout) is chosen here and nowhere else; the
derated Fmax itself is the synthesis record's `fmax_derated_mhz` (pstlib/synth/report.py, the one
place that applies scripts/synth/layout_derate.json's ratio), read, never recomputed. `data_json`
writes the choice for the C++ tool (docs/data/silicon.json, which `pst atlas` reads).
"""
import json

from ..synth.report import PAPER_GATES, REALTIME_MPIX

PROFILES = ("full", "full_2clk", "full_1clk", "reduced", "balanced")
GE_UM2 = 24.0     # NAND2X1 of OSU018: GE -> mm^2 where only GE are stored


def _worst_psnr(psnr: dict):
    if not psnr:
        return None
    scene = min(psnr, key=psnr.get)
    return (scene, psnr[scene])


def _worst_stage(paths: dict):
    """"stage, ns" of the slowest path group (baseline.json's stage_path_ns), or None."""
    if not paths:
        return None
    stage = max(paths, key=paths.get)
    return f"{stage}, {paths[stage]:.2f} ns"


def clock_source(name: str, derate) -> str:
    """Where profile NAME's clock after layout comes from (DERATE: the layout_derate.json entry
    it is derated by, pstlib/synth/report.py derate_for, or None)."""
    if not derate:
        return "pre-layout only (nothing routed)"
    n = len(derate.get("blocks") or [])
    if derate["profile"] != name:
        return f"not routed: x {derate['ratio']:.3f}, the worst routed ratio ({derate['profile']}'s {n} blocks)"
    if derate.get("critical_blocks_only"):
        return f"its own {n} critical blocks routed: x {derate['ratio']:.3f}, their worst ratio"
    return f"its {n} blocks routed" + (", assembled" if derate.get("assembled_fmax_mhz") else "")


def from_baseline(name: str, b: dict, derate, record=None) -> dict:
    """A profile of scripts/synth/baseline.json (DERATE: the layout_derate.json entry it is
    derated by, pstlib/synth/report.py derate_for, or None; RECORD: the profile's synthesis
    record, scripts/synth/records/NAME.json, for its derated Fmax, or None). Its clock after
    layout is post-route where the profile itself was routed whole (every block it chose to
    run), else its derated Fmax."""
    whole = bool(derate and derate["profile"] == name and not derate.get("critical_blocks_only"))
    return {"profile": name, "logic_ge": b["logic_ge"], "memory_ge": b["memory_ge"], "total_ge": b["total_ge"],
            "flip_flops": b["flip_flops"], "fmax_mhz": b.get("fmax_mhz"),
            "signoff_sdc": b.get("fmax_setup_uncertainty_ns") is not None,
            "post_route_mhz": ((derate.get("assembled_fmax_mhz") or derate["post_route_fmax_mhz"])
                               if whole else None),
            "post_route_assembled": bool(whole and derate.get("assembled_fmax_mhz")),
            "post_route_partial": bool(whole and derate.get("not_routed")),
            "derate": derate["ratio"] if derate else None, "fmax_derated_mhz": (record or {}).get("fmax_derated_mhz"),
            "clock_source": clock_source(name, derate),
            "clocks_per_pixel": b["clocks_per_pixel"], "worst_psnr": _worst_psnr(b.get("psnr_db")),
            "worst_path": _worst_stage(b.get("stage_path_ns")), "paper_gates": PAPER_GATES.get(name),
            "block_ge": b.get("block_ge") or {}, "stage_path_ns": b.get("stage_path_ns") or {}}


def from_synth(s: dict, pnr=None, psnr=None) -> dict:
    """A profile of out/synth/PROFILE.json (PNR: out/pnr/PROFILE.json or None; PSNR: scene ->
    dB of the regression, or None)."""
    tm = s.get("timing") or {}
    worst = tm.get("worst") or {}
    d = s.get("fmax_derate")
    return {"profile": s["profile"], "logic_ge": s.get("logic_ge"), "memory_ge": s.get("memory_ge"),
            "total_ge": s.get("total_ge"), "flip_flops": s.get("flip_flops"), "fmax_mhz": s.get("fmax_mhz"),
            "signoff_sdc": "constraints" in tm,
            "post_route_mhz": ((pnr.get("assembled") or {}).get("fmax_mhz") or pnr["post_route_fmax_mhz"]) if pnr else None,
            "post_route_assembled": bool(pnr and (pnr.get("assembled") or {}).get("fmax_mhz")),
            "post_route_partial": bool(pnr and (pnr.get("failed_blocks") or pnr.get("skipped_blocks"))),
            "derate": d["ratio"] if d else None, "fmax_derated_mhz": s.get("fmax_derated_mhz"),
            "clocks_per_pixel": s.get("clocks_per_pixel"),
            "worst_psnr": _worst_psnr(psnr), "paper_gates": s.get("paper_gates"),
            "worst_path": (f"{worst['stage']}, {s['worst_path_ns']:.2f} ns" if worst.get("stage") and s.get("worst_path_ns")
                           else None),
            "block_ge": {b: v["logic_ge"] for b, v in (s.get("blocks") or {}).items()},
            "stage_path_ns": s.get("critical_path_ns") or {}}


def layout_clock(p: dict):
    """(MHz, label) the throughput is quoted at: post-route (the chip assembled from its routed
    blocks where the place and route timed it, else its slowest block), else the synthesis
    record's derated Fmax, else pre-layout."""
    if p["post_route_mhz"]:
        if p.get("post_route_assembled"):
            # The chip timed from its routed blocks; a block without a layout is in it before layout.
            return p["post_route_mhz"], "post-route, blocks assembled" + (
                "; some without layout" if p.get("post_route_partial") else "")
        return p["post_route_mhz"], "post-route" + (", timed blocks only" if p.get("post_route_partial") else "")
    if p.get("fmax_derated_mhz"):
        return p["fmax_derated_mhz"], "derated"
    return p["fmax_mhz"], "pre-layout"



def data_json(profiles: list) -> str:
    """docs/data/silicon.json: per profile its pre-layout Fmax, the clock after layout the summary
    quotes (layout_clock; null when it has only the pre-layout one) with its basis, and clocks per
    pixel, for the C++ tool, which reads these figures instead of working them out."""
    out = {}
    for p in profiles:
        mhz, basis = layout_clock(p)
        out[p["profile"]] = {"fmax_mhz": p["fmax_mhz"], "fmax_layout_mhz": mhz if basis != "pre-layout" else None,
                             "fmax_layout_basis": basis if basis != "pre-layout" else None,
                             "clocks_per_pixel": p["clocks_per_pixel"]}
    return json.dumps({"generated_by": "scripts/gen_docs.py --write (pstlib/report/silicon_table.py)",
                       "profiles": out}, indent=2) + "\n"


def throughput(p: dict):
    """The one throughput of profile P, the table's "Mpixel/s at that clock": (Mpixel/s, MHz,
    basis), basis "post-route[...]", "derated (post-route ratio x R)" or "pre-layout"; None
    without a clock or clocks per pixel."""
    mhz, basis = layout_clock(p)
    if not (mhz and p["clocks_per_pixel"]):
        return None
    if basis == "derated":
        basis = f"derated (post-route ratio x {p['derate']:.3f})"
    return mhz / p["clocks_per_pixel"], mhz, basis


def rows(profiles: list) -> list:
    """[label, value per profile] rows (values as text, '-' when unknown)."""
    def col(f):
        return [f(p) for p in profiles]

    def num(v, fmt="{:,}"):
        return "-" if v is None else fmt.format(v)

    out = [
        ["logic GE", *col(lambda p: num(p["logic_ge"]))],
        ["memory GE", *col(lambda p: num(p["memory_ge"]))],
        ["total GE (mm^2)", *col(lambda p: "-" if p["total_ge"] is None else
                                 f"{p['total_ge']:,} ({p['total_ge'] * GE_UM2 / 1e6:.1f})")],
        ["flip-flops", *col(lambda p: num(p["flip_flops"]))],
        ["Fmax pre-layout (typical, no wire)", *col(lambda p: "-" if not p["fmax_mhz"] else
                                                    f"{p['fmax_mhz']:.1f} MHz" + ("" if p["signoff_sdc"] else " (ideal clock)"))],
        ["Fmax post-route, or pre-layout x derate", *col(lambda p: "-" if not layout_clock(p)[0] else
                                                         f"{layout_clock(p)[0]:.1f} MHz ({layout_clock(p)[1]}"
                                                         + (f" x {p['derate']:.3f})" if layout_clock(p)[1] == "derated" else ")"))],
        *([["clock after layout from", *col(lambda p: p.get("clock_source") or "-")]]
          if any(p.get("clock_source") for p in profiles) else []),
        ["clocks per pixel", *col(lambda p: num(p["clocks_per_pixel"]))],
        ["Mpixel/s at that clock", *col(lambda p: "-" if not (layout_clock(p)[0] and p["clocks_per_pixel"]) else
                                        f"{layout_clock(p)[0] / p['clocks_per_pixel']:.2f}")],
        [f"meets {REALTIME_MPIX:.1f} Mpixel/s", *col(lambda p: "-" if not (layout_clock(p)[0] and p["clocks_per_pixel"]) else
                                                     ("yes" if layout_clock(p)[0] / p["clocks_per_pixel"] >= REALTIME_MPIX else "no"))],
        ["logic GE x clocks per pixel", *col(lambda p: "-" if not (p["logic_ge"] and p["clocks_per_pixel"]) else
                                             f"{p['logic_ge'] * p['clocks_per_pixel']:,}")],
        ["worst path", *col(lambda p: p["worst_path"] or "-")],
        ["worst paper scene", *col(lambda p: "-" if not p["worst_psnr"] else
                                   f"{p['worst_psnr'][0]} {p['worst_psnr'][1]:.1f} dB")],
        ["the paper's gate count", *col(lambda p: num(p["paper_gates"]))],
    ]
    if any(p.get("power") for p in profiles):
        # scripts/power.py's summary (docs/POWER.md): pre-layout, RAMs not modelled
        out += [
            ["energy per pixel (pre-layout, RAMs not modelled)", *col(lambda p: "-" if not p.get("power") else
                                                                   f"{p['power']['pj_per_pixel']:,.0f} pJ")],
            [f"power at {REALTIME_MPIX:.1f} Mpixel/s (copies side by side)", *col(lambda p: "-" if not (p.get("power") or {}).get("mw_at_realtime") else
                                                 f"{p['power']['mw_at_realtime']:,.0f} mW ({p['power']['realtime_copies']})")],
        ]
    return out


def with_power(p: dict, summary) -> dict:
    """Profile P with scripts/power.py's SUMMARY (docs/data/power.json's or out/power/P.json's)."""
    return {**p, "power": summary} if summary else p


def markdown(profiles: list) -> str:
    head = ["figure", *(p["profile"] for p in profiles)]
    lines = ["| " + " | ".join(head) + " |", "|---|" + "---:|" * len(profiles)]
    lines += ["| " + " | ".join(r) + " |" for r in rows(profiles)]
    return "\n".join(lines) + "\n"


def _table(head: list, body: list) -> str:
    lines = ["| " + " | ".join(head) + " |", "|---|" + "---:|" * (len(head) - 1)]
    lines += ["| " + " | ".join(r) + " |" for r in body]
    return "\n".join(lines) + "\n"


def blocks_markdown(profiles: list) -> str:
    """Logic GE per block (a block: a module at depth 1 or 2 of the hierarchy, pstlib/synth/
    blocks.py; building blocks counted in the block holding them), the top's own row last."""
    names = sorted({b for p in profiles for b in p["block_ge"]}, key=lambda b: (b == "top", b))
    body = [[f"`{b}`", *("-" if b not in p["block_ge"] else f"{p['block_ge'][b]:,}" for p in profiles)]
            for b in names]
    body.append(["**logic**", *("-" if p["logic_ge"] is None else f"**{p['logic_ge']:,}**" for p in profiles)])
    return _table(["block (logic GE)", *(p["profile"] for p in profiles)], body)


def _stage_key(stage: str):
    """Pipeline order: by the first register letter the stage names ([A] .. [D]), the others
    (the register file, the clock group) last."""
    i = stage.find("[")
    return (stage[i + 1] if i >= 0 else "~", stage)


def stages_markdown(profiles: list) -> str:
    """Critical path per stage (ns, pre-layout, min period of the stage's path group) and
    each profile's worst in bold."""
    names = sorted({s for p in profiles for s in p["stage_path_ns"]}, key=_stage_key)
    body = []
    for st in names:
        row = [st]
        for p in profiles:
            v = p["stage_path_ns"].get(st)
            worst = v is not None and v == max(p["stage_path_ns"].values())
            row.append("-" if v is None else (f"**{v:.2f}**" if worst else f"{v:.2f}"))
        body.append(row)
    return _table(["path group (ns)", *(p["profile"] for p in profiles)], body)
