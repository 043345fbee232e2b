"""The search's run: its settings from the command line's values (checked), the job on disk, the
evaluator (stored results reused, the rest on the local or the SLURM backend), Fmax by the
whole flow on the candidates that need it, the walks, validation, the RTL check and reports."""
import dataclasses
import hashlib
import json
import os
import pathlib
import shutil
import time

from ..validation import acceptance, scenegen, valset
from .. import atomic, contract
from ..fmt import tail
from ..paths import ROOT, profile_path
from ..synth import flow
from . import evaluate as E
from . import search as S
from . import search_report
from ..backends import slurm
from ..backends.local import STOP, run_points, say, stop_children
from .rtlcheck import rtl_check
from .store import Store, read_json

BIG = {"train": 32, "valid": 64, "size": 128, "paper": True, "budget": 200, "backtracks": 4,
       "psnr": "1=50,4=45,32=30"}
DEFAULTS = {"psnr": "40", "budget": 40, "backtracks": 2, "size": 48, "train": 8, "valid": 8, "paper": False}
DEFAULT_START = {1: "full_1clk", 2: "full_2clk", 3: "full", 4: "full_2clk", 32: "reduced"}
PAPER_SCENES = ["wood_teapot", "marble", "seascape", "fire", "planet", "moonrise", "zoneplate", "wood_torus"]


@dataclasses.dataclass
class SearchSettings:
    class_list: list
    targets: dict                   # class -> worst training PSNR, dB
    max_losses: dict                # class -> dB (empty: no texture-by-texture bound)
    start_docs: dict                # class -> (profile file, profile)
    knob_list: list
    out: pathlib.Path
    pst: str
    rom_dir: str
    module_cache: str
    size: int = 48
    train: int = 8
    valid: int = 8
    paper: bool = False
    seed: int = 1
    valid_seed: int = valset.DEFAULT_SEED
    budget: int = 40
    backtracks: int = 2
    fmax: float = 0.0
    synth_floor: float = 30.0
    jobs: int = 2
    backend: str = "local"
    slurm: dict = dataclasses.field(default_factory=dict)   # partition, account, time_limit, extra
    rtl: int | None = None
    rtl_size: int = 32
    retry_failed: bool = False


def per_class(spec: str, classes, conv, what):
    """A value per class from "V" (every class) or "C1=V1,C2=V2"; ValueError naming WHAT."""
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


def settings(o: dict) -> SearchSettings:
    """The search's settings from the command line's values O (None: --big's or the default);
    ValueError("--flag: what is wrong")."""
    o = dict(o)
    for k, v in (BIG if o.get("big") else {}).items():
        o[k] = v if o.get(k) is None else o[k]
    o.update({k: v for k, v in DEFAULTS.items() if o.get(k) is None})
    try:
        classes = [int(c) for c in o["classes"].split(",") if c.strip()]
    except ValueError:
        classes = []
    if not classes or min(classes) < 1:
        raise ValueError("--classes: positive integers")
    targets = per_class(o["psnr"], classes, float, "--psnr")
    losses = per_class(o["max_loss"], classes, float, "--max-loss") if o.get("max_loss") else {}
    if any(not 0 <= v < 100 for v in list(targets.values()) + list(losses.values())):
        raise ValueError("--psnr and --max-loss: dB in [0, 100)")
    starts = dict(DEFAULT_START)
    starts.update(per_class(o["start"], [], str, "--start") if o.get("start") else {})
    start_docs = {}
    for c in classes:
        p = profile_path(starts.get(c, "full"))
        try:
            start_docs[c] = (p, contract.read_profile(p))
        except (OSError, contract.ProfileError) as e:
            raise ValueError(f"--start: {e}") from None
    knobs = [k.strip() for k in (o.get("knobs") or ",".join(S.KNOB_NAMES)).split(",") if k.strip()]
    bad = [k for k in knobs if k not in S.KNOB_NAMES]
    if bad or not knobs:
        raise ValueError(f"--knobs: unknown {', '.join(bad) or '(none)'}; known: {', '.join(S.KNOB_NAMES)}")
    for ok, what in ((8 <= o["size"] <= 1024, "--size: must be in [8, 1024]"),
                     (1 <= o["train"] <= 1000 and 0 <= o["valid"] <= 1000, "--train: 1..1000, --valid: 0..1000"),
                     (o["budget"] >= 1 and o["backtracks"] >= 0 and o["jobs"] >= 1,
                      "--budget >= 1, --backtracks >= 0, --jobs >= 1"),
                     (os.access(o["pst"], os.X_OK), f"--pst: {o['pst']}: not an executable (cmake --build build --target pst)"),
                     ((pathlib.Path(o["rom_dir"]) / "hash4096.memh").exists(),
                      f"--rom-dir: {o['rom_dir']}: no ROM images (cmake --build build --target pst_rom_images)")):
        if not ok:
            raise ValueError(what)
    scenegen.check_training_seed(o.get("seed", 1))
    valid_seed = valset.DEFAULT_SEED if o.get("valid_seed") is None else o["valid_seed"]
    valset.check_seed(valid_seed, "--valid-seed")
    floor = o.get("synth_floor")
    return SearchSettings(classes, targets, losses, start_docs, knobs, pathlib.Path(o["out"]).resolve(), o["pst"],
                          o["rom_dir"], o["module_cache"], o["size"], o["train"], o["valid"], bool(o["paper"]),
                          o["seed"], valid_seed, o["budget"], o["backtracks"], o["fmax"],
                          min(targets.values()) - 10 if floor is None else floor, o["jobs"], o["backend"],
                          {"partition": o.get("partition"), "account": o.get("account"),
                           "time_limit": o.get("time_limit"), "extra": o.get("slurm_arg") or []},
                          o.get("rtl"), o["rtl_size"], o["retry_failed"])


