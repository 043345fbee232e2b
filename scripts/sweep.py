#!/usr/bin/python3
"""Precision sweep: gates against image quality, one knob at a time around a base profile.

    scripts/sweep.py --base full|reduced|FILE [--knobs k1,k2,...] [--values KNOB=v1,v2 ...]
                     [--scenes a,b] [--size 128] [--truth 2] [--jobs 2] [--rtl-subset 2]
                     [--no-synth] [--match-variant] [--retry-failed] [--out out/sweep/<base>]
    scripts/sweep.py --quick        the small default sweep (base reduced, coord_frac 8,10,16,
                                    octaves 2,8, hash; marble and zoneplate at 64 x 64; synthesis
                                    on; no RTL check) -> out/sweep/reduced_quick

Every point is the base profile with ONE change (a knob set to one value; values equal to the
base are skipped, values that make an invalid profile are listed as skipped with the reason).
Per point:
  - out/sweep/<base>/points/<name>.toml, name = <base>_<knob>_<value> (a C identifier);
  - each scene rendered through the golden model of that profile (`pst render SCENE --profile
    POINT.toml --model golden --truth T`): PSNR against the double reference and against the
    T x T supersampled ground truth, from the render's summary.json; and the PSNR of its images
    against the base profile's (`vs base`, worst scene);
  - unless --no-synth, scripts/synth.py on the point (logic GE, ROM bits, RAM bits), cached as
    out/synth/<name>.json with a sidecar <name>.sweep.json of content hashes (the profile's
    values; rtl/*.sv, scripts/synth.py with its pstlib modules and scripts/synth/ files); --no-synth
    still uses a valid cache;
  - out/sweep/<base>/results/<name>.json, written through a temporary file and a rename.
    A point with a result is not recomputed (resumable; a result without synthesis gets only
    its synthesis added; other scenes / size / truth re-render it; --retry-failed reruns the
    failed ones).
The knob `basis` sets the noise unit's interp / corner / hash triple (rayshade or perlin2002), or a
worley unit (noise.worley_search octant, the base's worley_points and worley_order), and renders
scene copies whose textures ask for that basis (worley: its variant, F1 where a texture has no
coefficients; a profile runs only its own basis), so PSNR vs reference is against the basis's own
double reference.
The knob `filter` is per texture, not a profile key: its points render copies of the scene
files with every texture's filter replaced, through the base profile (the hardware holds every
filter kind, so the GE of those points is the base's). Its reference images use the same
filter, so PSNR vs reference measures the hardware's filter against the exact one of the same
kind, and PSNR vs truth says which kind looks best.
--match-variant renders scene copies whose textures ask for each point's noise variant and
|grad| norm, so the reference is the same function and PSNR measures precision alone (without
it, a profile whose noise differs from the scenes' Rayshade noise, like reduced, is measured
against Rayshade's texture).

--rtl-subset N verilates N points (the cheapest point within 1 dB of the base of N different
knobs) into build-sweep/ (-DPST_EXTRA_PROFILE_DIR=out/sweep/<base>/rtl_points) and runs
`pst regress --profile rtl_points/NAME.toml --size 64` on each: the RTL matches the golden
model bit for bit there, so the golden figures stand for the hardware.

Outputs in --out: sweep.csv, sweep.md (table, cheapest setting within 1 dB per knob, failures),
ge_vs_psnr_reference.png, ge_vs_psnr_truth.png, knobs/<knob>.png. Exit status: 0, 1 if any
point (render, synthesis, RTL check) failed, 2 on bad arguments, 130 when interrupted (Ctrl-C,
or SIGTERM in the background; running children are stopped).
"""
import argparse
import json
import os
import pathlib
import shutil
import sys
import time

from pstlib import atomic
from pstlib.contract import ProfileError, read_profile
from pstlib.fmt import fnum, kge, tail
from pstlib.paths import ROOT
from pstlib.plots import plot_all
from pstlib.results import PSNR_CAP, psnr_vs_base, row_of, rtl_subset, summarize
from pstlib.rtlcheck import rtl_check
from pstlib.runner import (STOP, read_json, reusable, run_point, run_points, say, stop_children, synth_cache_valid,
                           synth_key)
from pstlib.sweep import DEFAULT_SCENES, KNOBS, QUICK, ident, make_points, parse_values
from pstlib.sweep_report import write_reports


