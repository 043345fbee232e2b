"""Evaluating a point: golden renders of its scenes (`pst render --model golden`) and its area.

- A sweep point (sweep_point): every scene rendered with its ground truth, the render's
  summary kept per scene; area by the whole flow (pstlib.synth.flow: logic, memories), cached
  as out/synth/NAME.json with a sidecar of content keys.
- A search point (search_point): the PSNR of each training (and validation) scene; logic area
  from the per-module cache (pstlib.synth.modules); stored in OUT/results/NAME.json, so an
  interrupted search (local workers or a SLURM array) resumes where it stopped. The job's
  settings (image size, the scene sets, the PSNR floor below which a point is not
  synthesized) live in OUT/job.json, written by the driver; a worker (`scripts/search.py
  worker OUT NAME`, what a SLURM array task runs) reads them and OUT/points/NAME.toml.
"""
import hashlib
import json
import os
import pathlib
import shutil
import time
import tomllib

from .. import atomic, contract
from ..fmt import tail
from ..synth import flow, inputs, liberty
from ..backends.local import run
from .results import psnr as summary_psnr
from .store import Store, read_json, reusable

SUMMARY_KEYS = ("vs_reference", "vs_truth", "reference_vs_truth", "notes", "fragments")


def render(pst, scene, profile, size: int, rdir: pathlib.Path, truth: int = 0):
    """The golden model of PROFILE on one scene at SIZE (and its TRUTH x TRUTH ground truth):
    (summary.json parsed, None) or (None, an error text)."""
    cmd = [pst, "render", scene, "--profile", profile, "--model", "golden", "--size", size, "-o", rdir, "-q", "-j", "1"]
    if truth > 0:
        cmd += ["--truth", truth]
    rc, so, se = run(cmd)
    sj = rdir / "summary.json"
    if rc != 0 or not sj.exists():
        return None, f"pst render {pathlib.Path(scene).stem} exited {rc}:\n{tail(se or so)}"
    return json.loads(sj.read_text()), None


# ---- the sweep's area: the whole flow, cached as out/synth/NAME.json with a sidecar NAME.sweep.json

def synth_inputs() -> list:
    """What a gate count depends on besides the profile: the files of pstlib.synth.inputs
    (RTL, contract, the flow's code and scripts/synth/ files, the cell library, the ROM images
    the flow reads by default)."""
    return inputs.input_files(liberty.osu018_lib(), flow.Options().rom_dir)


def synth_key(profile: pathlib.Path, files=None) -> dict:
    """Content keys of a synthesis: the profile's values (comments aside), and every input
    file with the Yosys and OpenSTA versions."""
    values = json.dumps(tomllib.loads(profile.read_text()), sort_keys=True)
    return {"profile": hashlib.sha256(values.encode()).hexdigest()[:16],
            "inputs": inputs.digest(synth_inputs() if files is None else files, inputs.tool_versions())}


def synth_cache_valid(synth_json: pathlib.Path, profile: pathlib.Path, files=None) -> bool:
    """out/synth/NAME.json stands for this profile: its sidecar NAME.sweep.json has the same
    content keys or, without a sidecar (a synthesis run by hand), it is newer than the profile
    and every synthesis input."""
    files = synth_inputs() if files is None else files
    if not synth_json.exists():
        return False
    try:
        if "logic_ge" not in json.loads(synth_json.read_text()):
            return False
    except (OSError, ValueError):
        return False
    side = synth_json.with_name(synth_json.stem + ".sweep.json")
    if side.exists():
        try:
            return json.loads(side.read_text()) == synth_key(profile, files)
        except (OSError, ValueError):
            return False
    t = synth_json.stat().st_mtime
    return not any(d.stat().st_mtime > t for d in [profile, *files])


def synth_record(sha: str, sj: pathlib.Path, key=None) -> dict:
    """What a point's result keeps of its synthesis; KEY (synth_key of the profile when it was
    recorded) lets a resumed sweep see that the RTL or the synthesis flow changed since."""
    s = json.loads(sj.read_text())
    return {"sha": sha, "key": key, "file": str(sj), "logic_ge": s["logic_ge"],
            "rom_bits": s.get("rom_bits"), "ram_bits": s.get("ram_bits"),
            "flip_flops": s.get("flip_flops"), "yosys_seconds": s.get("yosys_seconds"),
            "blocks": {b: v.get("logic_ge") for b, v in s.get("blocks", {}).items()}}


def synth_current(r: dict, pt, key=None) -> bool:
    """R's synthesis record stands for point PT: same profile and, when KEY (the synth_key now) is
    given, the same RTL and synthesis flow as when it was recorded."""
    syn = r.get("synth")
    return bool(syn) and syn.get("sha") == pt.sha and (key is None or syn.get("key") == key)


# ---- a sweep point

def scene_record(summary: dict) -> dict:
    """What a point's result keeps of one render's summary.json."""
    return {k: summary.get(k) for k in SUMMARY_KEYS}


def sweep_reusable(r, pt, settings: dict, scenes, retry_failed: bool, synth_to_do, key=None) -> bool:
    """The reuse rule (store.reusable) for a sweep point: same render settings and scenes, and no
    synthesis to add (synth_to_do(): one would run or a cached one be picked up; with KEY, the
    synth_key of the profile now, one recorded under another RTL or flow is to add again)."""
    def area_missing(r):
        return not (pt.knob == "filter" or synth_current(r, pt, key) or not synth_to_do())
    return reusable(r, pt.sha, {"settings": settings}, {"scenes": scenes}, retry_failed, area_missing)


