#!/usr/bin/python3
"""Collects the main job's JSON files under out/ into one Markdown report (stdout)."""
import json
import pathlib
import re
import sys


def fmt(v, digits=4):
    return "-" if v is None else f"{v:.{digits}f}"


def reference_section(root: pathlib.Path) -> None:
    reports = sorted(root.glob("*/report.json"))
    print("## Reference renders\n")
    if not reports:
        print("(none)\n")
        return
    print("Ground truth: n x n jittered, unfiltered samples per pixel. RMS over RGB in [0, 1].\n")
    print("| scene | size | fragments | render s | truth s | RMS filtered vs truth | RMS unfiltered vs truth | images |")
    print("|---|---|---|---|---|---|---|---|")
    for path in reports:
        r = json.loads(path.read_text())
        name = path.parent.name
        vt = r.get("vs_truth", {})
        sec = r["seconds"]
        imgs = " ".join(f"[{k}]({name}/{k}.png)" for k in ("filtered", "unfiltered", "width", "truth")
                        if (path.parent / f"{k}.png").exists())
        print(f"| {r['title']} | {r['width']}x{r['height']} | {r['fragments']} | "
              f"{sec['total'] - sec['truth']:.2f} | {sec['truth']:.2f} | "
              f"{fmt(vt.get('filtered', {}).get('rms'))} | {fmt(vt.get('unfiltered', {}).get('rms'))} | {imgs} |")
    print()


def regress_section(root: pathlib.Path) -> None:
    path = root / "regress.json"
    print("## RTL regression\n")
    if not path.exists():
        print("(not run)\n")
        return
    runs = json.loads(path.read_text())
    failed = [r for r in runs if not r["passed"]]
    print(f"**{'FAILED' if failed else 'PASSED'}**: {len(runs)} runs, {len(failed)} with mismatches against the "
          "golden model. Error figures: RTL image against the double reference over RGB.\n")
    print("| scene | profile | pixels | mismatches | cycles/pixel | PSNR dB | within 1 LSB % | max LSB | RTL px/s | images |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for r in runs:
        name = pathlib.Path(r["scene"]).stem
        v = r["vs_reference"]
        d = f"{name}/{r['profile']}"
        imgs = " ".join(f"[{k}]({d}/{k}.png)" for k in ("rtl", "difference") if (root / d / f"{k}.png").exists())
        print(f"| {name} | {r['profile']} | {r['pixels_checked']} | {r['mismatches']} | {r['cycles_per_pixel']:.3f} | "
              f"{v['psnr']:.2f} | {v['within_1lsb_percent']:.2f} | {v['max_lsb']:.0f} | "
              f"{r['pixels_per_second']['rtl']:.0f} | {imgs} |")
    notes = sorted({n for r in runs for n in r.get("notes", [])})
    if notes:
        print("\nDriver notes (what the hardware does differently from the scene's request):\n")
        for n in notes:
            print(f"- {n}")
    print()


def include_markdown(title: str, path: pathlib.Path, missing: str, rebase: str = "") -> None:
    """Includes a Markdown file written by another script; its links are relative to its
    own folder, so they are re-based onto out/."""
    print(f"## {title}\n")
    if not path.exists():
        print(f"({missing})\n")
        return
    text = path.read_text()
    if rebase:
        text = re.sub(r"\]\((?!http)([^)]+)\)", lambda m: f"]({rebase}/{m.group(1)})", text)
    # Demote the included file's own headings below this section's.
    text = re.sub(r"^(#+) ", lambda m: "#" + m.group(1) + " ", text, flags=re.M)
    print(text)
    print()


def main(out_dir: str) -> int:
    root = pathlib.Path(out_dir)
    print("# pst: main job report\n")
    print("Contents: RTL regression (bit-exact against the golden model, error against the double "
          "reference), gate counts (Yosys), Figure 11 (reference | full | reduced), Figure 10 "
          "(texture-coordinate precision), the default precision sweep, the reference renders.\n")
    regress_section(root)
    for name in ("reduced", "full"):
        include_markdown(f"Gates: {name}", root / "synth" / f"{name}.md", "not synthesized: scripts/synth.py " + name)
    include_markdown("Figure 11", root / "figures" / "fig11.md", "not built: scripts/figures.py fig11", "figures")
    include_markdown("Figure 10", root / "figures" / "fig10.md", "not built: scripts/figures.py fig10", "figures")
    for sweep in sorted((root / "sweep").glob("*/sweep.md")):
        include_markdown(f"Precision sweep around {sweep.parent.name}", sweep, "", f"sweep/{sweep.parent.name}")
    reference_section(root)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "out"))
