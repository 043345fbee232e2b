"""The power table (docs/POWER.md section power-table, docs/HARDWARE.md links to it) from
docs/data/power.json, which `scripts/power.py PROFILE --record` writes (every number there is
measured by that flow, none typed)."""
import json
from pathlib import Path

from .. import atomic
from . import docgen

SOURCE = Path("docs/data/power.json")


def load(root: Path) -> dict:
    return docgen.load_record(root, SOURCE, "profiles", "scripts/power.py PROFILE --record")


def _f(v, d=1) -> str:
    return "-" if v is None else f"{v:,.{d}f}"


def markdown(root: Path) -> str:
    d = load(root)["profiles"]
    L = ["Measured by `scripts/power.py PROFILE --record` (pre-layout netlist of scripts/synth.py, OpenSTA "
         "report_power at the typical corner, activity from the verilated RTL's traces of the paper scenes and "
         "random validation textures; the method is below). pJ/pixel: mean over the workloads (least - most); "
         "mW at the profile's pre-layout Fmax and at the real-time rate (copies: profiles side by side to reach "
         "it). Sequential: flip-flops with their clock pins. Memories: the area model of the ROMs and, where the "
         "record says so (RAM reads modelled: yes), of the RAMs' read ports (the method's step 6; a record "
         "measured before that model has the ROMs alone).", "",
         "| profile | workloads (image size) | pJ/pixel | least - most | Fmax (MHz) | mW at Fmax | mW at real time "
         "(copies) | leakage mW | sequential | memories | RAM reads modelled | top blocks (mW at the SDC clock) |",
         "|---|---:|---:|---|---:|---:|---:|---:|---:|---:|---|---|"]
    for name, p in d.items():
        s = p["summary"]
        blocks = ", ".join(f"{b} {_f(w)}" for b, w in list(s["blocks_mw_at_sdc_clock"].items())[:3])
        L.append(f"| {name} | {s['workloads']} ({p['window'].get('size', '-')}) | {_f(s['pj_per_pixel'], 0)} | {_f(s['pj_per_pixel_min'], 0)} - "
                 f"{_f(s['pj_per_pixel_max'], 0)} | {_f(s['fmax_mhz'])} | {_f(s['mw_at_fmax'])} | "
                 f"{_f(s.get('mw_at_realtime'))} ({s.get('realtime_copies', '-')}) | {_f(s['leakage_mw'], 3)} | "
                 f"{100 * s['sequential_share']:.0f} % | {100 * s['memory_model_share']:.0f} % | "
                 f"{'yes' if 'rams_modelled' in s else 'no'} | {blocks} |")
    L.append("")
    L.append("Per workload (pJ/pixel):")
    L.append("")
    names = sorted({w for p in d.values() for w in p["workloads"]})
    L.append("| profile | " + " | ".join(names) + " |")
    L.append("|---|" + "---:|" * len(names))
    for name, p in d.items():
        L.append(f"| {name} | " + " | ".join(_f(p["workloads"].get(w), 0) for w in names) + " |")
    return "\n".join(L) + "\n"


def record(root: Path, doc: dict) -> None:
    """Merges one profile's scripts/power.py result into SOURCE (summary, per-workload pJ/pixel,
    the window and the activity source)."""
    path = root / SOURCE
    d = json.loads(path.read_text()) if path.exists() else {"profiles": {}}
    d["profiles"][doc["profile"]] = {
        "summary": doc["summary"], "window": doc["window"], "activity_source": doc["activity_source"],
        "basis": doc["basis"], "seconds": doc["seconds"],
        "workloads": {k: r["pj_per_pixel"] for k, r in doc["workloads"].items()}}
    d["profiles"] = dict(sorted(d["profiles"].items()))
    path.parent.mkdir(parents=True, exist_ok=True)
    atomic.write_text(path, json.dumps(d, indent=2) + "\n")