class Job:
    """The search's shared state on disk: OUT/job.json (settings, every point's values hash),
    OUT/points/NAME.toml."""

    def __init__(self, s: SearchSettings):
        self.out = s.out
        self.points = {}
        old = read_json(self.out / "job.json") or {}
        self.known = old.get("points", {})
        sdir = self.out / "scenes"
        # Training scenes from scenegen (seed s.seed), validation from the held-out set (valset.py,
        # its own seed range): the front points are judged where no walk looked.
        scenegen.write(sdir, s.seed, {"train": s.train})
        if s.valid:
            valset.write(sdir / "holdout", s.valid_seed, s.valid, valset.DEFAULT_SIZE)
        else:
            for old in (sdir / "holdout").glob("val_*.toml"):
                old.unlink()
        train = sorted(str(p) for p in (sdir / "train").glob("train_*.toml"))
        if s.paper:
            train += [str(ROOT / "scenes" / f"{n}.toml") for n in PAPER_SCENES]
        pst_sha = hashlib.sha256(pathlib.Path(s.pst).read_bytes()).hexdigest()[:16]
        self.settings = {"size": s.size, "synth_floor": s.synth_floor, "pst": str(pathlib.Path(s.pst).resolve()),
                         "pst_sha": pst_sha, "module_cache": str(pathlib.Path(s.module_cache).resolve()),
                         "rom_dir": str(pathlib.Path(s.rom_dir).resolve()), "retry_failed": s.retry_failed,
                         "scenes": {"train": train,
                                    "valid": sorted(str(p) for p in (sdir / "holdout").glob("val_*.toml"))},
                         "valid_seed": s.valid_seed}
        self.save()

    def save(self):
        points = dict(self.known, **{n: p.sha for n, p in self.points.items()})
        atomic.write_text(self.out / "job.json", json.dumps(dict(self.settings, points=points), indent=1) + "\n")

    def add(self, pts):
        new = [p for p in pts if p.name not in self.points]
        for p in new:
            self.points[p.name] = p
            atomic.write_if_changed(self.out / "points" / f"{p.name}.toml", p.text)
        if new:
            self.save()