def sweep_point(pt, out: pathlib.Path, pst, size: int, truth: int, synth_dir: pathlib.Path, no_synth: bool) -> dict:
    """Renders the scenes and synthesizes the profile of one sweep point (what is not done yet)."""
    settings = {"size": size, "truth": truth}
    old = Store(out).get(pt.name)
    if old and (old.get("profile_sha") != pt.sha or old.get("settings") != settings):
        old = None          # the profile or the render settings changed: start again
    res = old or {"name": pt.name, "knob": pt.knob, "value": pt.value, "profile": str(pt.profile),
                  "profile_sha": pt.sha, "settings": settings, "scenes": {}, "synth": None}
    res["status"] = "ok"
    res.pop("error", None)
    t0 = time.time()
    did = []
    # 1. Golden renders of the scenes not yet done.
    for scene, scene_file in pt.scene_files.items():
        if scene in res["scenes"]:
            continue
        summary, err = render(pst, scene_file, pt.profile, size, out / "renders" / pt.name / scene, truth)
        if err:
            return dict(res, status="failed", error=err)
        res["scenes"][scene] = scene_record(summary)
        did.append("render")
    res["render_seconds"] = round(time.time() - t0, 1) if did else res.get("render_seconds")
    # 2. Synthesis (cached in out/synth/<name>.json).
    res["synth_note"] = None
    key = None if pt.knob == "filter" else synth_key(pt.profile)
    have = synth_current(res, pt, key)
    sj = synth_dir / f"{pt.synth_name}.json"
    if not no_synth and pt.knob != "filter" and not have:
        if synth_cache_valid(sj, pt.profile):
            res["synth_note"] = "synth cached"
        else:
            err = synthesize(pt, synth_dir, out / "tmp" / pt.name, res)
            if err:
                return dict(res, status="failed", error=err)
        res["synth"] = synth_record(pt.sha, sj, key)
    elif have:
        res["synth_note"] = "synth cached"
    elif no_synth and pt.knob != "filter" and synth_cache_valid(sj, pt.profile):
        res["synth"] = synth_record(pt.sha, sj, key)     # free: already synthesized
        res["synth_note"] = "synth cached"
    return res


def synthesize(pt, synth_dir: pathlib.Path, tmp: pathlib.Path, res: dict):
    """The flow on the point's profile into TMP, then moved into SYNTH_DIR with its sidecar; an
    error message, or None."""
    shutil.rmtree(tmp, ignore_errors=True)
    tmp.mkdir(parents=True)
    t1 = time.time()
    key = synth_key(pt.profile)       # before the run: an input edited meanwhile makes it stale
    try:
        flow.synthesize(pt.profile, flow.Options(out=tmp))
    except (flow.InputError, RuntimeError) as e:
        return f"synthesis failed: {tail(str(e))}"
    secs = time.time() - t1
    synth_dir.mkdir(parents=True, exist_ok=True)
    side = synth_dir / f"{pt.synth_name}.sweep.json"
    side.unlink(missing_ok=True)
    for ext in ("md", "json"):      # then the sidecar: it makes the json a valid cache
        if (tmp / f"{pt.synth_name}.{ext}").exists():
            os.replace(tmp / f"{pt.synth_name}.{ext}", synth_dir / f"{pt.synth_name}.{ext}")
    atomic.write_text(side, json.dumps(key) + "\n")
    shutil.rmtree(tmp, ignore_errors=True)
    res["synth_note"] = f"synth {secs:.0f} s"
    return None


# ---- a search point

def job_settings(out: pathlib.Path) -> dict:
    return json.loads((out / "job.json").read_text())


def render_psnr(pst: str, scene: pathlib.Path, profile: pathlib.Path, size: int, rdir: pathlib.Path):
    """PSNR (dB, capped at 100) of the golden model of PROFILE against the double reference on one
    scene, or an error text."""
    summary, err = render(pst, scene, profile, size, rdir)
    return (None, err) if err else (summary_psnr(summary.get("vs_reference")), None)


def scene_sets(job: dict, which=("train",)) -> dict:
    return {s: {pathlib.Path(f).stem: pathlib.Path(f) for f in job["scenes"][s]} for s in which}


def search_reusable(r, sha: str, job: dict, which) -> bool:
    """The reuse rule (store.reusable) for a search point: same image size and pst build (the sha
    of the binary: its golden model and verilated RTL), every scene of the sets in WHICH scored,
    and its area done when the job wants one."""
    return reusable(r, sha, {"size": job["size"], "pst_sha": job.get("pst_sha")},
                    {s: [pathlib.Path(f).stem for f in job["scenes"][s]] for s in which}, job.get("retry_failed"),
                    lambda r: _wants_area(r, job) and r.get("logic_ge") is None)


def _wants_area(r, job) -> bool:
    return r.get("train_worst") is not None and r["train_worst"] >= job["synth_floor"]


def search_point(out: pathlib.Path, name: str, which=("train",), module_cache=None, pst=None) -> dict:
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
    r["cpp"] = contract.stage_cycles(doc)["pixel"]
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
            from ..synth import liberty, modules
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
