"""The sweep's run: its settings from the command line's values (checked), then every point
evaluated on the local backend, the RTL check of a few, the tables and plots."""
import dataclasses
import os
import pathlib
import shutil
import time

from ..contract import ProfileError, read_profile
from ..fmt import fnum, kge, tail
from ..paths import ROOT, profile_path
from . import evaluate
from ..backends.local import STOP, run_points, say, stop_children
from .plots import plot_all
from .results import PSNR_CAP, psnr_vs_base, row_of, rtl_subset, summarize
from .rtlcheck import rtl_check
from .store import Store
from .sweep import DEFAULT_SCENES, KNOBS, QUICK, ident, make_points, parse_values
from .sweep_report import write_reports

RTL_SIZE = 64


@dataclasses.dataclass
class SweepSettings:
    base_path: pathlib.Path
    base_doc: dict
    base_name: str
    knob_list: list
    value_lists: dict               # knob -> values
    scene_files: dict               # scene name -> file
    out: pathlib.Path
    pst: str
    size: int = 128
    truth: int = 2
    jobs: int = 2
    rtl_subset: int = 2
    no_synth: bool = False
    retry_failed: bool = False
    match_variant: bool = False
    synth_dir: pathlib.Path = ROOT / "out" / "synth"

    @property
    def scene_names(self) -> list:
        return list(self.scene_files)


def settings(base=None, knobs=None, values=None, scenes=None, size=None, truth=None, jobs=2, rtl_subset=None,
             no_synth=False, retry_failed=False, match_variant=False, quick=False, out=None,
             pst=str(ROOT / "build" / "pst")) -> SweepSettings:
    """The sweep's settings from the command line's values (None: the default, or --quick's);
    ValueError("--flag: what is wrong")."""
    given = dict(base=base, knobs=knobs, values=values, scenes=scenes, size=size, truth=truth, rtl_subset=rtl_subset)
    if quick:
        given = {k: QUICK[k] if v is None and k in QUICK else v for k, v in given.items()}
    base = given["base"] or "reduced"
    path = profile_path(base).resolve()
    if not path.is_file():
        raise ValueError(f"--base: {base}: no such profile (full, reduced or a profile file)")
    try:
        doc = read_profile(path)
    except (ProfileError, UnicodeDecodeError) as e:
        raise ValueError(f"--base: {e}") from None
    knob_list = [k.strip() for k in (given["knobs"] or ",".join(KNOBS)).split(",") if k.strip()]
    unknown = [k for k in knob_list if k not in KNOBS]
    if unknown or not knob_list:
        raise ValueError(f"--knobs: unknown knob(s) {', '.join(unknown) or '(none given)'}; known: {', '.join(KNOBS)}")
    value_lists = {k: list(KNOBS[k][1]) for k in knob_list}
    for spec in given["values"] or []:
        try:
            k, vals = parse_values(spec)
        except ValueError as e:
            raise ValueError(f"--values: {e}") from None
        if k in value_lists:
            value_lists[k] = vals
    scene_files = {}
    for s in [s.strip() for s in (given["scenes"] or ",".join(DEFAULT_SCENES)).split(",") if s.strip()]:
        p = pathlib.Path(s) if (s.endswith(".toml") or "/" in s) else ROOT / "scenes" / f"{s}.toml"
        if not p.is_file():
            raise ValueError(f"--scenes: {s}: no such scene ({p})")
        scene_files[ident(p.stem)] = p.resolve()
    if not scene_files:
        raise ValueError("--scenes: no scene given")
    s = SweepSettings(path, doc, ident(path.stem), knob_list, value_lists, scene_files, out, pst,
                      128 if given["size"] is None else given["size"], 2 if given["truth"] is None else given["truth"],
                      jobs, 2 if given["rtl_subset"] is None else given["rtl_subset"], no_synth, retry_failed,
                      match_variant)
    for ok, what in ((1 <= s.size <= 4096, "--size: must be in [1, 4096]"),
                     (0 <= s.truth <= 64, "--truth: must be in [0, 64]"), (s.jobs >= 1, "--jobs: must be >= 1"),
                     (s.rtl_subset >= 0, "--rtl-subset: must be >= 0"),
                     (os.access(s.pst, os.X_OK),
                      f"--pst: {s.pst}: not an executable (cmake --build build --target pst)")):
        if not ok:
            raise ValueError(what)
    suffix = ("_quick" if quick else "") + ("_matched" if match_variant else "")
    s.out = pathlib.Path(out or ROOT / "out" / "sweep" / (s.base_name + suffix)).resolve()
    return s


