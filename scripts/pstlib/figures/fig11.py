"""Figure 11: 100,000-gate simulations of Figures 1-6 (reference | full | reduced per scene)."""
import tomllib
from pathlib import Path

import numpy as np

from .. import atomic
from .figdata import PAPER_FIGURE, PAPER_ORDER, REGRESS_CMD, InputMissing, fmt_db, fmt_pct, gates_label, load_regress, progress, rel, scene_order
from .images import Canvas, fit, read_rgb, write_png
from ..paths import ROOT, profile_path


def scene_row(out: Path, name: str, runs: dict) -> dict:
    """One scene's images (reference, full and reduced RTL, their differences) and regress entries."""
    d = out / name
    need = [d / "full" / "reference.png", d / "full" / "difference.png", d / "reduced" / "difference.png"]
    for p in need:
        if not p.exists():
            raise InputMissing(f"{rel(p)} is missing: run `{REGRESS_CMD.format(out=rel(out))}` first")
    ref = read_rgb(d / "full" / "reference.png")
    full = read_rgb(d / "full" / "rtl.png")
    red = read_rgb(d / "reduced" / "rtl.png")
    dfull = read_rgb(d / "full" / "difference.png")
    dred = read_rgb(d / "reduced" / "difference.png")
    if (d / "reduced" / "reference.png").exists():
        ref2 = read_rgb(d / "reduced" / "reference.png")
        if ref2.shape != ref.shape or np.any(ref2 != ref):
            progress(f"fig11: warning: {name}: full/reference.png and reduced/reference.png differ; "
                     "using full's")
    if not (ref.shape == full.shape == red.shape == dfull.shape == dred.shape):
        raise InputMissing(f"{rel(d)}: images of different sizes: run `{REGRESS_CMD.format(out=rel(out))}` again")
    ef, er = runs.get((name, "full")), runs.get((name, "reduced"))
    for prof, e in (("full", ef), ("reduced", er)):
        if e is None:
            progress(f"fig11: warning: {rel(out / 'regress.json')} has no {name} x {prof} entry (PSNR n/a)")
        elif (e.get("width"), e.get("height")) != (ref.shape[1], ref.shape[0]):
            progress(f"fig11: warning: {name} x {prof}: regress.json is for {e.get('width')}x{e.get('height')}, "
                     f"the images are {ref.shape[1]}x{ref.shape[0]}: stale? rerun the regression")
    return dict(name=name, ref=ref, full=full, red=red, dfull=dfull, dred=dred, ef=ef, er=er)


def scene_image(out: Path, r: dict):
    """One scene: 3 x 2 tiles at native size, the scene's name and the bit-exactness in the corner."""
    name, ref, full, red, dfull, dred, ef, er = (r[k] for k in ("name", "ref", "full", "red", "dfull", "dred",
                                                              "ef", "er"))
    h, w = ref.shape[:2]
    gap, head = 8, 30
    c = Canvas(3 * w + 4 * gap, 2 * (h + head) + 3 * gap)
    tiles = [
        (0, 0, ref, "reference (double precision)"),
        (1, 0, full, f"full{gates_label(out, 'full', '1.25M')}: {fmt_db(ef)} dB"),
        (2, 0, red, f"reduced{gates_label(out, 'reduced', '100k')}: {fmt_db(er)} dB"),
        (1, 1, dfull, "|full - reference| x 8"),
        (2, 1, dred, "|reduced - reference| x 8"),
    ]
    for col, row, img, label in tiles:
        x = gap + col * (w + gap)
        y = gap + row * (h + head + gap)
        c.text(x + 4, y + 21, label, 19)
        c.paste(img, x, y + head)
    x, y = gap, gap + (h + head + gap) + head
    fig = PAPER_FIGURE.get(name, "")
    c.text(x + 12, y + 40, f"{name}", 30)
    if fig:
        in11 = name in PAPER_ORDER[:6]
        c.text(x + 12, y + 76, f"paper {fig}" + ("; reduced: Fig. 11" if in11 else ""), 20)
    exact = [e.get("passed") and e.get("mismatches") == 0 for e in (ef, er) if e]
    if len(exact) == 2 and all(exact):
        c.text(x + 12, y + 116, "RTL images, bit-exact", 18, (0.75, 0.75, 0.75))
        c.text(x + 12, y + 140, "against the golden model.", 18, (0.75, 0.75, 0.75))
    elif not all(exact):
        c.text(x + 12, y + 116, "RTL DIFFERS from the", 18, (1.0, 0.4, 0.4))
        c.text(x + 12, y + 140, "golden model (regress.json).", 18, (1.0, 0.4, 0.4))
    c.text(x + 12, y + 176, "Bottom row: per-channel", 18, (0.75, 0.75, 0.75))
    c.text(x + 12, y + 200, "|RTL - reference| x 8.", 18, (0.75, 0.75, 0.75))
    return c.finish()