def parse_args(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--base", help="full, reduced or a profile file (default reduced)")
    ap.add_argument("--knobs", help=f"comma-separated, default all: {','.join(KNOBS)}")
    ap.add_argument("--values", action="append", default=None, metavar="KNOB=V1,V2",
                    help="values of one knob instead of its defaults (repeatable)")
    ap.add_argument("--scenes", help=f"comma-separated scene names or files (default {','.join(DEFAULT_SCENES)})")
    ap.add_argument("--size", type=int, help="image size (default 128)")
    ap.add_argument("--truth", type=int, help="ground truth samples per axis, 0 = none (default 2)")
    ap.add_argument("--jobs", type=int, default=2, help="points in parallel (default 2)")
    ap.add_argument("--rtl-subset", type=int, dest="rtl_subset", help="points checked on the RTL (default 2)")
    ap.add_argument("--no-synth", action="store_true", help="no gate counts (renders only)")
    ap.add_argument("--retry-failed", action="store_true", help="recompute points recorded as failed")
    ap.add_argument("--match-variant", action="store_true",
                    help="render scene copies whose textures ask for the point profile's noise variant and "
                         "|grad| norm, so the reference (and truth) is the same function and PSNR measures "
                         "precision only (default out: out/sweep/<base>_matched)")
    ap.add_argument("--quick", action="store_true",
                    help="small sweep: base reduced, coord_frac 8,10,16, octaves 2,8, hash; marble and zoneplate "
                         "at 64 x 64; synthesis on; no RTL check (explicit options override)")
    ap.add_argument("--out", help="output folder (default out/sweep/<base>, out/sweep/<base>_quick with --quick)")
    ap.add_argument("--pst", default=str(ROOT / "build" / "pst"), help="pst binary for the golden renders")
    a = ap.parse_args(argv)
    if a.quick:
        for k, v in QUICK.items():
            if getattr(a, k) is None:
                setattr(a, k, v)
    a.base = a.base or "reduced"
    a.knobs = a.knobs or ",".join(KNOBS)
    a.scenes = a.scenes or ",".join(DEFAULT_SCENES)
    a.size = 128 if a.size is None else a.size
    a.truth = 2 if a.truth is None else a.truth
    a.rtl_subset = 2 if a.rtl_subset is None else a.rtl_subset
    a.values = a.values or []

    if "/" not in a.base and not a.base.endswith(".toml"):
        a.base_path = ROOT / "rtl" / "configs" / f"{a.base}.toml"
    else:
        a.base_path = pathlib.Path(a.base).resolve()
    if not a.base_path.is_file():
        ap.error(f"--base: {a.base}: no such profile (full, reduced or a profile file)")
    try:
        a.base_doc = read_profile(a.base_path)
    except (ProfileError, UnicodeDecodeError) as e:
        ap.error(f"--base: {e}")
    a.base_name = ident(a.base_path.stem)

    a.knob_list = [k.strip() for k in a.knobs.split(",") if k.strip()]
    unknown = [k for k in a.knob_list if k not in KNOBS]
    if unknown or not a.knob_list:
        ap.error(f"--knobs: unknown knob(s) {', '.join(unknown) or '(none given)'}; known: {', '.join(KNOBS)}")
    a.value_lists = {k: list(KNOBS[k][1]) for k in a.knob_list}
    for spec in a.values:
        try:
            k, vals = parse_values(spec)
        except ValueError as e:
            ap.error(f"--values: {e}")
        if k in a.value_lists:
            a.value_lists[k] = vals
    a.scene_files = {}
    for s in [s.strip() for s in a.scenes.split(",") if s.strip()]:
        p = pathlib.Path(s) if (s.endswith(".toml") or "/" in s) else ROOT / "scenes" / f"{s}.toml"
        if not p.is_file():
            ap.error(f"--scenes: {s}: no such scene ({p})")
        a.scene_files[ident(p.stem)] = p.resolve()
    if not a.scene_files:
        ap.error("--scenes: no scene given")
    a.scene_names = list(a.scene_files)
    if not 1 <= a.size <= 4096:
        ap.error("--size: must be in [1, 4096]")
    if not 0 <= a.truth <= 64:
        ap.error("--truth: must be in [0, 64]")
    if a.jobs < 1:
        ap.error("--jobs: must be >= 1")
    if a.rtl_subset < 0:
        ap.error("--rtl-subset: must be >= 0")
    if not os.access(a.pst, os.X_OK):
        ap.error(f"--pst: {a.pst}: not an executable (cmake --build build --target pst)")
    suffix = ("_quick" if a.quick else "") + ("_matched" if a.match_variant else "")
    a.out = pathlib.Path(a.out or ROOT / "out" / "sweep" / (a.base_name + suffix)).resolve()
    a.synth_dir = ROOT / "out" / "synth"
    return a


def main(argv=None) -> int:
    a = parse_args(argv if argv is not None else sys.argv[1:])
    out = a.out
    out.mkdir(parents=True, exist_ok=True)
    t_start = time.time()
    base, points, skipped, base_values = make_points(a, out)
    todo = [base] + points
    for k, v, why in skipped:
        say(f"skip {k} = {v}: {why}")
    say(f"sweep of {a.base_name}: {len(points)} points + base, {len(a.scene_files)} scenes at {a.size}x{a.size}, "
        f"truth {a.truth}, synthesis {'off' if a.no_synth else 'on'}, {a.jobs} jobs -> {out}")

    n = len(todo)
    done = [0]

    settings = {"size": a.size, "truth": a.truth}

    def cached(pt):
        r = read_json(out / "results" / f"{pt.name}.json")
        synth_to_do = lambda: not a.no_synth or synth_cache_valid(a.synth_dir / f"{pt.synth_name}.json", pt.profile)
        key = None if pt.knob == "filter" else synth_key(pt.profile)
        return r if reusable(r, pt, settings, a.scene_files, a.retry_failed, synth_to_do, key) else None

    def report(pt, r, how):
        done[0] += 1
        if r.get("status") != "ok":
            say(f"[{done[0]}/{n}] {pt.name}: FAILED ({how}): {tail(r.get('error', ''), 1)}")
            return
        s = summarize(r, a.scene_names)
        syn = r.get("synth")
        ge = f", {syn['logic_ge'] / 1000:.1f}k GE" if syn else ""
        note = f" ({r.get('synth_note')})" if syn and r.get("synth_note") and how != "cached" else ""
        say(f"[{done[0]}/{n}] {pt.name}: PSNR {fnum(s['psnr_ref'], 1)} dB (truth {fnum(s['psnr_truth'], 1)} dB)"
            f"{ge}{note}{' [result cached]' if how == 'cached' else ''}")

    def work(pt):
        r = run_point(pt, a, out)
        if STOP.is_set():
            raise KeyboardInterrupt
        atomic.write_text(out / "results" / f"{pt.name}.json", json.dumps(r, indent=2) + "\n")
        return r

    def failed(pt, e):     # a bug or an unreadable output: record it, keep going
        r = {"name": pt.name, "knob": pt.knob, "value": pt.value, "status": "failed",
             "profile": str(pt.profile), "profile_sha": pt.profile_sha, "settings": settings, "scenes": {},
             "error": f"{type(e).__name__}: {e}"}
        atomic.write_text(out / "results" / f"{pt.name}.json", json.dumps(r, indent=2) + "\n")
        return r

    try:
        results = run_points(todo, a.jobs, cached, work, failed, report)
    except KeyboardInterrupt:
        shutil.rmtree(out / "tmp", ignore_errors=True)
        say("interrupted: finished points are kept in results/; rerun the same command to resume")
        return 130
    shutil.rmtree(out / "tmp", ignore_errors=True)

    base_res = results[base.name]
    base_row = row_of(base_res, a.scene_names)
    base_row["base_value"] = base_values
    base_row["name"] = base.name
    base_row["knob"] = "base"
    base_row["value"] = "-"
    rows = [row_of(results[p.name], a.scene_names, base_res) for p in points]
    base_row["psnr_base"] = PSNR_CAP
    for r in rows:
        r["psnr_base"] = psnr_vs_base(out, r["name"], base.name, a.scene_names) if r["status"] == "ok" else None

    # RTL subset: the cheapest point within 1 dB of N different knobs (else any passing point).
    rtl = {}
    chosen = rtl_subset(rows, base_row, a.knob_list, a.rtl_subset)
    if chosen:
        try:
            rtl = rtl_check(a, out, base.name, chosen, {r["name"]: r for r in rows})
        except KeyboardInterrupt:
            stop_children()
            say("interrupted during the RTL check; rerun to resume")
            return 130

    knobs = a.knob_list
    title = f"sweep of {base.name}" + (" (matched variant)" if a.match_variant else "")
    plots = plot_all(out, rows, base_row, knobs, title)
    elapsed = time.time() - t_start
    lines = write_reports(a, out, base_row, rows, knobs, skipped, rtl, title, elapsed)
    say("")
    say(f"cheapest setting within 1 dB of {base.name} (mean PSNR vs reference {fnum(base_row['psnr_ref'])} dB, "
        f"{kge(base_row['logic_ge'])} GE):")
    for line in lines:
        say("  " + line.replace("**", "").replace("`", ""))
    failed = [r["name"] for r in [base_row] + rows if r["status"] != "ok"]
    rtl_failed = [k for k, v in rtl.items() if not v.get("passed")]
    say(f"wrote {out / 'sweep.md'}, {out / 'sweep.csv'}, {len(plots)} plots; {elapsed:.0f} s")
    if failed or rtl_failed:
        say(f"FAILED: {', '.join(failed + [f'rtl:{n}' for n in rtl_failed])}")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
