"""Running pst and synthesis for sweep points: child processes that an interrupt stops, the
synthesis cache, one point's renders and gate count, and which stored results can be reused."""
import concurrent.futures
import hashlib
import json
import os
import pathlib
import shutil
import signal
import subprocess
import threading
import time
import tomllib

from . import atomic
from .fmt import tail
from .paths import PY, ROOT

STOP = threading.Event()
_procs = set()
_procs_lock = threading.Lock()
_print_lock = threading.Lock()


def say(msg: str) -> None:
    with _print_lock:
        print(msg, flush=True)


def run(cmd, cwd=ROOT, timeout=None, on_start=None):
    """Runs a command in its own process group (so an interrupt can stop its children too);
    on_start(pid) is called once it runs."""
    if STOP.is_set():
        raise KeyboardInterrupt
    p = subprocess.Popen([str(c) for c in cmd], cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                         text=True, start_new_session=True)
    with _procs_lock:
        _procs.add(p)
    try:
        if on_start:
            on_start(p.pid)
        out, err = p.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        out, err = p.communicate()
        err = (err or "") + f"\n(timed out after {timeout} s)"
    finally:
        with _procs_lock:
            _procs.discard(p)
    if STOP.is_set():
        raise KeyboardInterrupt
    return p.returncode, out, err


def stop_children() -> None:
    STOP.set()
    with _procs_lock:
        procs = list(_procs)
    for p in procs:
        try:
            os.killpg(p.pid, signal.SIGTERM)
        except ProcessLookupError:
            pass


def run_points(todo: list, jobs: int, cached, work, failed, report) -> dict:
    """Name -> result of every point of TODO: cached(pt) where it gives one, else work(pt) on JOBS
    threads (failed(pt, exception) when work raises). report(pt, result, "cached" or "run") as
    each is known. An interrupt (Ctrl-C, SIGTERM) stops the children and the queued points, then
    raises KeyboardInterrupt; the finished points' results stay where work put them."""
    results = {}
    interrupted = False

    def on_term(*_):
        raise KeyboardInterrupt
    prev = signal.signal(signal.SIGTERM, on_term)
    pool = concurrent.futures.ThreadPoolExecutor(max_workers=jobs)
    try:
        futs = {}
        for pt in todo:
            r = cached(pt)
            if r is not None:
                results[pt.name] = r
                report(pt, r, "cached")
            else:
                futs[pool.submit(work, pt)] = pt
        for f in concurrent.futures.as_completed(futs):
            pt = futs[f]
            try:
                r = f.result()
            except KeyboardInterrupt:
                raise
            except Exception as e:
                r = failed(pt, e)
            results[pt.name] = r
            report(pt, r, "run")
    except KeyboardInterrupt:
        interrupted = True
        stop_children()
        pool.shutdown(wait=True, cancel_futures=True)
        raise
    finally:
        if not interrupted:
            pool.shutdown(wait=True)
        signal.signal(signal.SIGTERM, prev)
    return results


# ----------------------------------------------------------------------------------------------
# Synthesis cache: out/synth/NAME.json with a sidecar NAME.sweep.json of content keys

SYNTH_MODULES = ("liberty.py", "memarea.py", "sta.py")     # pstlib modules scripts/synth.py uses


def synth_inputs(root=ROOT) -> list:
    """What a gate count depends on besides the profile: the RTL, scripts/synth.py with its pstlib
    modules and its files in scripts/synth/ (cell libraries, stand-ins, constraints)."""
    synth = root / "scripts" / "synth"
    return [root / "scripts" / "synth.py",
            *[root / "scripts" / "pstlib" / m for m in SYNTH_MODULES if (root / "scripts" / "pstlib" / m).exists()],
            *sorted(p for p in synth.glob("*") if p.suffix in (".lib", ".v", ".sdc")),
            *sorted((root / "rtl").glob("*.sv"))]


def synth_key(profile: pathlib.Path, inputs=None) -> dict:
    """Content keys of a synthesis: the profile's values (comments aside) and the RTL + synthesis
    script + cell library."""
    h = hashlib.sha256()
    for f in synth_inputs() if inputs is None else inputs:
        h.update(f.name.encode() + b"\0" + f.read_bytes() + b"\0")
    values = json.dumps(tomllib.loads(profile.read_text()), sort_keys=True)
    return {"profile": hashlib.sha256(values.encode()).hexdigest()[:16], "rtl": h.hexdigest()[:16]}


def synth_cache_valid(synth_json: pathlib.Path, profile: pathlib.Path, inputs=None) -> bool:
    """out/synth/NAME.json stands for this profile: its sidecar NAME.sweep.json has the same
    content keys or, without a sidecar (a synthesis run by hand), it is newer than the profile
    and every synthesis input."""
    inputs = synth_inputs() if inputs is None else inputs
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
            return json.loads(side.read_text()) == synth_key(profile, inputs)
        except (OSError, ValueError):
            return False
    t = synth_json.stat().st_mtime
    return not any(d.stat().st_mtime > t for d in [profile, *inputs])


def synth_record(sha: str, sj: pathlib.Path, key=None) -> dict:
    """What a point's result keeps of its synthesis; KEY (synth_key of the profile when it was
    recorded) lets a resumed sweep see that the RTL or the synthesis flow changed since."""
    s = json.loads(sj.read_text())
    return {"sha": sha, "key": key, "file": str(sj), "logic_ge": s["logic_ge"],
            "rom_bits": s.get("rom_bits"), "ram_bits": s.get("ram_bits"),
            "flip_flops": s.get("flip_flops"), "yosys_seconds": s.get("yosys_seconds"),
            "blocks": {b: v.get("logic_ge") for b, v in s.get("blocks", {}).items()}}


