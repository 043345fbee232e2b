#!/usr/bin/python3
"""Design-space search: the least logic area at a quality, throughput and clock target.

    scripts/search.py [--classes 1,4,32] [--psnr DB | --psnr 1=50,4=45,32=30] [--max-loss DB] [--fmax MHZ]
                      [--start 1=full,4=full,32=reduced] [--knobs k1,k2,...] [--budget N]
                      [--backtracks N] [--size 48] [--train 8] [--valid 8] [--seed 1] [--paper]
                      [--jobs 2] [--backend local|slurm] [--rtl N] [--rtl-size 32] [--out out/search]
    scripts/search.py --big        the big run (below); explicit options override its values

Per clocks-per-pixel class C (a point belongs to C when its clocks per pixel are <= C) a greedy
walk with backtracking (scripts/pstlib/search.py says how and why) starts from a profile that
meets the targets and moves, one knob at a time but choosing among all knobs at every step, to
the cheaper neighbour of least logic area that still has worst training PSNR >= the target
(and Fmax >= --fmax when given: scripts/synth.py with OpenSTA on those candidates only).
--max-loss DB adds issue 13's texture-by-texture rule: every training scene within DB of the
class's start profile (the worst scene alone hides a step colour map or a mod wrap that a
cut spoils); the walk's merit is then GE saved per dB lost on the scene that loses most, the
starts are scored on the validation set too, and each front point carries its largest loss on
one scene against the start, training and validation (flagged when validation passes DB).
Knobs: the fraction bits of every format (coord, jacobian, matrix, amplitude, offset, quadric,
f, grad, width), the noise unit's value/lattice/out fractions and guard bits, the reciprocal
bits, interpolation, corner, hash, |grad| norm, and `structure` (octaves, noise units, noise
steps, datapath among those within the class's clocks per pixel).

A point is evaluated by golden renders (`pst render --model golden`) of the training scenes
(random scenes of scripts/gen_scenes.py, seed --seed, plus the paper's scenes with --paper) at
--size: its worst-scene PSNR against the double reference; clocks per pixel from the contract;
logic GE from a per-module synthesis cache (scripts/pstlib/synth/modules.py: a derived module
is synthesized once per parameter set and source, so a point that changes one format
re-synthesizes only the modules it reaches; cache in out/search_modules/, shared by searches).
Points under --synth-floor dB are not synthesized.

Outputs in --out: points/NAME.toml, results/NAME.json (atomic; a rerun resumes: stored points
are not recomputed), points.csv, front.csv, front.md, front.png (area against worst training
PSNR per class, the validation PSNR of each front point beside), rtl/ (the RTL check of every
front point: verilated into build-search/, `pst regress --size --rtl-size`, 0 mismatches).

--backend slurm submits each batch of points as an sbatch job array (scripts/pstlib/search_slurm.py:
--partition, --account, --time, --slurm-arg) and collects the same per-point results; a failed
or cancelled task is rerun by the next run of the same command.

--big: all knobs, 32 training + 32 validation scenes plus the paper's at 128 x 128, budget 200
points per class, 4 backtracks, PSNR targets 1=50,4=45,32=30 (hours on a many-core machine or a
cluster: use --backend slurm).
Exit status: 0; 1 if a front point fails its RTL check or a point failed; 2 on bad arguments;
130 when interrupted.
"""
import argparse
import hashlib
import json
import os
import pathlib
import shutil
import sys
import time

from pstlib import atomic, contract, scenegen
from pstlib import search as S
from pstlib import search_eval, search_report
from pstlib.fmt import tail
from pstlib.paths import PY, ROOT
from pstlib.rtlcheck import regress_summary
from pstlib.runner import STOP, read_json, run, run_points, say, stop_children

BIG = {"train": 32, "valid": 32, "size": 128, "paper": True, "budget": 200, "backtracks": 4,
       "psnr": "1=50,4=45,32=30"}
DEFAULT_START = {1: "full", 4: "full", 32: "reduced"}
PAPER_SCENES = ["wood_teapot", "marble", "seascape", "fire", "planet", "moonrise", "zoneplate", "wood_torus"]


