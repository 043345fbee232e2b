#!/usr/bin/python3
"""The paper's Figures 10 and 11 from the simulator's images.

    /usr/bin/python3 scripts/figures.py fig11 --out out
        Needs `build/pst regress --size 512 -o out/regress.json --images out` first. Writes
        out/figures/fig11_<scene>.png (reference | full | reduced over |full - reference| and
        |reduced - reference|, differences x8), out/figures/fig11.png (every scene, one row
        each) and out/figures/fig11.md (captions, PSNR of full and reduced against the reference).

    /usr/bin/python3 scripts/figures.py fig10 --out out [--bits 4,6,8,10,12,16]
        Writes out/figures/fig10/coord_frac_<b>.toml (rtl/configs/full.toml with
        formats.coord.frac = b), renders scenes/precision.toml through the golden model of each
        (build/pst render --model golden), and builds out/figures/fig10.png (each precision over
        a zoomed crop) and out/figures/fig10.md (captions, PSNR per precision).

Inputs missing: a message naming the command to run first, exit status 2. Every output file is
written to a temporary name in its folder and renamed into place.
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import time
import tomllib
from pathlib import Path

import numpy as np
import OpenImageIO as oiio

ROOT = Path(__file__).resolve().parent.parent
REGRESS_CMD = "build/pst regress --size 512 -o {out}/regress.json --images {out}"
BUILD_CMD = "cmake --build build --target pst -j2"

# The paper's figures, in its order; other scenes follow alphabetically.
PAPER_FIGURE = {
    "wood_teapot": "Fig. 1", "marble": "Fig. 2", "seascape": "Fig. 3", "fire": "Fig. 4",
    "planet": "Fig. 5", "moonrise": "Fig. 6", "zoneplate": "Fig. 8", "wood_torus": "Fig. 9",
    "precision": "Fig. 10",
}
PAPER_ORDER = list(PAPER_FIGURE)

CANVAS = (24, 24, 28)       # background of the mosaics
HEADER_FG = (1.0, 1.0, 1.0)
FONTS = [
    "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/truetype/liberation2/LiberationSans-Regular.ttf",
    "/usr/share/fonts/truetype/liberation/LiberationSans-Regular.ttf",
    "/usr/share/fonts/truetype/lato/Lato-Regular.ttf",
]


class InputMissing(Exception):
    """An input file is missing or unusable: exit status 2."""


def progress(msg):
    print(f"figures: {msg}", file=sys.stderr, flush=True)


def rel(p):
    try:
        return str(Path(p).resolve().relative_to(Path.cwd()))
    except ValueError:
        return str(p)


# ---------------------------------------------------------------------------------------------
# Files: atomic writes, image I/O


def atomic_write_text(path, text):
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    try:
        tmp.write_text(text)
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()


def atomic_write_png(path, rgb):
    """rgb: H x W x 3 uint8."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.stem}.{os.getpid()}.tmp.png")
    h, w, c = rgb.shape
    buf = oiio.ImageBuf(oiio.ImageSpec(w, h, c, oiio.UINT8))
    buf.set_pixels(oiio.ROI(0, w, 0, h, 0, 1, 0, c), np.ascontiguousarray(rgb))
    try:
        if not buf.write(str(tmp)):
            raise RuntimeError(f"{path}: cannot write: {buf.geterror()}")
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()


def read_rgb(path):
    buf = oiio.ImageBuf(str(path))
    px = buf.get_pixels(oiio.UINT8)
    if buf.has_error or px is None or px.ndim != 3:
        raise InputMissing(f"{rel(path)}: cannot read image: {buf.geterror()}")
    if px.shape[2] == 1:
        px = np.repeat(px, 3, axis=2)
    return np.ascontiguousarray(px[:, :, :3])