def make_evaluator(s: SearchSettings, job: Job, stats: dict):
    """evaluate(points, which) -> {name: result}: stored results reused, the rest run on the backend."""
    from ..synth import liberty, modules
    mc = modules.ModuleCache(pathlib.Path(s.module_cache), liberty.osu018_lib(), pathlib.Path(s.rom_dir))
    store = Store(s.out)

    def evaluate(points, which=("train",)):
        job.add(points)

        def cached(p):
            r = store.get(p.name)
            return r if E.search_reusable(r, p.sha, job.settings, which) else None

        def work(p):
            r = E.search_point(s.out, p.name, which, module_cache=mc)
            if STOP.is_set():
                raise KeyboardInterrupt
            return r

        def failed(p, e):
            return store.put(p.name, {"name": p.name, "profile_sha": p.sha, "size": s.size,
                                      "pst_sha": job.settings["pst_sha"], "status": "failed",
                                      "error": f"{type(e).__name__}: {e}", "cpp": p.cpp})

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

        if s.backend == "local":
            return run_points(points, s.jobs, cached, work, failed, report)
        res = {}
        todo = [p for p in points if cached(p) is None]
        for p in points:
            if p not in todo:
                res[p.name] = cached(p)
                report(p, res[p.name], "cached")
        if todo:
            slurm.run_search_array(s.out, [p.name for p in todo], which, **s.slurm)
        for p in todo:
            r = store.get(p.name)
            if not E.search_reusable(r, p.sha, job.settings, which):
                r = failed(p, RuntimeError("SLURM task left no complete result (rerun to retry)"))
            report(p, r, "run")
            res[p.name] = r
        return res

    return evaluate


def make_fmax(s: SearchSettings):
    """fmax_of(point, result): the whole flow (OpenSTA) on the point, cached in OUT/synth/."""
    store = Store(s.out)

    def fmax_of(p, r):
        sj = s.out / "synth" / f"{p.name}.json"
        if not sj.exists():
            try:
                flow.synthesize(s.out / "points" / f"{p.name}.toml",
                                flow.Options(out=s.out / "synth", rom_dir=pathlib.Path(s.rom_dir), old_basis=False))
            except (flow.InputError, RuntimeError) as e:
                say(f"    {p.name}: synthesis failed: {tail(str(e), 3)}")
                return dict(r, fmax_mhz=None)
        syn = json.loads(sj.read_text())
        return store.put(p.name, dict(r, fmax_mhz=syn.get("fmax_mhz"), fmax_derated_mhz=syn.get("fmax_derated_mhz"),
                                      memory_ge=syn.get("memory_ge"),
                                      synth_logic_ge=syn.get("logic_ge")))
    return fmax_of


def run(s: SearchSettings) -> int:
    """The walks of every class, validation of the fronts, the RTL check and the reports; the exit
    status (0, 1 a failed point or RTL check, 130 interrupted)."""
    s.out.mkdir(parents=True, exist_ok=True)
    t0 = time.time()
    job = Job(s)
    stats = {"points": set(), "modules_synthesized": 0}
    evaluate = make_evaluator(s, job, stats)
    fmax_of = make_fmax(s) if s.fmax > 0 else None
    say(f"search: classes {s.class_list}, targets {s.targets} dB, Fmax >= {s.fmax or '-'} MHz; "
        f"{len(job.settings['scenes']['train'])} training / {len(job.settings['scenes']['valid'])} validation scenes "
        f"at {s.size} x {s.size}; knobs {','.join(s.knob_list)}; budget {s.budget}/class; backend {s.backend} -> {s.out}")
    walks, archive = {}, {}
    try:
        for c in s.class_list:
            path, doc = s.start_docs[c]
            text = path.read_text()
            structs = S.structures(doc["pipeline"]["octaves"], c, doc)
            start = S.make_point(text, doc, doc, "start")
            start.move = f"start ({path.stem})"
            targets = S.Targets(s.targets[c], c, s.fmax, max_loss=s.max_losses.get(c))
            bound = f", every training scene within {targets.max_loss:g} dB of the start" if targets.max_loss is not None else ""
            say(f"class <= {c} clk/px from {path.stem}, target {targets.psnr:g} dB{bound}:")
            w = S.walk(start, evaluate, targets, s.knob_list, structs, text, doc, s.budget, s.backtracks,
                       say=say, fmax_of=fmax_of)
            walks[c] = w
            archive.update(w["archive"])
        rows = [dict(r, name=n, move=p.move, cpp=p.cpp, profile_sha=p.sha) for n, (p, r) in archive.items()]
        search_report.add_energy(rows, {c: s.start_docs[c][0].stem for c in s.class_list})
        fr = search_report.fronts(rows, s.class_list)
        front_names = sorted({r["name"] for f in fr.values() for r in f})
        # The starts are scored on the validation set too: each front point is judged by the rule
        # of acceptance (acceptance.py) against its class's start, scene by scene.
        starts = {c: w["path"][0] for c, w in walks.items()}
        say(f"validation of {len(front_names)} front point(s)")
        vnames = sorted(set(front_names) | set(starts.values()))
        vres = evaluate([archive[n][0] for n in vnames], which=("train", "valid"))
        by = {r["name"]: r for r in rows}
        for n in vnames:
            by[n].update({k: vres[n].get(k) for k in ("valid", "valid_worst", "valid_mean")})
        fr = search_report.fronts(rows, s.class_list)
        fr = {c: [dict(r, **search_report.losses(r, by.get(starts.get(c)))) for r in f] for c, f in fr.items()}
        chosen = sorted({r["name"] for f in fr.values() for r in f[: (len(f) if s.rtl is None else s.rtl)]})
        rtl = rtl_check(s.out, {n: (s.out / "points" / f"{n}.toml", by[n]["profile_sha"]) for n in chosen},
                        s.rtl_size, ROOT / "build-search", s.jobs) if chosen else {}
    except KeyboardInterrupt:
        stop_children()
        say("interrupted: finished points are kept in results/; rerun the same command to resume")
        return 130
    return report(s, job, stats, walks, rows, by, fr, rtl, time.time() - t0)