def _per_class(spec: str, classes, conv, what):
    def value(v):
        try:
            return conv(v)
        except ValueError:
            raise ValueError(f"{what}: not a valid value: {v!r}") from None
    out = {}
    if "=" not in spec:
        return {c: value(spec) for c in classes}
    for part in spec.split(","):
        k, _, v = part.partition("=")
        if not k.strip().isdigit():
            raise ValueError(f"{what}: expected CLASS=VALUE, got {part!r}")
        out[int(k)] = value(v.strip())
    missing = [c for c in classes if c not in out]
    if missing:
        raise ValueError(f"{what}: no value for class {', '.join(map(str, missing))}")
    return out


def parse_args(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--classes", default="1,4,32")
    ap.add_argument("--psnr", help="target worst training PSNR, dB (one value or CLASS=DB,...; default 40)")
    ap.add_argument("--max-loss", help="texture by texture: every training scene within this many dB of the "
                    "class's start profile (one value or CLASS=DB,...; default: no such bound)")
    ap.add_argument("--fmax", type=float, default=0.0, help="target Fmax, MHz (0: no constraint)")
    ap.add_argument("--start", help="start profile per class, CLASS=PROFILE,... (default 1=full,4=full,32=reduced)")
    ap.add_argument("--knobs", help=f"comma-separated, default all: {','.join(S.KNOB_NAMES)}")
    ap.add_argument("--budget", type=int, help="points per class walk (default 40)")
    ap.add_argument("--backtracks", type=int, help="backtracks per walk (default 2)")
    ap.add_argument("--size", type=int, help="image size of the renders (default 48)")
    ap.add_argument("--train", type=int, help="random training scenes (default 8)")
    ap.add_argument("--valid", type=int, help="random validation scenes (default 8)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--paper", action="store_true", default=None, help="the paper's scenes in the training set too")
    ap.add_argument("--synth-floor", type=float, default=None,
                    help="points whose worst training PSNR is below this are not synthesized (default: lowest target - 10)")
    ap.add_argument("--jobs", type=int, default=2, help="points in parallel (local backend)")
    ap.add_argument("--backend", choices=["local", "slurm"], default="local")
    ap.add_argument("--partition", help="SLURM partition")
    ap.add_argument("--account", help="SLURM account")
    ap.add_argument("--time", dest="time_limit", default="02:00:00", help="SLURM time limit per task")
    ap.add_argument("--slurm-arg", action="append", default=[], help="extra sbatch argument (repeatable)")
    ap.add_argument("--rtl", type=int, default=None, help="front points per class checked on the RTL (default all)")
    ap.add_argument("--rtl-size", type=int, default=32)
    ap.add_argument("--retry-failed", action="store_true")
    ap.add_argument("--big", action="store_true", help="the big run (see above)")
    ap.add_argument("--out", default=str(ROOT / "out" / "search"))
    ap.add_argument("--module-cache", default=str(ROOT / "out" / "search_modules"))
    ap.add_argument("--rom-dir", default=str(ROOT / "build" / "rom"))
    ap.add_argument("--pst", default=str(ROOT / "build" / "pst"))
    a = ap.parse_args(argv)
    if a.big:
        for k, v in BIG.items():
            if getattr(a, k) is None:
                setattr(a, k, v)
    a.psnr = a.psnr or "40"
    a.budget = 40 if a.budget is None else a.budget
    a.backtracks = 2 if a.backtracks is None else a.backtracks
    a.size = 48 if a.size is None else a.size
    a.train = 8 if a.train is None else a.train
    a.valid = 8 if a.valid is None else a.valid
    a.paper = bool(a.paper)
    try:
        a.class_list = [int(c) for c in a.classes.split(",") if c.strip()]
        if not a.class_list or min(a.class_list) < 1:
            raise ValueError("--classes: positive integers")
        a.targets = _per_class(a.psnr, a.class_list, float, "--psnr")
        a.max_losses = _per_class(a.max_loss, a.class_list, float, "--max-loss") if a.max_loss else {}
        if any(not 0 <= v < 100 for v in list(a.targets.values()) + list(a.max_losses.values())):
            raise ValueError("--psnr and --max-loss: dB in [0, 100)")
        starts = dict(DEFAULT_START)
        if a.start:
            starts.update(_per_class(a.start, [], str, "--start"))
        a.starts = {c: starts.get(c, "full") for c in a.class_list}
    except ValueError as e:
        ap.error(str(e))
    a.start_docs = {}
    for c, s in a.starts.items():
        p = ROOT / "rtl" / "configs" / f"{s}.toml" if "/" not in s and not s.endswith(".toml") else pathlib.Path(s)
        try:
            a.start_docs[c] = (p, contract.read_profile(p))
        except (OSError, contract.ProfileError) as e:
            ap.error(f"--start: {e}")
    a.knob_list = [k.strip() for k in (a.knobs or ",".join(S.KNOB_NAMES)).split(",") if k.strip()]
    bad = [k for k in a.knob_list if k not in S.KNOB_NAMES]
    if bad or not a.knob_list:
        ap.error(f"--knobs: unknown {', '.join(bad) or '(none)'}; known: {', '.join(S.KNOB_NAMES)}")
    if not 8 <= a.size <= 1024:
        ap.error("--size: must be in [8, 1024]")
    if not 1 <= a.train <= 1000 or not 0 <= a.valid <= 1000:
        ap.error("--train: 1..1000, --valid: 0..1000")
    if a.budget < 1 or a.backtracks < 0 or a.jobs < 1:
        ap.error("--budget >= 1, --backtracks >= 0, --jobs >= 1")
    if a.synth_floor is None:
        a.synth_floor = min(a.targets.values()) - 10
    if not os.access(a.pst, os.X_OK):
        ap.error(f"--pst: {a.pst}: not an executable (cmake --build build --target pst)")
    if not (pathlib.Path(a.rom_dir) / "hash4096.memh").exists():
        ap.error(f"--rom-dir: {a.rom_dir}: no ROM images (cmake --build build --target pst_rom_images)")
    a.out = pathlib.Path(a.out).resolve()
    return a


class Job:
    """The search's shared state on disk: OUT/job.json (settings, every point's values hash),
    OUT/points/NAME.toml."""

    def __init__(self, a):
        self.a = a
        self.out = a.out
        self.points = {}
        old = read_json(self.out / "job.json") or {}
        self.known = old.get("points", {})
        sdir = self.out / "scenes"
        scenegen.write(sdir, a.seed, {"train": a.train, "valid": a.valid})
        train = sorted(str(p) for p in (sdir / "train").glob("train_*.toml"))
        if a.paper:
            train += [str(ROOT / "scenes" / f"{s}.toml") for s in PAPER_SCENES]
        pst_sha = hashlib.sha256(pathlib.Path(a.pst).read_bytes()).hexdigest()[:16]
        self.settings = {"size": a.size, "synth_floor": a.synth_floor, "pst": str(pathlib.Path(a.pst).resolve()),
                         "pst_sha": pst_sha,
                         "module_cache": str(pathlib.Path(a.module_cache).resolve()),
                         "rom_dir": str(pathlib.Path(a.rom_dir).resolve()), "retry_failed": a.retry_failed,
                         "scenes": {"train": train,
                                    "valid": sorted(str(p) for p in (sdir / "valid").glob("valid_*.toml"))}}
        self.save()

    def save(self):
        atomic.write_text(self.out / "job.json",
                          json.dumps(dict(self.settings, points=dict(self.known, **{n: p.sha for n, p in self.points.items()})),
                                     indent=1) + "\n")

    def add(self, pts):
        new = False
        for p in pts:
            if p.name not in self.points:
                self.points[p.name] = p
                atomic.write_if_changed(self.out / "points" / f"{p.name}.toml", p.text)
                new = True
        if new:
            self.save()


def make_evaluator(a, job, stats):
    """evaluate(points, which) -> {name: result}: stored results reused, the rest run on the backend."""
    from pstlib.synth import liberty, modules
    mc = modules.ModuleCache(pathlib.Path(a.module_cache), liberty.osu018_lib(), pathlib.Path(a.rom_dir))

    def evaluate(points, which=("train",)):
        job.add(points)
        res = {}

        def cached(p):
            r = read_json(a.out / "results" / f"{p.name}.json")
            return r if search_eval.reusable(r, p.sha, job.settings, which) else None

        def work(p):
            r = search_eval.evaluate(a.out, p.name, which, module_cache=mc)
            if STOP.is_set():
                raise KeyboardInterrupt
            return r

        def failed(p, e):
            r = {"name": p.name, "profile_sha": p.sha, "size": a.size, "pst_sha": job.settings["pst_sha"],
                 "status": "failed",
                 "error": f"{type(e).__name__}: {e}", "cpp": p.cpp}
            atomic.write_text(a.out / "results" / f"{p.name}.json", json.dumps(r, indent=1) + "\n")
            return r

        def report(p, r, how):
            stats["points"].add(p.name)
            fresh = how != "cached" and r.get("area_new")
            if fresh:
                stats["modules_synthesized"] += r["area"].get("modules_synthesized", 0)
            ge = f"{r['logic_ge'] / 1000:.1f}k GE" if r.get("logic_ge") else "not synthesized"
            syn = (f" ({r['area']['modules_synthesized']}/{r['area']['modules_total']} modules synthesized, "
                   f"{r['area']['seconds']:.0f} s)") if fresh else ""
            if r.get("status") != "ok":
                say(f"    {p.name}: FAILED: {tail(r.get('error', ''), 2)}")
            else:
                v = f", valid {r['valid_worst']:.2f}" if r.get("valid_worst") is not None else ""
                say(f"    {p.name} [{p.move.split('; ')[-1]}]: {p.cpp} clk/px, worst train {r['train_worst']:.2f} dB{v}, "
                    f"{ge}{syn}{' [cached]' if how == 'cached' else ''}")

        if a.backend == "slurm":
            from pstlib import search_slurm
            todo = [p for p in points if cached(p) is None]
            for p in points:
                if p not in todo:
                    report(p, cached(p), "cached")
            if todo:
                search_slurm.run_array(a, [p.name for p in todo], which)
            for p in todo:
                r = read_json(a.out / "results" / f"{p.name}.json")
                if not search_eval.reusable(r, p.sha, job.settings, which):
                    r = failed(p, RuntimeError("SLURM task left no complete result (rerun to retry)"))
                report(p, r, "run")
                res[p.name] = r
            for p in points:
                res.setdefault(p.name, cached(p))
            return res
        return run_points(points, a.jobs, cached, work, failed, report)

    return evaluate


def make_fmax(a):
    """fmax_of(point, result): scripts/synth.py (OpenSTA) on the point, cached in OUT/synth/."""
    def fmax_of(p, r):
        sj = a.out / "synth" / f"{p.name}.json"
        if not sj.exists():
            rc, so, se = run([PY, ROOT / "scripts" / "synth.py", a.out / "points" / f"{p.name}.toml", "--out",
                              a.out / "synth", "--rom-dir", a.rom_dir, "--quiet", "--no-old-basis"])
            if rc != 0:
                say(f"    {p.name}: synth.py failed: {tail(se or so, 3)}")
                return dict(r, fmax_mhz=None)
        s = json.loads(sj.read_text())
        r = dict(r, fmax_mhz=s.get("fmax_mhz"), memory_ge=s.get("memory_ge"), synth_logic_ge=s.get("logic_ge"))
        atomic.write_text(a.out / "results" / f"{p.name}.json", json.dumps(r, indent=1) + "\n")
        return r
    return fmax_of


def rtl_check(a, names: list, rows: dict) -> dict:
    """Verilates the points into build-search/ and runs `pst regress` (the paper's scenes) on each."""
    results, todo = {}, []
    rdir = a.out / "rtl"
    for n in names:
        c = read_json(rdir / f"{n}.json")
        if c and c.get("profile_sha") == rows[n]["profile_sha"] and c.get("size") == a.rtl_size and c.get("passed"):
            results[n] = c
        else:
            todo.append(n)
    if not todo:
        return results
    pdir = a.out / "rtl_points"
    pdir.mkdir(parents=True, exist_ok=True)
    for f in pdir.glob("*.toml"):
        if f.stem not in names:
            f.unlink()
    for n in names:
        atomic.write_if_changed(pdir / f"{n}.toml", (a.out / "points" / f"{n}.toml").read_text())
    bdir = ROOT / "build-search"
    t0 = time.time()
    say(f"[rtl] verilating {len(names)} front point(s) into {bdir.name}/ (minutes each)")
    for cmd in (["cmake", "-S", ROOT, "-B", bdir, "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
                 "-DPST_PROFILES=reduced", "-DPST_TEST_PROFILES=none", f"-DPST_EXTRA_PROFILE_DIR={pdir}"],
                ["cmake", "--build", bdir, "--target", "pst", f"-j{a.jobs}"]):
        rc, so, se = run(cmd)
        if rc != 0:
            for n in todo:
                results[n] = {"passed": False, "summary": "build failed", "error": tail(se + so)}
            say(f"[rtl] build failed:\n{tail(se + so)}")
            return results
    say(f"[rtl] built in {time.time() - t0:.0f} s")
    for n in todo:
        t1 = time.time()
        jpath = rdir / f"{n}.regress.json"
        rdir.mkdir(parents=True, exist_ok=True)
        rc, so, se = run([bdir / "pst", "regress", "--profile", pdir / f"{n}.toml", "--size", a.rtl_size, "-o", jpath])
        runs = read_json(jpath) or []
        r = {"name": n, "profile_sha": rows[n]["profile_sha"], "size": a.rtl_size, **regress_summary(runs, rc),
             "seconds": round(time.time() - t1, 1)}
        atomic.write_text(rdir / f"{n}.json", json.dumps(r, indent=1) + "\n")
        results[n] = r
        say(f"[rtl] {n}: {r['summary']} ({r['seconds']:.0f} s)")
    return results


def main(argv=None) -> int:
    a = parse_args(argv if argv is not None else sys.argv[1:])
    a.out.mkdir(parents=True, exist_ok=True)
    t0 = time.time()
    job = Job(a)
    stats = {"points": set(), "modules_synthesized": 0}
    evaluate = make_evaluator(a, job, stats)
    fmax_of = make_fmax(a) if a.fmax > 0 else None
    say(f"search: classes {a.class_list}, targets {a.targets} dB, Fmax >= {a.fmax or '-'} MHz; "
        f"{len(job.settings['scenes']['train'])} training / {len(job.settings['scenes']['valid'])} validation scenes "
        f"at {a.size} x {a.size}; knobs {','.join(a.knob_list)}; budget {a.budget}/class; backend {a.backend} -> {a.out}")
    walks = {}
    archive = {}
    try:
        for c in a.class_list:
            path, doc = a.start_docs[c]
            text = path.read_text()
            structs = S.structures(doc["pipeline"]["octaves"], c, doc)
            start = S.make_point(text, doc, doc, "start")
            start.move = f"start ({path.stem})"
            targets = S.Targets(a.targets[c], c, a.fmax, max_loss=a.max_losses.get(c))
            bound = f", every training scene within {targets.max_loss:g} dB of the start" if targets.max_loss is not None else ""
            say(f"class <= {c} clk/px from {path.stem}, target {targets.psnr:g} dB{bound}:")
            w = S.walk(start, evaluate, targets, a.knob_list, structs, text, doc, a.budget, a.backtracks,
                       say=say, fmax_of=fmax_of)
            walks[c] = w
            archive.update(w["archive"])
        rows = []
        for n, (p, r) in archive.items():
            rows.append(dict(r, name=n, move=p.move, cpp=p.cpp, profile_sha=p.sha))
        fr = search_report.fronts(rows, a.class_list)
        front_names = sorted({r["name"] for f in fr.values() for r in f})
        # With --max-loss the starts are scored on the validation set too: each front point's
        # loss texture by texture is measured against its class's start there as well.
        starts = {c: w["path"][0] for c, w in walks.items()} if a.max_losses else {}
        say(f"validation of {len(front_names)} front point(s)")
        vnames = sorted(set(front_names) | set(starts.values()))
        vres = evaluate([archive[n][0] for n in vnames], which=("train", "valid"))
        by = {r["name"]: r for r in rows}
        for n in vnames:
            by[n].update({k: vres[n].get(k) for k in ("valid", "valid_worst", "valid_mean")})
        fr = search_report.fronts(rows, a.class_list)
        fr = {c: [dict(r, **search_report.losses(r, by.get(starts.get(c)), a.max_losses.get(c))) for r in f]
              for c, f in fr.items()}
        chosen = []
        for c, f in fr.items():
            chosen += [r["name"] for r in f][: (len(f) if a.rtl is None else a.rtl)]
        chosen = sorted(set(chosen))
        rtl = rtl_check(a, chosen, by) if chosen else {}
    except KeyboardInterrupt:
        stop_children()
        say("interrupted: finished points are kept in results/; rerun the same command to resume")
        return 130
    wall = time.time() - t0
    best = {c: (by.get(w["best"]) if w["best"] else None) for c, w in walks.items()}
    nsyn = sum(1 for r in rows if r.get("logic_ge") is not None)
    st = {"points": len(rows), "synthesized": nsyn, "modules_synthesized": stats["modules_synthesized"],
          "wall_s": wall, "points_per_hour": len(rows) / max(wall, 1e-9) * 3600,
          "train": len(job.settings["scenes"]["train"]), "valid": len(job.settings["scenes"]["valid"]), "size": a.size}
    frows = search_report.front_rows(fr, rtl)
    search_report.write_csv(a.out / "points.csv", sorted(rows, key=lambda r: (r["cpp"], r.get("logic_ge") or 1e18)),
                            ["name", "cpp", "logic_ge", "train_worst", "train_mean", "valid_worst", "status", "move"])
    search_report.write_csv(a.out / "front.csv", frows, search_report.COLUMNS)
    title = f"Design-space search ({a.size} x {a.size}, seed {a.seed})"
    atomic.write_text(a.out / "front.md", search_report.markdown(title, frows, a.targets, best, st, a.max_losses))
    search_report.plot(a.out / "front.png", rows, fr, title)
    atomic.write_text(a.out / "summary.json", json.dumps({"stats": st, "targets": a.targets,
                                                          "best": {c: b and b["name"] for c, b in best.items()},
                                                          "walks": {c: {"path": w["path"], "backtracks": w["backtracks"]}
                                                                    for c, w in walks.items()}}, indent=1) + "\n")
    shutil.rmtree(a.out / "tmp", ignore_errors=True)
    say(f"wrote {a.out / 'front.md'}, front.csv, front.png, points.csv: {len(rows)} points in {wall:.0f} s "
        f"({st['points_per_hour']:.1f} points/hour)")
    for c, b in best.items():
        if b:
            say(f"  <= {c} clk/px: {b['name']} {b['logic_ge']:,} GE, worst train {b['train_worst']:.2f} dB")
    flagged = [f"{r['name']} (class {r['class']})" for r in frows if r.get("valid_loss_flag")]
    if flagged:
        say(f"validation loss beyond --max-loss on some texture: {', '.join(flagged)}")
    bad_rtl = [n for n, r in rtl.items() if not r.get("passed")]
    bad = [r["name"] for r in rows if r.get("status") != "ok"]
    if bad_rtl or bad:
        say(f"FAILED: {', '.join(bad + ['rtl:' + n for n in bad_rtl])}")
        return 1
    return 0


if __name__ == "__main__":
    if len(sys.argv) >= 2 and sys.argv[1] == "worker":      # a SLURM array task: scripts/search.py worker OUT NAMES WHICH
        out = pathlib.Path(sys.argv[2])
        names = (out / "slurm" / sys.argv[3]).read_text().split()
        idx = int(os.environ.get("SLURM_ARRAY_TASK_ID", "0"))
        which = tuple(sys.argv[4].split(","))
        r = search_eval.evaluate(out, names[idx], which)
        sys.exit(0 if r.get("status") == "ok" else 1)
    sys.exit(main())
