"""Figures read off a routed block: die, cell area and utilization, cell and flip-flop
counts (LEF sizes, DEF components), total routed wirelength (DEF wiring), and a PNG of the
layout drawn by KLayout from the GDS."""
import os
import pathlib
import re
import subprocess

FILL = re.compile(r"^FILL")


def lef_sizes(lef_text: str) -> dict:
    """Macro -> (width, height) in µm."""
    out = {}
    for m in re.finditer(r"^MACRO\s+(\S+)(.*?)^END\s+\1", lef_text, re.M | re.S):
        s = re.search(r"\bSIZE\s+([\d.]+)\s+BY\s+([\d.]+)", m.group(2))
        if s:
            out[m.group(1)] = (float(s.group(1)), float(s.group(2)))
    return out


def def_figures(def_text: str, sizes: dict) -> dict:
    """Die (µm), cells without fillers, flip-flops, cell area and utilization, routed
    wirelength (µm, every ROUTED/NEW wire segment of every net; vias count zero)."""
    units = float(re.search(r"^UNITS DISTANCE MICRONS (\d+)", def_text, re.M).group(1))
    x0, y0, x1, y1 = (float(v) / units for v in
                      re.search(r"^DIEAREA \( (-?\d+) (-?\d+) \) \( (-?\d+) (-?\d+) \)", def_text, re.M).groups())
    comp = def_text[def_text.index("\nCOMPONENTS"):def_text.index("\nEND COMPONENTS")]
    cells = re.findall(r"^- (\S+) (\S+)", comp, re.M)
    logic = [(n, c) for n, c in cells if not FILL.match(c)]
    missing = sorted({c for _, c in logic if c not in sizes})
    if missing:
        raise ValueError(f"cells without a LEF size: {missing}")
    area = sum(sizes[c][0] * sizes[c][1] for _, c in logic)
    nets = def_text[def_text.index("\nNETS"):def_text.index("\nEND NETS")]
    wire = 0.0
    for stmt in re.findall(r"(?:ROUTED|NEW)\s+\S+((?:\s+\(\s*[-\d*]+\s+[-\d*]+(?:\s+[-\d]+)?\s*\))+)", nets):
        pts = re.findall(r"\(\s*([-\d*]+)\s+([-\d*]+)", stmt)
        px = py = None
        for xs, ys in pts:
            x = px if xs == "*" else float(xs)
            y = py if ys == "*" else float(ys)
            if px is not None:
                wire += abs(x - px) + abs(y - py)
            px, py = x, y
    die_w, die_h = x1 - x0, y1 - y0
    return {"die_um": [round(die_w, 1), round(die_h, 1)], "die_mm2": round(die_w * die_h / 1e6, 4),
            "cells": len(logic), "flip_flops": sum(1 for _, c in logic if c.startswith("DFF")),
            "cell_area_mm2": round(area / 1e6, 4), "utilization": round(area / (die_w * die_h), 3),
            "wirelength_mm": round(wire / units / 1000, 1)}


KLAYOUT_SHOT = """import pya
lv = pya.LayoutView()
lv.load_layout(gds, True)
lv.max_hier()
lv.zoom_fit()
lv.save_image(png, int(width), int(height))
"""


def png(gds: pathlib.Path, out: pathlib.Path, width: int = 1400, height: int = 1000) -> None:
    """The layout drawn by KLayout (batch mode, no display)."""
    script = out.with_suffix(".klayout.py")
    script.write_text(KLAYOUT_SHOT)
    env = dict(os.environ, QT_QPA_PLATFORM="offscreen")
    r = subprocess.run(["klayout", "-z", "-nc", "-rx", "-rd", f"gds={gds}", "-rd", f"png={out}",
                        "-rd", f"width={width}", "-rd", f"height={height}", "-r", str(script)],
                       capture_output=True, text=True, env=env, timeout=600)
    script.unlink()
    if r.returncode != 0 or not out.exists():
        raise RuntimeError(f"klayout could not draw {gds}: {r.stderr[-2000:]}")
