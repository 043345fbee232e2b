"""Power and energy per pixel of one hardware profile from simulated activity (OSU 0.18 um cells,
Debian's OpenSTA report_power).

    scripts/power.py PROFILE [--scenes NAME ...] [--random N] [--seed S] [--size PX]
                     [--start CYCLE] [--window CYCLES] [--out DIR] [--work DIR] [--pst BIN] [--record]
                     [--animate SCENE [--frames N] [--at K1,K2,...]]

Writes DIR/PROFILE.json and DIR/PROFILE.md (default DIR: out/power). PROFILE must be verilated
in this build (the default build has full and reduced; others: cmake -DPST_PROFILES=...).

Workloads: the paper scenes named by --scenes (default: marble wood_teapot seascape zoneplate)
and N random textures of scripts/gen_scenes.py's validation stream (--random,
default 2, --seed 11: never the scenes anything was tuned on), each rendered at --size (96) by
the verilated RTL with an FST trace of --window cycles (4000) from cycle --start (4000: after
the configuration writes). Energy per pixel = the power over the window times its length,
divided by the pixels that left the pipeline in it (changes of out_tag_o).

Fly-in: --animate SCENE (a scene with an [animation] time track) also measures frames of its
track as workloads: `pst animate SCENE --frames N` (default: the scene's animation.frames; frame
k at t = k / (N - 1)), each frame of --at (default: four spread over the track, the first and
the last among them) traced over the same --start/--window of its own stream. They are reported
per frame in the JSON's `animation` and the MD beside the still workloads, not in the summary
(the profile's figures stay those of the still workloads) and not in --record's record;
--record-animation merges them (with the still of the same scene when measured) into
docs/data/power_animation.json (scripts/gen_docs.py's power-flyin section of docs/POWER.md).

Netlist: the profile's synthesis (scripts/synth.py --keep, the netlist the silicon figures
count), made in DIR/synth/ unless --work names a kept synthesis folder (NAME.work) whose
NAME.json sits beside it. Method and limits: docs/POWER.md and scripts/pstlib/power/flow.py.
Exit 2 on bad input, 1 when a tool fails.
"""
import argparse
import json
import tomllib
import pathlib
import shutil
import subprocess
import sys
import time

from .. import atomic, kept
from ..docs import power_doc
from ..paths import PY, ROOT, profile_path
from ..power import activity, figures, flow
from ..synth import flow as synth_flow, liberty, memarea

PAPER_SCENES = ("marble", "wood_teapot", "seascape", "zoneplate")


def workloads(a, out: pathlib.Path) -> dict:
    """name -> scene file."""
    scenes = {s: ROOT / "scenes" / f"{s}.toml" for s in a.scenes}
    if a.random:
        rdir = out / "scenes_random"
        r = subprocess.run([PY, str(ROOT / "scripts" / "gen_scenes.py"), "--seed", str(a.seed), "--train", "0",
                            "--valid", str(a.random), "--out", str(rdir)], capture_output=True, text=True)
        if r.returncode:
            raise RuntimeError(f"gen_scenes.py failed: {r.stderr.strip()}")
        for p in sorted((rdir / "valid").glob("valid_*.toml"))[:a.random]:
            scenes[f"random/{p.stem}"] = p
    return scenes


def track_frames(scene: pathlib.Path) -> int:
    """The frames of SCENE's [animation] time track (0: the scene has none)."""
    try:
        anim = tomllib.loads(scene.read_text()).get("animation") or {}
    except tomllib.TOMLDecodeError as e:
        raise synth_flow.InputError(f"--animate: {scene}: {e}")
    if not anim.get("track"):
        return 0
    return int(anim.get("frames", 0))


def frames_at(spec, frames: int) -> list:
    """The frames of --at (a comma-separated list of frame numbers, 0 .. FRAMES - 1, each once), in
    order; None: four spread over the track (the first, about 1/3 and 2/3, the last)."""
    if spec is None:
        return sorted({round(i * (frames - 1) / 3) for i in range(4)})
    out = []
    for part in spec.split(","):
        try:
            k = int(part.strip())
        except ValueError:
            raise synth_flow.InputError(f"--at: '{part.strip()}' is not a frame number")
        if not 0 <= k < frames:
            raise synth_flow.InputError(f"--at: frame {k} is not in the track (0 .. {frames - 1} of --frames {frames})")
        if k in out:
            raise synth_flow.InputError(f"--at: frame {k} given twice")
        out.append(k)
    return sorted(out)