def report(s: SearchSettings, job: Job, stats: dict, walks: dict, rows: list, by: dict, fr: dict, rtl: dict,
           wall: float) -> int:
    """points.csv, front.csv, front.md, front.png, summary.json; the exit status."""
    best = {c: (by.get(w["best"]) if w["best"] else None) for c, w in walks.items()}
    nsyn = sum(1 for r in rows if r.get("logic_ge") is not None)
    st = {"points": len(rows), "synthesized": nsyn, "modules_synthesized": stats["modules_synthesized"],
          "wall_s": wall, "points_per_hour": len(rows) / max(wall, 1e-9) * 3600,
          "train": len(job.settings["scenes"]["train"]), "valid": len(job.settings["scenes"]["valid"]), "size": s.size}
    frows = search_report.front_rows(fr, rtl)
    search_report.write_csv(s.out / "points.csv", sorted(rows, key=lambda r: (r["cpp"], r.get("logic_ge") or 1e18)),
                            ["name", "cpp", "logic_ge", "energy_pj", "energy_ref", "ace", "train_worst", "train_mean",
                             "valid_worst", "status", "move"])
    search_report.write_csv(s.out / "front.csv", frows, search_report.COLUMNS)
    title = f"Design-space search ({s.size} x {s.size}, seed {s.seed})"
    atomic.write_text(s.out / "front.md", search_report.markdown(title, frows, s.targets, best, st, s.max_losses))
    search_report.plot(s.out / "front.png", rows, fr, title)
    atomic.write_text(s.out / "summary.json", json.dumps({"stats": st, "targets": s.targets,
                                                          "best": {c: b and b["name"] for c, b in best.items()},
                                                          "walks": {c: {"path": w["path"], "backtracks": w["backtracks"]}
                                                                    for c, w in walks.items()}}, indent=1) + "\n")
    shutil.rmtree(s.out / "tmp", ignore_errors=True)
    say(f"wrote {s.out / 'front.md'}, front.csv, front.png, points.csv: {len(rows)} points in {wall:.0f} s "
        f"({st['points_per_hour']:.1f} points/hour)")
    for c, b in best.items():
        if b:
            say(f"  <= {c} clk/px: {b['name']} {b['logic_ge']:,} GE, worst train {b['train_worst']:.2f} dB")
    failed = [f"{r['name']} (class {r['class']}, {r['valid_loss']:.2f} dB on {r['valid_loss_scene']})"
              for r in frows if r.get("valid_pass") is False]
    if failed:
        say(f"front points losing more than {acceptance.TOLERANCE_DB:g} dB against the start on a validation scene: "
            f"{', '.join(failed)}")
    bad_rtl = [n for n, r in rtl.items() if not r.get("passed")]
    bad = [r["name"] for r in rows if r.get("status") != "ok"]
    if bad_rtl or bad:
        say(f"FAILED: {', '.join(bad + ['rtl:' + n for n in bad_rtl])}")
        return 1
    return 0


def worker(out: pathlib.Path, names_file: str, which: str) -> int:
    """A SLURM array task: evaluates the point at $SLURM_ARRAY_TASK_ID of OUT/slurm/NAMES_FILE."""
    names = (out / "slurm" / names_file).read_text().split()
    r = E.search_point(out, names[int(os.environ.get("SLURM_ARRAY_TASK_ID", "0"))], tuple(which.split(",")))
    return 0 if r.get("status") == "ok" else 1