def run(s: SweepSettings) -> int:
    """Evaluates, checks and reports the sweep; the exit status (0, 1 failed points, 130 interrupted)."""
    out = s.out
    out.mkdir(parents=True, exist_ok=True)
    store = Store(out, indent=2)
    t_start = time.time()
    base, points, skipped, base_values = make_points(s, out)
    todo = [base] + points
    for k, v, why in skipped:
        say(f"skip {k} = {v}: {why}")
    say(f"sweep of {s.base_name}: {len(points)} points + base, {len(s.scene_files)} scenes at {s.size}x{s.size}, "
        f"truth {s.truth}, synthesis {'off' if s.no_synth else 'on'}, {s.jobs} jobs -> {out}")
    n, done = len(todo), [0]
    render_settings = {"size": s.size, "truth": s.truth}

    def cached(pt):
        def synth_to_do():
            return not s.no_synth or evaluate.synth_cache_valid(s.synth_dir / f"{pt.synth_name}.json", pt.profile)
        key = None if pt.knob == "filter" else evaluate.synth_key(pt.profile)
        r = store.get(pt.name)
        return r if evaluate.sweep_reusable(r, pt, render_settings, s.scene_files, s.retry_failed, synth_to_do,
                                            key) else None

    def report(pt, r, how):
        done[0] += 1
        if r.get("status") != "ok":
            say(f"[{done[0]}/{n}] {pt.name}: FAILED ({how}): {tail(r.get('error', ''), 1)}")
            return
        m = summarize(r, s.scene_names)
        syn = r.get("synth")
        ge = f", {syn['logic_ge'] / 1000:.1f}k GE" if syn else ""
        note = f" ({r.get('synth_note')})" if syn and r.get("synth_note") and how != "cached" else ""
        say(f"[{done[0]}/{n}] {pt.name}: PSNR {fnum(m['psnr_ref'], 1)} dB (truth {fnum(m['psnr_truth'], 1)} dB)"
            f"{ge}{note}{' [result cached]' if how == 'cached' else ''}")

    def work(pt):
        r = evaluate.sweep_point(pt, out, s.pst, s.size, s.truth, s.synth_dir, s.no_synth)
        if STOP.is_set():
            raise KeyboardInterrupt
        return store.put(pt.name, r)

    def failed(pt, e):     # a bug or an unreadable output: record it, keep going
        return store.put(pt.name, {"name": pt.name, "knob": pt.knob, "value": pt.value, "status": "failed",
                                   "profile": str(pt.profile), "profile_sha": pt.sha, "settings": render_settings,
                                   "scenes": {}, "error": f"{type(e).__name__}: {e}"})

    try:
        results = run_points(todo, s.jobs, cached, work, failed, report)
    except KeyboardInterrupt:
        shutil.rmtree(out / "tmp", ignore_errors=True)
        say("interrupted: finished points are kept in results/; rerun the same command to resume")
        return 130
    shutil.rmtree(out / "tmp", ignore_errors=True)

    base_res = results[base.name]
    base_row = dict(row_of(base_res, s.scene_names), base_value=base_values, name=base.name, knob="base", value="-",
                    psnr_base=PSNR_CAP)
    rows = [row_of(results[p.name], s.scene_names, base_res) for p in points]
    for r in rows:
        r["psnr_base"] = psnr_vs_base(out, r["name"], base.name, s.scene_names) if r["status"] == "ok" else None

    # RTL subset: the cheapest point within 1 dB of N different knobs (else any passing point).
    rtl = {}
    chosen = rtl_subset(rows, base_row, s.knob_list, s.rtl_subset)
    if chosen:
        by = {r["name"]: r for r in rows}
        named = profile_path(s.base_name).exists()
        try:
            rtl = rtl_check(out, {c: (by[c]["profile"], by[c]["profile_sha"]) for c in chosen}, RTL_SIZE,
                            ROOT / "build-sweep", s.jobs, s.base_name if named else "reduced")
        except KeyboardInterrupt:
            stop_children()
            say("interrupted during the RTL check; rerun to resume")
            return 130

    title = f"sweep of {base.name}" + (" (matched variant)" if s.match_variant else "")
    plots = plot_all(out, rows, base_row, s.knob_list, title)
    elapsed = time.time() - t_start
    lines = write_reports(s, out, base_row, rows, s.knob_list, skipped, rtl, title, elapsed)
    say("")
    say(f"cheapest setting with every scene within 1 dB of {base.name} (mean PSNR vs reference {fnum(base_row['psnr_ref'])} dB, "
        f"{kge(base_row['logic_ge'])} GE):")
    for line in lines:
        say("  " + line.replace("**", "").replace("`", ""))
    bad = [r["name"] for r in [base_row] + rows if r["status"] != "ok"]
    rtl_failed = [k for k, v in rtl.items() if not v.get("passed")]
    say(f"wrote {out / 'sweep.md'}, {out / 'sweep.csv'}, {len(plots)} plots; {elapsed:.0f} s")
    if bad or rtl_failed:
        say(f"FAILED: {', '.join(bad + [f'rtl:{n}' for n in rtl_failed])}")
        return 1
    return 0