def trace(pst: pathlib.Path, scene: pathlib.Path, profile: str, a, tmp: pathlib.Path, frame=None) -> pathlib.Path:
    """The VCD of the traced window of SCENE rendered by the verilated PROFILE: the still, or
    (FRAME given) that frame's stream of `pst animate SCENE --frames a.frames`."""
    fst, vcd = tmp / "t.fst", tmp / "t.vcd"
    window = ["--trace", str(fst), "--trace-start", str(a.start), "--trace-end", str(a.start + a.window)]
    if frame is None:
        what = f"pst render {scene.name} --profile {profile}"
        cmd = [str(pst), "render", str(scene), "--profile", profile, "--size", str(a.size), "-q", *window,
               "-o", str(tmp / "img")]
    else:
        what = f"pst animate {scene.name} --profile {profile} --trace-frame {frame}"
        cmd = [str(pst), "animate", str(scene), "--profile", profile, "--frames", str(a.frames), "--size", str(a.size),
               "--no-video", "-q", *window, "--trace-frame", str(frame), "-o", str(tmp / "anim")]
    r = subprocess.run(cmd, capture_output=True, text=True)
    shutil.rmtree(tmp / "anim", ignore_errors=True)
    if r.returncode:
        raise RuntimeError(f"{what}: {r.stderr.strip() or r.stdout.strip()}")
    if not fst.exists():
        raise RuntimeError(f"{what}: the run ended before cycle {a.start} "
                           f"(nothing traced): a larger --size or a smaller --start")
    activity.fst_to_vcd(fst, vcd)
    fst.unlink()
    return vcd


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("profile")
    ap.add_argument("--scenes", nargs="*", default=list(PAPER_SCENES))
    ap.add_argument("--random", type=int, default=2)
    ap.add_argument("--seed", type=int, default=11)
    ap.add_argument("--size", type=int, default=96)
    ap.add_argument("--start", type=int, default=4000)
    ap.add_argument("--window", type=int, default=4000)
    ap.add_argument("--out", default=str(ROOT / "out" / "power"))
    ap.add_argument("--work", help="a kept synthesis folder (scripts/synth.py --keep: OUT/NAME.work)")
    ap.add_argument("--pst", default=str(ROOT / "build" / "pst"))
    ap.add_argument("--check", action="store_true",
                    help="compare each workload's pJ/pixel with docs/data/power.json's (exit 1 beyond --tolerance)")
    ap.add_argument("--tolerance", type=float, default=0.01, help="--check's relative tolerance (default 0.01)")
    ap.add_argument("--record", action="store_true",
                    help="also merge the result into docs/data/power.json (scripts/gen_docs.py's power table)")
    ap.add_argument("--ram-reads", action="store_true",
                    help="also model the RAMs' read ports (their read multiplexers' area at the logic's density; "
                         "docs/POWER.md step 6); off: the RAMs are listed as not modelled, as in the records")
    ap.add_argument("--animate", metavar="SCENE",
                    help="also frames of this scene's time track (pst animate) as workloads, reported per frame")
    ap.add_argument("--frames", type=int, help="--animate: the track's frames (default: the scene's animation.frames)")
    ap.add_argument("--at", metavar="K1,K2,...",
                    help="--animate: the frames measured (default: four spread over the track, first and last among them)")
    ap.add_argument("--record-animation", action="store_true",
                    help="--animate: merge the frames (and the still of the scene) into docs/data/power_animation.json")
    a = ap.parse_args(argv)
    if not a.animate and (a.frames is not None or a.at is not None or a.record_animation):
        ap.error("--frames, --at, --record-animation: need --animate SCENE")
    if a.animate and a.record:
        ap.error("--record: not with --animate (the record holds the still workloads; run the fly-in without it)")
    if a.animate and not a.scenes and not a.random:
        ap.error("--animate: needs a still workload beside the frames (--scenes or --random: the summary's)")
    if a.frames is not None and not 1 <= a.frames <= 10000:
        ap.error("--frames: must be in [1, 10000]")
    for k, lo, hi in (("random", 0, 64), ("size", 8, 1024), ("start", 0, 1 << 30), ("window", 100, 1 << 22)):
        if not lo <= getattr(a, k) <= hi:
            ap.error(f"--{k.replace('_', '-')}: must be in [{lo}, {hi}]")
    if not shutil.which("fst2vcd") or not shutil.which("sta"):
        print("error: fst2vcd (gtkwave) and sta (opensta) are needed: run scripts/setup.sh", file=sys.stderr)
        return 2
    out = pathlib.Path(a.out)
    name = profile_path(a.profile).stem
    t0 = time.time()
    try:
        if not profile_path(a.profile).exists():
            raise synth_flow.InputError(f"{a.profile}: no such profile ({profile_path(a.profile)})")
        for s in a.scenes:
            if not (ROOT / "scenes" / f"{s}.toml").exists():
                raise synth_flow.InputError(f"--scenes: {s}: no such scene (scenes/{s}.toml)")
        if a.work and not (pathlib.Path(a.work) / "netlist_sta.v").exists():
            raise synth_flow.InputError(f"--work: {a.work}: not a kept synthesis (no netlist_sta.v)")
        if not pathlib.Path(a.pst).exists():
            raise synth_flow.InputError(f"--pst: {a.pst}: no such binary (build first: scripts/build.sh)")
        frames = []
        if a.animate:
            anim_scene = ROOT / "scenes" / f"{a.animate}.toml"
            if not anim_scene.exists():
                raise synth_flow.InputError(f"--animate: {a.animate}: no such scene (scenes/{a.animate}.toml)")
            track = track_frames(anim_scene)
            if not track:
                raise synth_flow.InputError(f"--animate: {a.animate}: the scene has no [animation] time track")
            a.frames = a.frames or track
            frames = frames_at(a.at, a.frames)
        scenes = workloads(a, out)
        work, record = kept.synthesis(a.profile, out, a.work)
    except synth_flow.InputError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    lib = liberty.osu018_lib()
    areas = liberty.cell_areas(lib.read_text())
    rows = {}
    mems = record.get("memories", [])
    rom_area = sum(m["area_um2"] for m in mems if m["kind"] == "ROM")
    ram_read_area = sum(memarea.ram_read_area_um2(m) for m in mems if m["kind"] != "ROM") if a.ram_reads else 0.0
    rams = ", ".join(f"{m['module']}.{m['memory']} ({m['size']} x {m['width']}, {m['read_ports']} read ports)"
                     for m in mems if m["kind"] != "ROM")
    tmp = out / f"{name}.traces"
    tmp.mkdir(parents=True, exist_ok=True)
    fly = {}
    try:
        def measure(wname, scene, frame=None):
            vcd = trace(pathlib.Path(a.pst), scene, a.profile, a, tmp, frame)
            act = activity.read_vcd(vcd)
            vcd.unlink()
            pixels = act.changes.get("out_tag_o", 0)
            pw = flow.run(work, act, [str(lib)], areas)
            row = figures.workload_figures(pw, act.cycles, pixels, rom_area, ram_read_area)
            print(f"{wname}: {row['pj_per_pixel'] or 0:,.0f} pJ/pixel, "
                  f"{row['dynamic_w'] * 1e3:.1f} mW dynamic at 100 MHz", flush=True)
            return row

        for wname, scene in scenes.items():
            rows[wname] = measure(wname, scene)
        for k in frames:
            fly[f"frame_{k:04d}"] = dict(measure(f"{a.animate} frame {k}/{a.frames}", anim_scene, k), frame=k,
                                         t=k / (a.frames - 1) if a.frames > 1 else 0.0)
        summary = figures.profile_figures(rows, record)
        summary["rams_modelled" if a.ram_reads else "rams_not_modelled"] = rams
    except (RuntimeError, ValueError, activity.VcdError) as e:
        print(f"error: {name}: {e}", file=sys.stderr)
        return 1
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    doc = {"profile": name, "activity_source": "verilated RTL, FST trace of each workload's window "
           "(port bits per driving cell, instance means elsewhere)", "basis": "pre-layout, typical corner, ideal clock",
           "window": {"start": a.start, "cycles": a.window, "size": a.size, "random_seed": a.seed},
           "summary": summary, "workloads": rows, "seconds": round(time.time() - t0, 1)}
    atomic.write_text(out / f"{name}.json", json.dumps(doc, indent=2) + "\n")
    if a.animate:
        doc["animation"] = animation_summary(a.animate, a.frames, fly, rows.get(a.animate))
    md = figures.markdown(name, summary, rows, flow.__doc__.split("\n", 2)[2])
    if a.animate:
        md += animation_markdown(doc["animation"])
    atomic.write_text(out / f"{name}.md", md)
    print(md)
    rc = 0
    if a.check:
        rc = check(name, rows, a.tolerance, doc["window"])
    if a.record:
        power_doc.record(ROOT, doc)
        print(f"recorded in {power_doc.SOURCE} (regenerate the docs: scripts/gen_docs.py --write)")
    if a.record_animation:
        power_doc.record_animation(ROOT, doc, recorded_command(argv if argv is not None else sys.argv[1:]))
        print(f"recorded in {power_doc.ANIMATION_SOURCE} (regenerate the docs: scripts/gen_docs.py --write)")
    return rc


