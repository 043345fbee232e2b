"""The sweep's tables: sweep.csv (one row per point) and sweep.md (the table, the cheapest
setting within 1 dB per knob, failures, skipped values, driver notes, plots)."""
import csv
import io
import os

from .. import atomic
from ..fmt import cnt, fnum
from ..paths import ROOT
from .results import PSNR_CAP, cheapest_within


def delta(r: dict, base: dict, k: str):
    """A row's change of K from the base's (None where either is missing)."""
    return None if r[k] is None or base[k] is None else r[k] - base[k]


def csv_text(base: dict, rows: list, scenes: list, rtl: dict) -> str:
    """sweep.csv: one row per point (the base first), per-scene PSNRs at the end."""
    buf = io.StringIO()
    w = csv.writer(buf)
    head = ["point", "knob", "value", "status", "logic_ge", "rom_bits", "ram_bits", "flip_flops",
            "psnr_ref_mean", "psnr_ref_min", "psnr_truth_mean", "delta_psnr_ref", "delta_psnr_truth",
            "psnr_vs_base_min", "rtl_check"]
    head += [f"psnr_ref_{s}" for s in scenes] + [f"psnr_truth_{s}" for s in scenes]
    w.writerow(head)
    for r in [base] + rows:
        sc = r.get("scenes", {})
        w.writerow([r["name"], r["knob"], r["value"], r["status"], r["logic_ge"], r["rom_bits"], r["ram_bits"],
                    r["flip_flops"], fnum(r["psnr_ref"], 3, ""), fnum(r["psnr_ref_min"], 3, ""),
                    fnum(r["psnr_truth"], 3, ""), fnum(delta(r, base, "psnr_ref"), 3, ""),
                    fnum(delta(r, base, "psnr_truth"), 3, ""), fnum(r.get("psnr_base"), 3, ""),
                    rtl.get(r["name"], {}).get("summary", "")]
                   + [fnum((sc.get(s, {}).get("vs_reference") or {}).get("psnr"), 3, "") for s in scenes]
                   + [fnum((sc.get(s, {}).get("vs_truth") or {}).get("psnr"), 3, "") for s in scenes])
    return buf.getvalue()