# The fly-in against the still (docs/POWER.md section power-flyin): scripts/power.py PROFILE
# --animate SCENE --record-animation merges its frames into ANIMATION_SOURCE.
ANIMATION_SOURCE = Path("docs/data/power_animation.json")


def load_animation(root: Path) -> dict:
    return docgen.load_record(root, ANIMATION_SOURCE, "runs",
                              "scripts/power.py PROFILE --animate SCENE --record-animation")


def record_animation(root: Path, doc: dict, command: str) -> None:
    """Merges one scripts/power.py --animate result (its `animation`, the window, the still of the
    same scene when measured) into ANIMATION_SOURCE under PROFILE/SCENE/SIZE:START+CYCLES."""
    path = root / ANIMATION_SOURCE
    d = json.loads(path.read_text()) if path.exists() else {"runs": {}}
    an = doc["animation"]
    keep = ("frame", "t", "cycles", "pixels", "clocks_per_pixel", "pj_per_pixel", "vs_still")
    w = doc["window"]
    d["runs"][f"{doc['profile']}/{an['scene']}/{w['size']}:{w['start']}+{w['cycles']}"] = {
        "profile": doc["profile"], "scene": an["scene"], "frames": an["frames"], "window": doc["window"],
        "command": command, "basis": doc["basis"],
        "still": {k: v for k, v in (doc["workloads"].get(an["scene"]) or {}).items() if k in keep} or None,
        "frames_measured": {n: {k: v for k, v in r.items() if k in keep} for n, r in an["workloads"].items()},
        "pj_per_pixel_min": an["pj_per_pixel_min"], "pj_per_pixel_max": an["pj_per_pixel_max"],
        "pj_per_pixel_mean": an["pj_per_pixel_mean"], "spread": an["spread"]}
    # by profile and scene, the larger image (the stills' window) first
    d["runs"] = dict(sorted(d["runs"].items(), key=lambda kv: (kv[1]["profile"], kv[1]["scene"], -kv[1]["window"]["size"],
                                                              kv[0])))
    path.parent.mkdir(parents=True, exist_ok=True)
    atomic.write_text(path, json.dumps(d, indent=2) + "\n")


def animation_markdown(root: Path) -> str:
    runs = load_animation(root)["runs"]
    L = ["Measured by `scripts/power.py PROFILE --animate SCENE --record-animation` (the flow of the table "
         "above; each frame of the scene's time track rendered by `pst animate` and its own stream traced over "
         "the stills' window). Cycles: those traced (the window, or up to the stream's end); pixels: those that "
         "left the pipeline in them; vs still: the frame's pJ/pixel over the still scene's.", ""]
    for r in runs.values():
        w = r["window"]
        L += [f"{r['profile']}, {r['scene']} ({r['frames']} frames, frame k at t = k / {max(r['frames'] - 1, 1)}; "
              f"size {w['size']}, window cycles {w['start']} - {w['start'] + w['cycles']}):", "",
              "| workload | t | cycles | pixels | clocks/pixel | pJ/pixel | vs still |",
              "|---|---:|---:|---:|---:|---:|---:|"]
        rows = ([("still", r["still"])] if r.get("still") else []) + \
            [(f"frame {x['frame']}", x) for x in r["frames_measured"].values()]
        for name, x in rows:
            L.append(f"| {name} | {x['t'] if 't' in x else 0:.3f} | {x['cycles']} | {x['pixels']} | {_f(x.get('clocks_per_pixel'), 2)} | "
                     f"{_f(x.get('pj_per_pixel'), 0)} | {_f(x.get('vs_still', 1.0 if name == 'still' else None), 3)} |")
        L += ["", f"Frames: {_f(r['pj_per_pixel_min'], 0)} - {_f(r['pj_per_pixel_max'], 0)} pJ/pixel, mean "
              f"{_f(r['pj_per_pixel_mean'], 0)}, most / least {_f(r['spread'], 3)}.", ""]
    return "\n".join(L)