def recorded_command(argv: list) -> str:
    """The command line as recorded: without --record-animation and the options naming this
    machine's files (--work, --out, --pst), which do not change a figure."""
    out, skip = [], False
    for x in argv:
        if skip:
            skip = False
        elif x in ("--work", "--out", "--pst"):
            skip = True
        elif x != "--record-animation" and not x.startswith(("--work=", "--out=", "--pst=")):
            out.append(x)
    return "scripts/power.py " + " ".join(out)


def animation_summary(scene: str, frames: int, fly: dict, still) -> dict:
    """The fly-in's frames (name -> workload_figures with frame and t), their least, most and
    mean pJ/pixel, the spread (most / least) and each frame against the still of the same scene
    when it was measured (STILL: its workload_figures, or None)."""
    pj = [r["pj_per_pixel"] for r in fly.values() if r["pj_per_pixel"]]
    out = {"scene": scene, "frames": frames, "workloads": fly,
           "pj_per_pixel_min": min(pj) if pj else None, "pj_per_pixel_max": max(pj) if pj else None,
           "pj_per_pixel_mean": sum(pj) / len(pj) if pj else None,
           "spread": max(pj) / min(pj) if pj else None,
           "still_pj_per_pixel": still["pj_per_pixel"] if still else None}
    if still and still["pj_per_pixel"]:
        for r in fly.values():
            r["vs_still"] = r["pj_per_pixel"] / still["pj_per_pixel"] if r["pj_per_pixel"] else None
    return out