def write_reports(s, out, base, rows, knobs, skipped, rtl, title, elapsed):
    """sweep.csv and sweep.md; S: the sweep's settings (sweep_run.SweepSettings)."""
    scenes = s.scene_names
    allrows = [base] + rows
    atomic.write_text(out / "sweep.csv", csv_text(base, rows, scenes, rtl))

    md = [f"# Precision sweep: base `{base['name']}`", "",
          f"One knob at a time around `{os.path.relpath(base['profile'], ROOT)}`. Golden-model renders of "
          f"{', '.join(scenes)} at {s.size} x {s.size}"
          + (f", ground truth {s.truth} x {s.truth} jittered samples per pixel" if s.truth else "")
          + ". PSNR over RGB in dB (means over the scenes; `min` = the worst scene). Logic in NAND2 gate "
          "equivalents (scripts/synth.py, Yosys; ROM/RAM bits outside the logic). "
          f"This invocation: {elapsed:.0f} s (points with a result are not recomputed); summed over the "
          f"points: renders {sum(r.get('render_seconds') or 0 for r in allrows):.0f} s, Yosys "
          f"{sum(r.get('yosys_seconds') or 0 for r in allrows if r['knob'] != 'filter'):.0f} s.", "",
          ("References: scene copies whose textures ask for each point's own noise variant and |grad| norm "
           "(--match-variant), so PSNR vs reference measures the fixed-point precision alone; for the "
           "interp / hash / corner / norm knobs it then says how exact that variant's hardware is, not how "
           "close the variant is to the scenes' texture." if s.match_variant else
           "References: the scenes' own textures (the noise variant and norm they ask for, Rayshade's by "
           "default): a profile with another variant is measured against that texture too."), "",
          f"Base: {cnt(base['logic_ge'])} GE, ROM {cnt(base['rom_bits'])} bits, RAM {cnt(base['ram_bits'])} bits, "
          f"PSNR vs reference {fnum(base['psnr_ref'])} dB (min {fnum(base['psnr_ref_min'])}), vs truth "
          f"{fnum(base['psnr_truth'])} dB. The double reference itself scores {fnum(base['ref_vs_truth'])} dB "
          "vs truth (the ceiling of the truth column).", "",
          "Columns: PSNR of the golden image against the double reference (`ref`, mean and worst scene) and "
          "against the supersampled ground truth (`truth`); Δ = change from the base; `vs base` = PSNR of "
          "the point's golden images against the base profile's, worst scene (what the change alone does, "
          "whatever the base's own error; `same` = bit-identical images).", "",
          "| knob | value | point | logic GE | ROM bits | RAM bits | PSNR ref mean | PSNR ref min | "
          "PSNR truth mean | Δ ref | Δ truth | vs base | RTL check |",
          "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|"]

    def vsb(r):
        v = r.get("psnr_base")
        return "" if r is base else "same" if v is not None and v >= PSNR_CAP else fnum(v, 1)

    def cell(v, fmt="{:,}"):
        return "-" if v is None else fmt.format(v)
    for r in allrows:
        dr, dt = delta(r, base, "psnr_ref"), delta(r, base, "psnr_truth")
        rc = rtl.get(r["name"], {}).get("summary", "")
        if r["status"] != "ok":
            md.append(f"| {r['knob']} | {r['value']} | {r['name']} | **failed** | | | | | | | | | {rc} |")
            continue
        ge = cell(r["logic_ge"]) + (" (=base)" if r["knob"] == "filter" and r["logic_ge"] is not None else "")
        md.append(f"| {r['knob']} | {r['value']} | {r['name']} | {ge} | {cell(r['rom_bits'])} | "
                  f"{cell(r['ram_bits'])} | {fnum(r['psnr_ref'])} | {fnum(r['psnr_ref_min'])} | "
                  f"{fnum(r['psnr_truth'])} | {'' if r is base else fnum(dr, 2)} | "
                  f"{'' if r is base else fnum(dt, 2)} | {vsb(r)} | {rc} |")
    md += ["", "## Cheapest setting within 1 dB of the base", "",
           "Per knob, among its values (the base's included) that pass the rule of acceptance against the base "
           "(scripts/pstlib/validation/acceptance.py: every scene's PSNR vs reference within 1 dB of the base's on that scene): "
           "the lowest logic GE, ties broken by ROM bits.", ""]
    lines = []
    for k in knobs if base["status"] == "ok" else []:
        if k == "filter":
            ok = [r for r in rows if r["knob"] == k and r["status"] == "ok" and r["psnr_truth"] is not None]
            if base["base_value"].get(k) and base["psnr_truth"] is not None:
                ok.append(dict(base, value=base["base_value"][k]))
            if ok:
                best = max(ok, key=lambda r: r["psnr_truth"])
                lines.append(f"- **filter**: no cost difference (the hardware holds every filter kind; GE = base). "
                             f"Best vs truth: `{best['value']}` ({fnum(best['psnr_truth'])} dB).")
            continue
        best, ok = cheapest_within(rows, base, k)
        if best is None and ok:
            lines.append(f"- **{k}**: values within 1 dB: {', '.join(str(r['value']) for r in ok)} "
                         "(no gate counts: run without --no-synth to rank them)")
        elif best is None:
            lines.append(f"- **{k}**: no value within 1 dB")
        else:
            dge = best["logic_ge"] - base["logic_ge"]
            drom = (best["rom_bits"] or 0) - (base["rom_bits"] or 0)
            lines.append(f"- **{k}**: `{best['value']}`"
                         + (" (the base value)" if best["value"] == base["base_value"].get(k) else
                            f" ({best['name']}): {best['logic_ge']:,} GE ({dge:+,} vs base)"
                            + (f", ROM {drom:+,} bits" if drom else "")
                            + f", PSNR vs reference {fnum(best['psnr_ref'])} dB "
                            f"(Δ {fnum(best['psnr_ref'] - base['psnr_ref'])}), vs truth {fnum(best['psnr_truth'])} dB "
                            f"(Δ {fnum(best['psnr_truth'] - base['psnr_truth'])}), images vs base "
                            + ("identical" if (best.get("psnr_base") or 0) >= PSNR_CAP else
                               f"{fnum(best.get('psnr_base'), 1)} dB (worst scene)")))
    md += lines or ["- (the base profile failed: nothing to compare with)"]
    failed = [r for r in allrows if r["status"] != "ok"]
    rtl_failed = [n for n, v in rtl.items() if not v.get("passed")]
    if failed or rtl_failed:
        md += ["", "## Failures", ""]
        for r in failed:
            md += [f"- `{r['name']}`:", "", "```", r.get("error", "").strip(), "```", ""]
        for n in rtl_failed:
            md += [f"- RTL check `{n}`: {rtl[n]['summary']}", "", "```", rtl[n].get("error", "").strip(), "```", ""]
    if skipped:
        md += ["", "## Skipped values", ""] + [f"- {k} = {v}: {why}" for k, v, why in skipped]
    notes = sorted({n for r in allrows for s in r.get("scenes", {}).values() for n in (s.get("notes") or [])})
    if notes:
        md += ["", "## Driver notes", "", "What the hardware did differently from the scenes' requests "
               "(octaves dropped, noise variant, ...):", ""] + [f"- {n}" for n in notes[:30]]
    md += ["", "## Plots", "", "- [GE vs PSNR vs reference](ge_vs_psnr_reference.png)",
           "- [GE vs PSNR vs truth](ge_vs_psnr_truth.png)"]
    md += [f"- [{k}](knobs/{k}.png)" for k in knobs if (out / "knobs" / f"{k}.png").exists()]
    atomic.write_text(out / "sweep.md", "\n".join(md) + "\n")
    return lines