def overview_image(rows: list):
    """Every scene, one row each, five columns."""
    T, gap, head, side = 200, 6, 28, 130
    cols = ["reference", "full (1.25M)", "reduced (100k)", "|full - ref| x8", "|reduced - ref| x8"]
    c = Canvas(side + 5 * (T + gap) + gap, head + len(rows) * (T + gap) + gap)
    for k, label in enumerate(cols):
        c.text(side + gap + k * (T + gap) + T // 2, head - 8, label, 16, align="center")
    for i, r in enumerate(rows):
        y = head + gap + i * (T + gap)
        c.text(8, y + T // 2 - 6, r["name"], 15)
        fig = PAPER_FIGURE.get(r["name"], "")
        c.text(8, y + T // 2 + 14, fig, 14, (0.7, 0.7, 0.7))
        c.text(8, y + T // 2 + 34, f"{fmt_db(r['ef'])} / {fmt_db(r['er'])} dB", 12, (0.7, 0.7, 0.7))
        for k, key in enumerate(("ref", "full", "red", "dfull", "dred")):
            img = fit(r[key], T, T)
            x = side + gap + k * (T + gap) + (T - img.shape[1]) // 2
            c.paste(img, x, y + (T - img.shape[0]) // 2)
    return c.finish()


def captions(out: Path, rows: list) -> str:
    """fig11.md."""
    size = f"{rows[0]['ref'].shape[1]} x {rows[0]['ref'].shape[0]}"
    md = []
    md.append("# Figure 11: 100,000-gate simulations of Figures 1 through 6\n")
    def describe(name):
        f = profile_path(name)
        # Clocks per pixel as the RTL runs measured them (the regress entries), not recomputed.
        cpps = [e["cycles_per_pixel"] for r in rows for e in (r["ef"], r["er"])
                if e and e.get("profile") == name and "cycles_per_pixel" in e]
        clocks = f", {max(cpps):.0f} clock{'s' if max(cpps) >= 1.5 else ''} per pixel (RTL)" if cpps else ""
        try:
            p = tomllib.loads(f.read_text())
            pp, nz, fm = p["pipeline"], p["noise"], p["formats"]
            return (f"{pp['octaves']} octaves through {pp['noise_units']} noise unit"
                    f"{'s' if pp['noise_units'] > 1 else ''} ({pp['noise_steps']} cycle"
                    f"{'s' if pp['noise_steps'] > 1 else ''} per evaluation, {pp['datapath']} datapath{clocks}), "
                    f"{nz['interp']} interpolation, {nz['hash']} hash, {nz['out_frac']}-bit noise fraction, "
                    f"{fm['coord']['frac']} fraction bits of texture coordinate, |grad| by {p['filter']['norm']}")
        except (OSError, tomllib.TOMLDecodeError, KeyError, TypeError, ZeroDivisionError):
            return f"see rtl/configs/{name}.toml"

    checked = [e for r in rows for e in (r["ef"], r["er"]) if e]
    failed = [f"{Path(e['scene']).stem} x {e['profile']}" for e in checked
              if not (e.get("passed") and e.get("mismatches") == 0)]
    if failed:
        bitexact = "**the RTL did NOT match the golden model in " + ", ".join(failed) + "**"
    elif len(checked) == 2 * len(rows):
        bitexact = "every RTL pixel matched the golden fixed-point model bit for bit"
    else:
        bitexact = "the runs present in regress.json matched the golden model bit for bit"
    md.append(
        f"Every scene rendered at {size} through the verilated RTL of both hardware profiles "
        f"(`{REGRESS_CMD.format(out=rel(out))}`; {bitexact}) next to the double-precision reference. "
        f"**full** (rtl/configs/full.toml, the paper's ~1.25M-gate model): {describe('full')}. "
        f"**reduced** (rtl/configs/reduced.toml, the paper's 100k-gate model): {describe('reduced')}. "
        "The bottom row is |RTL - reference| per channel, amplified x8 and clamped.\n")
    md.append(
        "PSNR is over RGB of the whole image (background included) against the reference, 8 bits per "
        "channel; \"within 1 LSB\" is the share of pixels whose three channels are all within one 8-bit step. "
        "The reduced profile's PSNR is low mainly because its noise is a *different* noise function (another "
        "hash, another interpolant, fewer octaves), not a noisy copy of the full one: its textures keep the "
        "character of the full ones (top row) while the pixel-wise difference is large (measured once, not "
        "regenerated by this script: the reduced formats with the full profile's SCURVE interpolation and "
        "Rayshade hash give 41.8, 46.3 and 49.9 dB on marble, fire and wood_teapot; with linear interpolation "
        "and the Rayshade hash 23.5, 29.1 and 32.0 dB). Fewer octaves make "
        "the planet, sky, water and moonrise smoother and less detailed, as the paper reports; the "
        "rectilinear lattice the paper sees in the reduced flame is only faint in these stills.\n")
    md.append("![Figure 11 overview](fig11.png)\n")
    md.append("*Overview: one row per scene; columns reference | full | reduced | |full - reference| x8 | "
              "|reduced - reference| x8; the left column gives full / reduced PSNR in dB.*\n")
    md.append("| scene | paper | full PSNR dB | full within 1 LSB % | reduced PSNR dB | reduced within 1 LSB % | "
              "RTL = golden |")
    md.append("|---|---|---|---|---|---|---|")
    for r in rows:
        ok = [e.get("passed") and e.get("mismatches") == 0 for e in (r["ef"], r["er"]) if e]
        bit = "yes" if ok and all(ok) and len(ok) == 2 else ("n/a" if not ok else "**NO**")
        md.append(f"| {r['name']} | {PAPER_FIGURE.get(r['name'], '-')} | {fmt_db(r['ef'])} | {fmt_pct(r['ef'])} | "
                  f"{fmt_db(r['er'])} | {fmt_pct(r['er'])} | {bit} |")
    md.append("")
    for r in rows:
        fig = PAPER_FIGURE.get(r["name"], "")
        md.append(f"## {r['name']}" + (f" ({fig})" if fig else "") + "\n")
        md.append(f"![{r['name']}: reference, full, reduced](fig11_{r['name']}.png)\n")
        md.append(f"*Top: reference (double precision) | full RTL ({fmt_db(r['ef'])} dB, {fmt_pct(r['ef'])} % "
                  f"within 1 LSB) | reduced RTL ({fmt_db(r['er'])} dB, {fmt_pct(r['er'])} % within 1 LSB). "
                  f"Bottom, under each profile: |RTL - reference| x8.*\n")
        notes = (r["er"] or {}).get("notes") or []
        if notes:
            md.append("Driver notes for reduced: " + " ".join(n.strip() for n in notes) + "\n")
    if not Canvas.labelled():
        md.append("*(No font was usable for labels inside the images: read them from the captions.)*\n")
    return "\n".join(md)


def fig11(args):
    out = Path(args.out)
    figdir = out / "figures"
    runs = load_regress(out / "regress.json")
    scenes = []
    if out.is_dir():
        for d in out.iterdir():
            if d.is_dir() and (d / "full" / "rtl.png").exists() and (d / "reduced" / "rtl.png").exists():
                scenes.append(d.name)
    if not scenes:
        raise InputMissing(f"no {rel(out)}/<scene>/full/rtl.png with {rel(out)}/<scene>/reduced/rtl.png: run "
                           f"`{REGRESS_CMD.format(out=rel(out))}` first")
    scenes.sort(key=scene_order)
    progress(f"fig11: {len(scenes)} scenes: {', '.join(scenes)}")
    rows = []
    for n, name in enumerate(scenes, 1):
        rows.append(scene_row(out, name, runs))
        path = figdir / f"fig11_{name}.png"
        write_png(path, scene_image(out, rows[-1]))
        progress(f"fig11: [{n}/{len(scenes)}] {rel(path)}")
    path = figdir / "fig11.png"
    write_png(path, overview_image(rows))
    progress(f"fig11: {rel(path)}")
    path = figdir / "fig11.md"
    atomic.write_text(path, captions(out, rows))
    progress(f"fig11: {rel(path)}")
    return 0