def animation_markdown(an: dict) -> str:
    f = lambda v, d=0: "-" if v is None else f"{v:,.{d}f}"      # noqa: E731
    L = ["", f"Fly-in: {an['scene']} ({an['frames']} frames; frame k at t = k / {max(an['frames'] - 1, 1)}), "
         "each frame's stream traced over the same window as the stills:", "",
         "| frame | t | cycles | pixels | clocks/pixel | mW at the SDC clock | pJ/pixel | vs still |",
         "|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in an["workloads"].values():
        L.append(f"| {r['frame']} | {r['t']:.3f} | {r['cycles']} | {r['pixels']} | {f(r['clocks_per_pixel'], 2)} | "
                 f"{f((r['dynamic_w'] + r['leakage_w']) * 1e3, 1)} | {f(r['pj_per_pixel'])} | "
                 f"{f(r.get('vs_still'), 3)} |")
    L += ["", f"Least / mean / most: {f(an['pj_per_pixel_min'])} / {f(an['pj_per_pixel_mean'])} / "
          f"{f(an['pj_per_pixel_max'])} pJ/pixel (spread {f(an['spread'], 3)}x); the still "
          f"{an['scene']}: {f(an['still_pj_per_pixel'])} pJ/pixel.", ""]
    return "\n".join(L)


def check(name: str, rows: dict, tolerance: float, window: dict) -> int:
    """Each workload's pJ/pixel against the record's (docs/data/power.json): 0 when every one
    present in both is within TOLERANCE, 1 otherwise (each printed); 2 without a record."""
    try:
        rec = power_doc.load(ROOT)["profiles"].get(name)
    except ValueError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    if not rec:
        print(f"error: {power_doc.SOURCE}: no record of {name} (scripts/power.py {name} --record)", file=sys.stderr)
        return 2
    if rec.get("window") != window:
        print(f"error: {power_doc.SOURCE}: {name} was recorded with --start/--window/--size {rec.get('window')}, "
              f"not {window}", file=sys.stderr)
        return 2
    both = [w for w in rows if rec["workloads"].get(w)]
    if not both:
        print(f"error: {power_doc.SOURCE}: none of these workloads is in {name}'s record", file=sys.stderr)
        return 2
    bad = 0
    for w in both:
        new, old = rows[w]["pj_per_pixel"], rec["workloads"][w]
        change = (new - old) / old
        ok = abs(change) <= tolerance
        bad += not ok
        print(f"power check {name} {w}: {new:,.0f} pJ/pixel, record {old:,.0f} ({100 * change:+.2f} %) "
              f"{'ok' if ok else 'MOVED'}")
    print(f"power check {name}: {'PASSED' if not bad else f'FAILED ({bad} moved beyond {100 * tolerance:g} %)'}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
