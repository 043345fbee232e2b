"""One search point: golden renders of the training (and validation) scenes, clocks per pixel,
logic area from the per-module synthesis cache; stored atomically in OUT/results/NAME.json, so
an interrupted search (local workers or a SLURM array) resumes where it stopped.

The job's settings (image size, the scene sets, the PSNR floor below which a point is not
synthesized) live in OUT/job.json, written by the driver; a worker (`scripts/search.py worker
OUT NAME`, what a SLURM array task runs) reads them and OUT/points/NAME.toml."""
import json
import pathlib
import time

from . import atomic, contract
from .fmt import tail
from .results import psnr as summary_psnr
from .runner import read_json, run
from .search import cycles_per_pixel


def job_settings(out: pathlib.Path) -> dict:
    return json.loads((out / "job.json").read_text())


def render_psnr(pst: str, scene: pathlib.Path, profile: pathlib.Path, size: int, rdir: pathlib.Path):
    """PSNR (dB, capped at 100) of the golden model of PROFILE against the double reference on one
    scene, or an error text."""
    rc, so, se = run([pst, "render", scene, "--profile", profile, "--model", "golden", "--size", size,
                      "-o", rdir, "-q", "-j", "1"])
    sj = rdir / "summary.json"
    if rc != 0 or not sj.exists():
        return None, f"pst render {scene.name} exited {rc}: {tail(se or so, 3)}"
    return summary_psnr(json.loads(sj.read_text()).get("vs_reference")), None


def scene_sets(job: dict, which=("train",)) -> dict:
    return {s: {pathlib.Path(f).stem: pathlib.Path(f) for f in job["scenes"][s]} for s in which}


def reusable(r, sha: str, job: dict, which) -> bool:
    """A stored result stands: same profile values, image size and pst build (the sha of the
    binary: its golden model and verilated RTL), every scene of the sets in WHICH scored, and its
    area done when the job wants one."""
    if not isinstance(r, dict) or r.get("profile_sha") != sha or r.get("size") != job["size"]:
        return False
    if r.get("pst_sha") != job.get("pst_sha"):      # another pst build (RTL, golden model): score again
        return False
    if r.get("status") != "ok":
        return not job.get("retry_failed")
    for s in which:
        if set(pathlib.Path(f).stem for f in job["scenes"][s]) - set(r.get(s, {})):
            return False
    return not _wants_area(r, job) or r.get("logic_ge") is not None


def _wants_area(r, job) -> bool:
    return r.get("train_worst") is not None and r["train_worst"] >= job["synth_floor"]


def evaluate(out: pathlib.Path, name: str, which=("train",), module_cache=None, pst=None) -> dict:
    """Evaluates point NAME (what is not stored yet) and stores the result."""
    job = job_settings(out)
    prof = out / "points" / f"{name}.toml"
    doc = contract.read_profile(prof)
    sha = job["points"].get(name) or ""
    path = out / "results" / f"{name}.json"
    old = read_json(path)
    if old and (old.get("profile_sha") != sha or old.get("size") != job["size"]
                or old.get("pst_sha") != job.get("pst_sha")):
        old = None
    r = old or {"name": name, "profile": str(prof), "profile_sha": sha, "size": job["size"],
                "pst_sha": job.get("pst_sha")}
    r["status"] = "ok"
    r.pop("error", None)
    r["cpp"] = cycles_per_pixel(doc)
    t0 = time.time()
    pst = pst or job["pst"]
    for s, scenes in scene_sets(job, which).items():
        got = r.setdefault(s, {})
        for scene, f in scenes.items():
            if scene in got:
                continue
            p, err = render_psnr(pst, f, prof, job["size"], out / "renders" / name / scene)
            if err:
                r.update(status="failed", error=err)
                atomic.write_text(path, json.dumps(r, indent=1) + "\n")
                return r
            got[scene] = p
        vals = [got[k] for k in scenes]
        r[f"{s}_worst"] = min(vals) if vals and None not in vals else None
        r[f"{s}_mean"] = sum(vals) / len(vals) if vals and None not in vals else None
    r["area_new"] = False
    r["render_seconds"] = round(time.time() - t0, 1) + (old or {}).get("render_seconds", 0)
    if _wants_area(r, job) and r.get("logic_ge") is None:
        if module_cache is None:
            from .synth import liberty, modules
            module_cache = modules.ModuleCache(pathlib.Path(job["module_cache"]), liberty.osu018_lib(),
                                                    pathlib.Path(job["rom_dir"]))
        try:
            a = module_cache.area(doc)
        except Exception as e:           # a tool failure: recorded, the search goes on
            r.update(status="failed", error=f"synthesis: {type(e).__name__}: {tail(str(e), 5)}")
            atomic.write_text(path, json.dumps(r, indent=1) + "\n")
            return r
        r["area"] = a
        r["logic_ge"] = a["logic_ge"]
        r["area_new"] = True
    atomic.write_text(path, json.dumps(r, indent=1) + "\n")
    return r
