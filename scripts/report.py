#!/usr/bin/python3
"""Collects out/<scene>/report.json files into one Markdown report (stdout)."""
import json
import pathlib
import sys


def main(out_dir: str) -> int:
    root = pathlib.Path(out_dir)
    reports = sorted(root.glob("*/report.json"))
    if not reports:
        print(f"error: no */report.json under {root}", file=sys.stderr)
        return 1
    print("# Reference renders\n")
    print("Ground truth: n x n jittered, unfiltered samples per pixel. RMS over RGB in [0, 1].\n")
    print("| scene | size | fragments | render s | truth s | RMS filtered vs truth | RMS unfiltered vs truth | images |")
    print("|---|---|---|---|---|---|---|---|")
    for path in reports:
        r = json.loads(path.read_text())
        name = path.parent.name
        vt = r.get("vs_truth", {})
        f = vt.get("filtered", {}).get("rms")
        u = vt.get("unfiltered", {}).get("rms")
        fmt = lambda v: "-" if v is None else f"{v:.4f}"
        sec = r["seconds"]
        imgs = " ".join(f"[{k}]({name}/{k}.png)" for k in ("filtered", "unfiltered", "width", "truth")
                        if (path.parent / f"{k}.png").exists())
        print(f"| {r['title']} | {r['width']}x{r['height']} | {r['fragments']} | "
              f"{sec['total'] - sec['truth']:.2f} | {sec['truth']:.2f} | {fmt(f)} | {fmt(u)} | {imgs} |")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "out"))