def resize(rgb, w, h):
    """Filtered resize (downscaling) to w x h."""
    if rgb.shape[1] == w and rgb.shape[0] == h:
        return rgb
    src = oiio.ImageBuf(oiio.ImageSpec(rgb.shape[1], rgb.shape[0], 3, oiio.UINT8))
    src.set_pixels(src.roi, np.ascontiguousarray(rgb))
    dst = oiio.ImageBufAlgo.resize(src, roi=oiio.ROI(0, w, 0, h, 0, 1, 0, 3))
    return dst.get_pixels(oiio.UINT8)[:, :, :3]


def fit(rgb, box_w, box_h):
    """Scale to fit a box, keeping the aspect ratio."""
    h, w = rgb.shape[:2]
    k = min(box_w / w, box_h / h)
    return resize(rgb, max(1, round(w * k)), max(1, round(h * k)))


def zoom_nearest(rgb, w, h):
    """Nearest-neighbour resize to w x h (pixels stay visible as blocks)."""
    ys = np.minimum((np.arange(h) * rgb.shape[0]) // h, rgb.shape[0] - 1)
    xs = np.minimum((np.arange(w) * rgb.shape[1]) // w, rgb.shape[1] - 1)
    return rgb[ys][:, xs]


def draw_box(rgb, x0, y0, x1, y1, colour, t=2):
    """Rectangle outline [x0, x1) x [y0, y1), t pixels thick, inside the box."""
    c = np.array(colour, np.uint8)
    rgb[y0:y0 + t, x0:x1] = c
    rgb[y1 - t:y1, x0:x1] = c
    rgb[y0:y1, x0:x0 + t] = c
    rgb[y0:y1, x1 - t:x1] = c


# ---------------------------------------------------------------------------------------------
# Canvas with text labels (OpenImageIO render_text; labels dropped when no font works)


class Canvas:
    font = None            # path of a working font, or "" when none works
    font_checked = False

    def __init__(self, w, h):
        self.px = np.empty((h, w, 3), np.uint8)
        self.px[:] = CANVAS
        self.labels = []

    def paste(self, rgb, x, y):
        h, w = rgb.shape[:2]
        self.px[y:y + h, x:x + w] = rgb

    def text(self, x, y, s, size=16, colour=HEADER_FG, align="left"):
        """Baseline at y."""
        self.labels.append((x, y, s, size, colour, align))

    @classmethod
    def find_font(cls):
        if cls.font_checked:
            return cls.font
        cls.font_checked = True
        cls.font = ""
        probe = oiio.ImageBuf(oiio.ImageSpec(64, 32, 3, oiio.FLOAT))
        candidates = list(FONTS)
        try:
            r = subprocess.run(["fc-match", "-f", "%{file}", "sans"], capture_output=True, text=True, timeout=10)
            if r.returncode == 0 and r.stdout:
                candidates.append(r.stdout.strip())
        except (OSError, subprocess.SubprocessError):
            pass
        for f in candidates:
            if Path(f).exists() and oiio.ImageBufAlgo.render_text(probe, 2, 20, "A", 12, f, (1, 1, 1)):
                cls.font = f
                break
        if not cls.font:
            progress("no font works with OpenImageIO's render_text: images unlabelled, labels in the captions")
        return cls.font

    def finish(self):
        font = self.find_font()
        if not self.labels or not font:
            return self.px
        h, w = self.px.shape[:2]
        buf = oiio.ImageBuf(oiio.ImageSpec(w, h, 3, oiio.UINT8))
        buf.set_pixels(buf.roi, self.px)
        for x, y, s, size, colour, align in self.labels:
            oiio.ImageBufAlgo.render_text(buf, int(x), int(y), s, int(size), font, tuple(colour), align)
        return buf.get_pixels(oiio.UINT8)[:, :, :3]

    @classmethod
    def labelled(cls):
        return bool(cls.find_font())


# ---------------------------------------------------------------------------------------------
# Figure 11: 100,000-gate simulations of Figures 1-6


def scene_order(name):
    return (PAPER_ORDER.index(name) if name in PAPER_ORDER else len(PAPER_ORDER), name)


def load_regress(path):
    if not path.exists():
        raise InputMissing(f"{rel(path)} is missing: run `{REGRESS_CMD.format(out=rel(path.parent))}` first")
    try:
        entries = json.loads(path.read_text())
    except (OSError, json.JSONDecodeError) as e:
        raise InputMissing(f"{rel(path)}: not a regression summary ({e}): run "
                           f"`{REGRESS_CMD.format(out=rel(path.parent))}` again")
    if not isinstance(entries, list):
        raise InputMissing(f"{rel(path)}: expected a list of runs")
    runs = {}
    for e in entries:
        try:
            runs[(Path(e["scene"]).stem, e["profile"])] = e
        except (KeyError, TypeError):
            raise InputMissing(f"{rel(path)}: an entry without 'scene' and 'profile'")
    return runs


def fmt_db(e):
    if e is None:
        return "n/a"
    p = e.get("vs_reference", {}).get("psnr")
    return "n/a" if p is None else ("inf" if p == float("inf") else f"{p:.2f}")


def fmt_pct(e):
    if e is None:
        return "n/a"
    p = e.get("vs_reference", {}).get("within_1lsb_percent")
    return "n/a" if p is None else f"{p:.2f}"


def gates_label(out: Path, profile: str, paper: str) -> str:
    """", 98.3k GE (paper 100k)" from out/synth/<profile>.json when synthesized, else
    " (paper: 100k gates)": the label never claims a count that was not measured."""
    try:
        ge = json.loads((out / "synth" / f"{profile}.json").read_text())["logic_ge"]
        text = f"{ge / 1e6:.2f}M" if ge >= 1e6 else f"{ge / 1e3:.1f}k"
        return f", {text} GE (paper {paper})"
    except (OSError, ValueError, KeyError, TypeError):
        return f" (paper: {paper} gates)"


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
        rows.append(dict(name=name, ref=ref, full=full, red=red, dfull=dfull, dred=dred, ef=ef, er=er))

        # One scene: 3 x 2 tiles at native size.
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
        path = figdir / f"fig11_{name}.png"
        atomic_write_png(path, c.finish())
        progress(f"fig11: [{n}/{len(scenes)}] {rel(path)}")

    # Overview: one row per scene, five columns.
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
    path = figdir / "fig11.png"
    atomic_write_png(path, c.finish())
    progress(f"fig11: {rel(path)}")

    # Captions.
    size = f"{rows[0]['ref'].shape[1]} x {rows[0]['ref'].shape[0]}"
    md = []
    md.append("# Figure 11: 100,000-gate simulations of Figures 1 through 6\n")
    def describe(name):
        f = ROOT / "rtl" / "configs" / f"{name}.toml"
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
    path = figdir / "fig11.md"
    atomic_write_text(path, "\n".join(md))
    progress(f"fig11: {rel(path)}")
    return 0


# ---------------------------------------------------------------------------------------------
# Figure 10: texture-coordinate precision


FORMAT_LINE = r"^(\s*{key}\s*=\s*\{{\s*int\s*=\s*)(\d+)(\s*,\s*frac\s*=\s*)(\d+)(\s*\}})"
INT_LINE = r"^(\s*{key}\s*=\s*)(\d+)"


def set_format_frac(text, key, frac):
    pat = re.compile(FORMAT_LINE.format(key=re.escape(key)), re.M)
    text, n = pat.subn(lambda m: f"{m.group(1)}{m.group(2)}{m.group(3)}{frac}{m.group(5)}", text, count=1)
    if n != 1:
        raise InputMissing(f"base profile: no line `{key} = {{ int = I, frac = F }}`")
    return text


def set_int(text, key, value):
    pat = re.compile(INT_LINE.format(key=re.escape(key)), re.M)
    text, n = pat.subn(lambda m: f"{m.group(1)}{value}", text, count=1)
    if n != 1:
        raise InputMissing(f"base profile: no line `{key} = N`")
    return text


def profile_for_bits(base_text, base, b, base_path):
    """The base profile with formats.coord.frac = b, plus what must follow (returned as notes)."""
    fm, nz = base["formats"], base["noise"]
    coord_int = fm["coord"]["int"]
    if coord_int + b > 40:
        raise ValueError(f"coord.frac = {b}: int + frac = {coord_int + b} exceeds the 40-bit coordinate format")
    acc = fm["matrix"]["frac"] + b           # fraction bits of M s in the octave transform
    if acc < 1:
        raise ValueError(f"coord.frac = {b}: matrix.frac + coord.frac = {acc} leaves no lattice fraction bit")
    notes = []
    text = set_format_frac(base_text, "coord", b)
    # rtl/pst_octave_transform.sv and model/golden/noise_fx.cpp:
    #   MatrixFrac + CoordFrac >= NoiseLatticeFrac and >= OffsetFrac.
    if nz["lattice_frac"] > acc:
        text = set_int(text, "lattice_frac", acc)
        notes.append(f"noise.lattice_frac {nz['lattice_frac']} -> {acc}")
    if fm["offset"]["frac"] > acc:
        text = set_format_frac(text, "offset", acc)
        notes.append(f"formats.offset.frac {fm['offset']['frac']} -> {acc}")
    header = (f"# Generated by scripts/figures.py fig10: {base_path} with formats.coord.frac = {b}"
              + (f" ({'; '.join(notes)}, required by MatrixFrac + CoordFrac >= NoiseLatticeFrac, OffsetFrac)"
                 if notes else "") + ".\n# Read by the golden model only (build/pst render --model golden).\n")
    text = header + text
    check = tomllib.loads(text)
    assert check["formats"]["coord"] == {"int": coord_int, "frac": b}, "profile rewrite failed"
    return text, notes


def pixel_footprint(pst, scene, tmpdir):
    """Median and 10/90th percentiles of texture units per pixel (max of |ds/dx|, |ds/dy|)."""
    frag = tmpdir / ".precision.frag"
    r = subprocess.run([str(pst), "fragments", str(scene), "-o", str(frag)], capture_output=True, text=True)
    try:
        if r.returncode != 0:
            progress(f"fig10: warning: pst fragments failed ({r.stderr.strip()}); no footprint in the caption")
            return None
        a = np.loadtxt(frag, comments="#", ndmin=2)
    finally:
        if frag.exists():
            frag.unlink()
    if a.size == 0:
        return None
    fx = np.linalg.norm(a[:, 3:6], axis=1)
    fy = np.linalg.norm(a[:, 6:9], axis=1)
    u = np.maximum(fx, fy)
    return tuple(float(np.percentile(u, q)) for q in (10, 50, 90))


def parse_bits(s):
    try:
        bits = [int(x) for x in s.split(",") if x.strip()]
    except ValueError:
        raise argparse.ArgumentTypeError(f"--bits: expected comma-separated integers, got '{s}'")
    if not bits or any(b < 0 for b in bits):
        raise argparse.ArgumentTypeError("--bits: expected non-negative integers")
    return sorted(set(bits))


def parse_crop(s):
    try:
        v = [int(x) for x in s.split(",")]
    except ValueError:
        v = []
    if len(v) != 4 or v[2] <= 0 or v[3] <= 0 or v[0] < 0 or v[1] < 0:
        raise argparse.ArgumentTypeError("--crop: expected X,Y,W,H (pixels of a 512 x 512 image)")
    return v


def fig10(args):
    out = Path(args.out)
    figdir = out / "figures"
    workdir = figdir / "fig10"
    pst = Path(args.pst)
    scene = Path(args.scene)
    base_path = Path(args.base)
    if not pst.exists():
        raise InputMissing(f"{rel(pst)} is missing: build it first (`{BUILD_CMD}`)")
    if not scene.exists():
        raise InputMissing(f"{rel(scene)} is missing (the Figure 10 scene; see scenes/README.md)")
    if not base_path.exists():
        raise InputMissing(f"{rel(base_path)} is missing (the base hardware profile)")
    base_text = base_path.read_text()
    try:
        base = tomllib.loads(base_text)
        base["formats"]["coord"]["int"], base["formats"]["matrix"]["frac"]
        base["formats"]["offset"]["frac"], base["noise"]["lattice_frac"]
    except (tomllib.TOMLDecodeError, KeyError, TypeError) as e:
        raise InputMissing(f"{rel(base_path)}: not a hardware profile ({e})")
    base_frac = base["formats"]["coord"]["frac"]
    workdir.mkdir(parents=True, exist_ok=True)

    results = []
    t_all = time.monotonic()
    for n, b in enumerate(args.bits, 1):
        try:
            text, notes = profile_for_bits(base_text, base, b, rel(base_path))
        except ValueError as e:
            raise InputMissing(f"--bits: {e}")
        prof = workdir / f"coord_frac_{b}.toml"
        atomic_write_text(prof, text)
        dest = workdir / f"coord_frac_{b}"
        tmp = workdir / f".coord_frac_{b}.{os.getpid()}.tmp"
        if tmp.exists():
            shutil.rmtree(tmp)
        cmd = [str(pst), "render", str(scene), "--profile", str(prof), "--model", "golden", "-o", str(tmp), "-q",
               "-j", str(args.threads)]
        progress(f"fig10: [{n}/{len(args.bits)}] coord.frac = {b}: {' '.join(rel(c) if '/' in c else c for c in cmd)}")
        t0 = time.monotonic()
        r = subprocess.run(cmd, capture_output=True, text=True)
        if r.returncode != 0:
            shutil.rmtree(tmp, ignore_errors=True)
            sys.stderr.write(r.stderr)
            print(f"error: fig10: pst render failed for coord.frac = {b} (exit {r.returncode})", file=sys.stderr)
            return 1
        if dest.exists():
            shutil.rmtree(dest)
        os.replace(tmp, dest)
        summ = json.loads((dest / "summary.json").read_text())
        vs = summ["vs_reference"]
        results.append(dict(bits=b, notes=notes, dir=dest, psnr=vs["psnr"], within=vs["within_1lsb_percent"],
                            maxlsb=vs["max_lsb"], seconds=time.monotonic() - t0))
        progress(f"fig10:   PSNR {vs['psnr']:.2f} dB, {vs['within_1lsb_percent']:.2f} % within 1 LSB "
                 f"({time.monotonic() - t0:.1f} s)")
    progress(f"fig10: {len(results)} renders in {time.monotonic() - t_all:.1f} s")

    foot = pixel_footprint(pst, scene, workdir)

    # Mosaic: each precision and the reference; full image (crop marked) over the zoomed crop.
    ref = read_rgb(results[0]["dir"] / "reference.png")
    panels = [(f"{r['bits']} fraction bits: {r['psnr']:.1f} dB", read_rgb(r["dir"] / "golden.png")) for r in results]
    panels.append(("reference (double precision)", ref))
    h, w = ref.shape[:2]
    k = w / 512.0
    crops = [[round(v * k) for v in cr] for cr in args.crop]
    for cr in crops:
        cr[2] = min(cr[2], w - cr[0])
        cr[3] = min(cr[3], h - cr[1])
        if cr[2] <= 0 or cr[3] <= 0:
            raise InputMissing(f"--crop {cr} lies outside the {w} x {h} image")
    T = args.tile
    ncrop = len(crops)
    ch = T // ncrop if ncrop > 1 else T                         # crop tiles side by side under the image
    cols = min(args.columns, len(panels))
    nrows = (len(panels) + cols - 1) // cols
    gap, head = 10, 30
    crop_h = max(round(ch * cr[3] / cr[2]) for cr in crops)
    cell_h = head + T + 4 + crop_h
    c = Canvas(cols * (T + gap) + gap, nrows * (cell_h + gap) + gap)
    colours = [(255, 220, 40), (60, 220, 255), (255, 90, 200)]
    for i, (label, img) in enumerate(panels):
        x = gap + (i % cols) * (T + gap)
        y = gap + (i // cols) * (cell_h + gap)
        c.text(x + 2, y + 21, label, 18)
        small = fit(img, T, T)
        sk = small.shape[1] / w
        small = small.copy()
        for j, (cx, cy, cw, chh) in enumerate(crops):
            draw_box(small, int(cx * sk), int(cy * sk), int(round((cx + cw) * sk)), int(round((cy + chh) * sk)),
                     colours[j % len(colours)], 2)
        c.paste(small, x + (T - small.shape[1]) // 2, y + head)
        cw_each = T // ncrop
        for j, (cx, cy, cw, chh) in enumerate(crops):
            crop = img[cy:cy + chh, cx:cx + cw]
            zc = zoom_nearest(crop, cw_each, round(cw_each * chh / cw)).copy()
            draw_box(zc, 0, 0, zc.shape[1], zc.shape[0], colours[j % len(colours)], 2)
            c.paste(zc, x + j * cw_each, y + head + T + 4)
    path = figdir / "fig10.png"
    atomic_write_png(path, c.finish())
    progress(f"fig10: {rel(path)}")

    # Captions.
    adjusted = [r for r in results if r["notes"]]
    md = ["# Figure 10: the effect of numerical precision on texture appearance\n"]
    md.append(
        f"`{rel(scene)}` ({w} x {h} pixels: a teapot of subdivision 2, an 8 x 5 sphere and a slab, "
        "textured with magnified wood (eq. 5) and marble (eq. 7)) rendered through the bit-accurate golden "
        f"model of `{rel(base_path)}` with the texture-coordinate format `formats.coord` changed to "
        f"{base['formats']['coord']['int']} integer bits (as in the base profile) and b fraction bits, "
        f"b = {', '.join(str(r['bits']) for r in results)} (the base profile has {base_frac}). "
        "The driver rounds each pixel's s, t, r to the nearest multiple of 2^-b, so the texture is "
        "constant over every cube of side 2^-b in texture space: where the texture is magnified that cube "
        "covers many pixels and the image shows blocks and stair-stepped ring and vein edges. "
        "Below each image, the marked regions (" + ", ".join(f"{cw} x {chh} pixels at ({cx}, {cy})" for cx, cy, cw, chh in crops)
        + ") enlarged by nearest neighbour so the steps are visible at report size. The last panel is the "
        "double-precision reference.\n")
    if foot:
        lo, med, hi = foot
        md.append(
            f"Texture units per pixel in this scene (max of |ds/dx|, |ds/dy|): median {med:.2e} "
            f"(10th-90th percentile {lo:.2e} - {hi:.2e}), so one coordinate step of 2^-b spans about "
            + ", ".join(f"{2.0 ** -r['bits'] / med:.3g} px at b = {r['bits']}" for r in results) + ".\n")
    if adjusted:
        md.append("Constraint MatrixFrac + CoordFrac >= NoiseLatticeFrac, OffsetFrac (rtl/pst_octave_transform.sv, "
                  "model/golden/noise_fx.cpp) forced: " + "; ".join(f"b = {r['bits']}: {', '.join(r['notes'])}"
                                                                   for r in adjusted) + ".\n")
    else:
        fmb = base["formats"]
        need = max(base["noise"]["lattice_frac"], fmb["offset"]["frac"]) - fmb["matrix"]["frac"]
        md.append(f"No other field had to change: the octave transform (rtl/pst_octave_transform.sv, "
                  f"model/golden/noise_fx.cpp) needs MatrixFrac + CoordFrac >= NoiseLatticeFrac and >= "
                  f"OffsetFrac; with MatrixFrac = {fmb['matrix']['frac']}, NoiseLatticeFrac = "
                  f"{base['noise']['lattice_frac']} and OffsetFrac = {fmb['offset']['frac']} that holds for every "
                  f"b >= {max(0, need)}.\n")
    md.append("![Figure 10](fig10.png)\n")
    md.append("| coord fraction bits b | step 2^-b (texture units) | PSNR dB | within 1 LSB % | max LSB | profile |")
    md.append("|---|---|---|---|---|---|")
    for r in results:
        md.append(f"| {r['bits']} | {2.0 ** -r['bits']:.3g} | {r['psnr']:.2f} | {r['within']:.2f} | {r['maxlsb']:.0f} | "
                  f"`fig10/coord_frac_{r['bits']}.toml` |")
    regress = out / "regress.json"
    if regress.exists() and base_path.resolve() == (ROOT / "rtl" / "configs" / "full.toml").resolve():
        try:
            e = load_regress(regress).get((scene.stem, "full"))
        except InputMissing:
            e = None
        if e:
            md.append(f"| {base_frac} (full profile, RTL from regress.json) | {2.0 ** -base_frac:.3g} | "
                      f"{fmt_db(e)} | {fmt_pct(e)} | {e['vs_reference'].get('max_lsb', 0):.0f} | "
                      f"`{rel(base_path)}` |")
    md.append("")
    md.append("PSNR over RGB of the whole image (background included) against the double-precision reference, "
              "8 bits per channel; in the enlarged crops every 4 x 4 block is one pixel, the larger stairs are "
              "the coordinate steps. Images: "
              "`fig10/coord_frac_<b>/golden.png` (with `difference.png` x8 and `summary.json`).\n")
    if not Canvas.labelled():
        md.append("*(No font was usable for labels inside the image: panels are in the order of the table, "
                  "then the reference.)*\n")
    path = figdir / "fig10.md"
    atomic_write_text(path, "\n".join(md))
    progress(f"fig10: {rel(path)}")
    return 0


def main(argv=None):
    ap = argparse.ArgumentParser(description="Figures 10 and 11 of Hart et al. 1999 from the simulator's images.")
    sub = ap.add_subparsers(dest="cmd", required=True)
    a11 = sub.add_parser("fig11", help="reference | full | reduced of every regressed scene")
    a11.add_argument("--out", default="out", help="output folder of the regression (default out)")
    a10 = sub.add_parser("fig10", help="texture-coordinate precision sweep through the golden model")
    a10.add_argument("--out", default="out", help="output folder (default out)")
    a10.add_argument("--bits", type=parse_bits, default=parse_bits("4,6,8,10,12,16"),
                     help="coord fraction bits to render (default 4,6,8,10,12,16)")
    a10.add_argument("--scene", default=str(ROOT / "scenes" / "precision.toml"))
    a10.add_argument("--base", default=str(ROOT / "rtl" / "configs" / "full.toml"), help="base profile")
    a10.add_argument("--pst", default=str(ROOT / "build" / "pst"))
    a10.add_argument("--threads", type=int, default=2, help="threads of each render (default 2)")
    a10.add_argument("--crop", type=parse_crop, action="append",
                     help="X,Y,W,H region to enlarge, in pixels of a 512 x 512 image (repeatable)")
    a10.add_argument("--tile", type=int, default=320, help="panel width in pixels (default 320)")
    a10.add_argument("--columns", type=int, default=4, help="panels per row (default 4)")
    args = ap.parse_args(argv)
    if args.cmd == "fig10" and not args.crop:
        # The 40 x 40 windows of largest error at 8 and 10 bits: a ring edge on the teapot's body
        # and marble veins on the slab's top.
        args.crop = [[132, 210, 40, 40], [228, 390, 40, 40]]
    try:
        return fig11(args) if args.cmd == "fig11" else fig10(args)
    except InputMissing as e:
        print(f"error: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