# ----------------------------------------------------------------------------------------------
# One point

SUMMARY_KEYS = ("vs_reference", "vs_truth", "reference_vs_truth", "notes", "fragments")


def scene_record(summary: dict) -> dict:
    """What a point's result keeps of one render's summary.json."""
    return {k: summary.get(k) for k in SUMMARY_KEYS}


def synth_current(r: dict, pt, key=None) -> bool:
    """R's synthesis record stands for point PT: same profile and, when KEY (the synth_key now) is
    given, the same RTL and synthesis flow as when it was recorded."""
    syn = r.get("synth")
    return bool(syn) and syn.get("sha") == pt.profile_sha and (key is None or syn.get("key") == key)


def reusable(r, pt, settings: dict, scenes, retry_failed: bool, synth_to_do, key=None) -> bool:
    """A stored result R (None or the parsed results/<name>.json) can stand for point PT as it is:
    same profile text and render settings, every scene rendered, not failed (unless failures are
    kept), and no synthesis to add (synth_to_do(): a synthesis would run or a cached one be picked
    up). With KEY (synth_key of the profile now), a synthesis recorded under another RTL or flow is
    one to add again."""
    if not isinstance(r, dict):
        return False
    if r.get("profile_sha") != pt.profile_sha or r.get("settings") != settings:
        return False
    if set(scenes) - set(r.get("scenes", {})):
        return False
    if r.get("status") != "ok":
        return not retry_failed
    return pt.knob == "filter" or synth_current(r, pt, key) or not synth_to_do()


def read_json(path: pathlib.Path):
    """The parsed file, None when it is missing or not JSON."""
    try:
        return json.loads(path.read_text())
    except (OSError, ValueError):
        return None


def run_point(pt, a, out: pathlib.Path) -> dict:
    """Renders the scenes and synthesizes the profile of one point (what is not done yet)."""
    settings = {"size": a.size, "truth": a.truth}
    old = read_json(out / "results" / f"{pt.name}.json")
    if old and (old.get("profile_sha") != pt.profile_sha or old.get("settings") != settings):
        old = None          # the profile or the render settings changed: start again
    res = old or {"name": pt.name, "knob": pt.knob, "value": pt.value, "profile": str(pt.profile),
                  "profile_sha": pt.profile_sha, "settings": settings, "scenes": {}, "synth": None}
    res["status"] = "ok"
    res.pop("error", None)
    t0 = time.time()
    did = []
    # 1. Golden renders of the scenes not yet done.
    for scene, scene_file in pt.scene_files.items():
        if scene in res["scenes"]:
            continue
        rdir = out / "renders" / pt.name / scene
        cmd = [a.pst, "render", scene_file, "--profile", pt.profile, "--model", "golden", "--size", a.size,
               "-o", rdir, "-q", "-j", "1"]
        if a.truth > 0:
            cmd += ["--truth", a.truth]
        rc, so, se = run(cmd)
        summary = rdir / "summary.json"
        if rc != 0 or not summary.exists():
            res["status"] = "failed"
            res["error"] = f"pst render {scene} exited {rc}:\n{tail(se or so)}"
            return res
        res["scenes"][scene] = scene_record(json.loads(summary.read_text()))
        did.append("render")
    res["render_seconds"] = round(time.time() - t0, 1) if did else res.get("render_seconds")
    # 2. Synthesis (cached in out/synth/<name>.json).
    res["synth_note"] = None
    key = None if pt.knob == "filter" else synth_key(pt.profile)
    have = synth_current(res, pt, key)
    sj = a.synth_dir / f"{pt.synth_name}.json"
    if not a.no_synth and pt.knob != "filter" and not have:
        if synth_cache_valid(sj, pt.profile):
            res["synth_note"] = "synth cached"
        else:
            err = synthesize(pt, a.synth_dir, out / "tmp" / pt.name, res)
            if err:
                res["status"] = "failed"
                res["error"] = err
                return res
        res["synth"] = synth_record(pt.profile_sha, sj, key)
    elif have:
        res["synth_note"] = "synth cached"
    elif a.no_synth and pt.knob != "filter" and synth_cache_valid(sj, pt.profile):
        res["synth"] = synth_record(pt.profile_sha, sj, key)     # free: already synthesized
        res["synth_note"] = "synth cached"
    return res


def synthesize(pt, synth_dir: pathlib.Path, tmp: pathlib.Path, res: dict):
    """scripts/synth.py on the point's profile into TMP, then moved into SYNTH_DIR with its sidecar;
    an error message, or None."""
    shutil.rmtree(tmp, ignore_errors=True)
    tmp.mkdir(parents=True)
    t1 = time.time()
    key = synth_key(pt.profile)       # before the run: an input edited meanwhile makes it stale
    rc, so, se = run([PY, ROOT / "scripts" / "synth.py", pt.profile, "--out", tmp, "--quiet"])
    secs = time.time() - t1
    made = tmp / f"{pt.synth_name}.json"
    if rc != 0 or not made.exists():
        return f"scripts/synth.py exited {rc}:\n{tail(se or so)}"
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
