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
    values; rtl/*.sv, scripts/synth.py, the cell library); --no-synth still uses a valid cache;
  - out/sweep/<base>/results/<name>.json, written through a temporary file and a rename.
    A point with a result is not recomputed (resumable; a result without synthesis gets only
    its synthesis added; other scenes / size / truth re-render it; --retry-failed reruns the
    failed ones).
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
import concurrent.futures
import copy
import csv
import hashlib
import io
import json
import math
import os
import pathlib
import re
import shutil
import signal
import subprocess
import sys
import threading
import time
import tomllib

ROOT = pathlib.Path(__file__).resolve().parent.parent
PY = "/usr/bin/python3"
DEFAULT_SCENES = ["wood_teapot", "marble", "seascape", "fire", "planet", "zoneplate"]
PSNR_CAP = 100.0        # PSNR of an exact match (rms 0) in the means
RTL_SIZE = 64


# ----------------------------------------------------------------------------------------------
# Knobs: name -> (what it changes, default values, apply(doc, value) -> None, base(doc) -> value)

def _set_format_frac(*names):
    def apply(doc, v):
        for n in names:
            doc["formats"][n]["frac"] = v
    return apply


def _apply_octaves(doc, v):
    pipe = doc["pipeline"]
    units = pipe["noise_units"]
    if units == pipe["octaves"]:
        units = v                      # one pass per pixel stays one pass per pixel
    else:
        units = max(d for d in range(1, units + 1) if v % d == 0)   # the most units <= the base's
    pipe["octaves"] = v
    pipe["noise_units"] = units


def _apply_key(section, key):
    def apply(doc, v):
        doc[section][key] = v
    return apply


KNOBS = {
    "coord_frac": ("formats.coord.frac", [6, 8, 10, 12, 14, 16, 20],
                   _set_format_frac("coord"), lambda d: d["formats"]["coord"]["frac"]),
    "jacobian_frac": ("formats.jacobian.frac", [8, 10, 12, 16, 24],
                      _set_format_frac("jacobian"), lambda d: d["formats"]["jacobian"]["frac"]),
    "noise_value_frac": ("noise.value_frac", [4, 5, 7, 9, 11, 15],
                         _apply_key("noise", "value_frac"), lambda d: d["noise"]["value_frac"]),
    "lattice_frac": ("noise.lattice_frac", [4, 6, 8, 10, 12, 16],
                     _apply_key("noise", "lattice_frac"), lambda d: d["noise"]["lattice_frac"]),
    "out_frac": ("noise.out_frac (noise value / weight-product bits)", [6, 8, 10, 12, 16],
                 _apply_key("noise", "out_frac"), lambda d: d["noise"]["out_frac"]),
    "guard_bits": ("noise.guard_bits (noise node fraction bits below out_frac)", [1, 2, 3, 4, 6],
                   _apply_key("noise", "guard_bits"), lambda d: d["noise"]["guard_bits"]),
    "amp_frac": ("formats.amplitude.frac = grad_matrix.frac = matrix.frac", [6, 8, 10, 12, 16],
                 _set_format_frac("amplitude", "grad_matrix", "matrix"),
                 lambda d: d["formats"]["amplitude"]["frac"]
                 if d["formats"]["amplitude"]["frac"] == d["formats"]["grad_matrix"]["frac"]
                 == d["formats"]["matrix"]["frac"] else None),
    "colour_bits": ("pipeline.colour_bits", [5, 6, 7, 8],
                    _apply_key("pipeline", "colour_bits"), lambda d: d["pipeline"]["colour_bits"]),
    "octaves": ("pipeline.octaves (noise_units: all of them if the base has one pass, else the "
                "largest divisor)", [1, 2, 3, 4, 6, 8],
                _apply_octaves, lambda d: d["pipeline"]["octaves"]),
    "interp": ("noise.interp", ["scurve", "linear"], _apply_key("noise", "interp"), lambda d: d["noise"]["interp"]),
    "hash": ("noise.hash", ["rayshade", "perm256"], _apply_key("noise", "hash"), lambda d: d["noise"]["hash"]),
    "corner": ("noise.corner", ["value_gradient", "value"], _apply_key("noise", "corner"),
               lambda d: d["noise"]["corner"]),
    "norm": ("filter.norm", ["euclid", "max_half_min", "l1"], _apply_key("filter", "norm"),
             lambda d: d["filter"]["norm"]),
    "datapath": ("pipeline.datapath (gates and cycles only: the images are the same bit for bit)",
                 ["parallel", "serial"], _apply_key("pipeline", "datapath"), lambda d: d["pipeline"]["datapath"]),
    "noise_steps": ("pipeline.noise_steps (gates and cycles only: the images are the same bit for bit)",
                    [1, 2, 4, 8], _apply_key("pipeline", "noise_steps"), lambda d: d["pipeline"]["noise_steps"]),
    "filter": ("every texture's filter (scene copies; not a profile key)", ["none", "mip", "mip_linear", "sat"],
               None, lambda d: None),
}

QUICK = {"base": "reduced", "knobs": "coord_frac,octaves,hash", "scenes": "marble,zoneplate", "size": 64,
         "truth": 2, "rtl_subset": 0, "values": ["coord_frac=8,10,16", "octaves=2,8"]}

ENUMS = {("pipeline", "datapath"): ["parallel", "serial"], ("noise", "interp"): ["scurve", "linear"], ("noise", "corner"): ["value_gradient", "value"],
         ("noise", "hash"): ["rayshade", "perm256"], ("filter", "norm"): ["euclid", "max_half_min", "l1"]}
FORMAT_MAX = {"coord": 40, "jacobian": 40, "matrix": 32, "offset": 32, "amplitude": 32, "grad_matrix": 32,
              "quadric": 32, "f": 48, "grad": 48}


def validate(doc: dict) -> list:
    """What model/golden/profile.cpp and the RTL's assertions would reject (empty: valid)."""
    bad = []

    def rng(sec, key, lo, hi):
        v = doc.get(sec, {}).get(key)
        if not isinstance(v, int) or not lo <= v <= hi:
            bad.append(f"{sec}.{key} = {v} outside [{lo}, {hi}]")
    for key, lo, hi in [("octaves", 1, 16), ("noise_units", 1, 16), ("log2_clut", 1, 11), ("colour_bits", 1, 8)]:
        rng("pipeline", key, lo, hi)
    for key, lo, hi in [("value_frac", 1, 15), ("lattice_frac", 1, 20), ("out_frac", 1, 24), ("guard_bits", 1, 8)]:
        rng("noise", key, lo, hi)
    rng("filter", "recip_frac", 4, 24)
    rng("formats", "width_frac", 0, 24)
    for (sec, key), choices in ENUMS.items():
        if doc.get(sec, {}).get(key) not in choices:
            bad.append(f"{sec}.{key} not one of {', '.join(choices)}")
    p = doc.get("pipeline", {})
    if not bad and p["octaves"] % p["noise_units"]:
        bad.append("pipeline.noise_units must divide pipeline.octaves")
    if p.get("noise_steps") not in (1, 2, 4, 8):
        bad.append("pipeline.noise_steps must be 1, 2, 4 or 8")
    elif p.get("datapath") == "serial" and p["noise_steps"] < 4:
        bad.append("pipeline.datapath = serial needs pipeline.noise_steps >= 4")
    fm = doc.get("formats", {})
    for name, mx in FORMAT_MAX.items():
        f = fm.get(name, {})
        i, fr = f.get("int"), f.get("frac")
        if not isinstance(i, int) or not isinstance(fr, int) or not 1 <= i <= 62 or not 0 <= fr <= 62:
            bad.append(f"formats.{name} must have int in [1, 62] and frac in [0, 62]")
        elif i + fr > mx:
            bad.append(f"formats.{name}: int + frac = {i + fr} > {mx}")
    if not bad:
        acc = fm["matrix"]["frac"] + fm["coord"]["frac"]
        if acc < doc["noise"]["lattice_frac"]:
            bad.append(f"matrix.frac + coord.frac = {acc} < noise.lattice_frac (pst_octave_transform)")
        if acc < fm["offset"]["frac"]:
            bad.append(f"matrix.frac + coord.frac = {acc} < offset.frac (pst_octave_transform)")
        if p["log2_clut"] - 1 + fm["width_frac"] < 1:
            bad.append("log2_clut - 1 + width_frac must be >= 1 (pst_clut_filter)")
    return bad


def toml_text(doc: dict, header: str) -> str:
    """The profile back as TOML (tables of integers, strings and {int, frac} inline tables)."""
    def val(v):
        if isinstance(v, bool):
            return "true" if v else "false"
        if isinstance(v, int):
            return str(v)
        if isinstance(v, str):
            return json.dumps(v)
        if isinstance(v, dict):
            return "{ " + ", ".join(f"{k} = {val(x)}" for k, x in v.items()) + " }"
        raise ValueError(f"cannot write {v!r} to a profile")
    out = [f"# {line}" if line else "#" for line in header.splitlines()]
    for sec, table in doc.items():
        if not isinstance(table, dict):
            raise ValueError(f"a profile has only tables at the top level, not {sec!r}")
        out += ["", f"[{sec}]"] + [f"{k} = {val(v)}" for k, v in table.items()]
    return "\n".join(out) + "\n"


# ----------------------------------------------------------------------------------------------
# Small helpers

def atomic_write(path: pathlib.Path, text: str) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.{threading.get_ident()}.tmp")
    tmp.write_text(text)
    os.replace(tmp, path)


def write_if_changed(path: pathlib.Path, text: str) -> None:
    """Keeps the file (and its mtime: the synthesis cache compares it) when the text is the same."""
    if not path.exists() or path.read_text() != text:
        atomic_write(path, text)


def sha(text: str) -> str:
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def ident(s: str) -> str:
    s = re.sub(r"[^A-Za-z0-9_]", "_", s)
    return s if re.match(r"[A-Za-z_]", s) else "p_" + s


def tail(text: str, n: int = 25) -> str:
    return "\n".join((text or "").strip().splitlines()[-n:])


def fnum(v, digits=2, none="-"):
    return none if v is None else f"{v:.{digits}f}"


def cnt(v):
    return "-" if v is None else f"{v:,}"


def kge(v):
    return "-" if v is None else f"{v / 1000:.1f}k"


STOP = threading.Event()
_procs = set()
_procs_lock = threading.Lock()
_print_lock = threading.Lock()


def say(msg: str) -> None:
    with _print_lock:
        print(msg, flush=True)


def run(cmd, cwd=ROOT, timeout=None):
    """Runs a command in its own process group (so an interrupt can stop its children too)."""
    if STOP.is_set():
        raise KeyboardInterrupt
    p = subprocess.Popen([str(c) for c in cmd], cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                         text=True, start_new_session=True)
    with _procs_lock:
        _procs.add(p)
    try:
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


# ----------------------------------------------------------------------------------------------
# Points

class Point:
    def __init__(self, name, knob, value, profile_path, profile_text, scene_files, base_value=False):
        self.name = name
        self.knob = knob            # "base" for the base profile itself
        self.value = value
        self.profile = profile_path
        self.profile_sha = sha(profile_text)
        self.scene_files = scene_files   # scene name -> file rendered
        self.is_base = base_value


def synth_inputs() -> list:
    """What a gate count depends on besides the profile."""
    return [ROOT / "scripts" / "synth.py", ROOT / "scripts" / "synth" / "cells.lib", *sorted((ROOT / "rtl").glob("*.sv"))]


def synth_key(profile: pathlib.Path) -> dict:
    """Content keys of a synthesis: the profile's values (comments aside) and the RTL + synthesis
    script + cell library."""
    h = hashlib.sha256()
    for f in synth_inputs():
        h.update(f.name.encode() + b"\0" + f.read_bytes() + b"\0")
    values = json.dumps(tomllib.loads(profile.read_text()), sort_keys=True)
    return {"profile": hashlib.sha256(values.encode()).hexdigest()[:16], "rtl": h.hexdigest()[:16]}


def synth_cache_valid(synth_json: pathlib.Path, profile: pathlib.Path) -> bool:
    """out/synth/NAME.json stands for this profile: its sidecar NAME.sweep.json has the same
    content keys or, without a sidecar (a synthesis run by hand), it is newer than the profile
    and every synthesis input."""
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
            return json.loads(side.read_text()) == synth_key(profile)
        except (OSError, ValueError):
            return False
    t = synth_json.stat().st_mtime
    return not any(d.stat().st_mtime > t for d in [profile, *synth_inputs()])


def run_point(pt: Point, a, out: pathlib.Path) -> dict:
    """Renders the scenes and synthesizes the profile of one point (what is not done yet)."""
    res_path = out / "results" / f"{pt.name}.json"
    settings = {"size": a.size, "truth": a.truth}
    old = None
    if res_path.exists():
        try:
            old = json.loads(res_path.read_text())
        except ValueError:
            old = None
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
        s = json.loads(summary.read_text())
        res["scenes"][scene] = {k: s.get(k) for k in ("vs_reference", "vs_truth", "reference_vs_truth", "notes",
                                                      "fragments")}
        did.append("render")
    res["render_seconds"] = round(time.time() - t0, 1) if did else res.get("render_seconds")
    # 2. Synthesis (cached in out/synth/<name>.json).
    res["synth_note"] = None
    have = res.get("synth") and res["synth"].get("sha") == pt.profile_sha
    if not a.no_synth and pt.knob != "filter" and not have:
        sj = a.synth_dir / f"{pt.synth_name}.json"
        if synth_cache_valid(sj, pt.profile):
            res["synth_note"] = "synth cached"
        else:
            tmp = out / "tmp" / pt.name
            shutil.rmtree(tmp, ignore_errors=True)
            tmp.mkdir(parents=True)
            t1 = time.time()
            key = synth_key(pt.profile)       # before the run: an input edited meanwhile makes it stale
            rc, so, se = run([PY, ROOT / "scripts" / "synth.py", pt.profile, "--out", tmp, "--quiet"])
            secs = time.time() - t1
            made = tmp / f"{pt.synth_name}.json"
            if rc != 0 or not made.exists():
                res["status"] = "failed"
                res["error"] = f"scripts/synth.py exited {rc}:\n{tail(se or so)}"
                return res
            a.synth_dir.mkdir(parents=True, exist_ok=True)
            side = a.synth_dir / f"{pt.synth_name}.sweep.json"
            side.unlink(missing_ok=True)
            for ext in ("md", "json"):      # then the sidecar: it makes the json a valid cache
                if (tmp / f"{pt.synth_name}.{ext}").exists():
                    os.replace(tmp / f"{pt.synth_name}.{ext}", a.synth_dir / f"{pt.synth_name}.{ext}")
            atomic_write(side, json.dumps(key) + "\n")
            shutil.rmtree(tmp, ignore_errors=True)
            res["synth_note"] = f"synth {secs:.0f} s"
        res["synth"] = synth_record(pt, sj)
    elif have:
        res["synth_note"] = "synth cached"
    elif a.no_synth and pt.knob != "filter" and synth_cache_valid(a.synth_dir / f"{pt.synth_name}.json", pt.profile):
        res["synth"] = synth_record(pt, a.synth_dir / f"{pt.synth_name}.json")     # free: already synthesized
        res["synth_note"] = "synth cached"
    return res


def synth_record(pt, sj: pathlib.Path) -> dict:
    s = json.loads(sj.read_text())
    return {"sha": pt.profile_sha, "file": str(sj), "logic_ge": s["logic_ge"],
            "rom_bits": s.get("rom_bits"), "ram_bits": s.get("ram_bits"),
            "flip_flops": s.get("flip_flops"), "yosys_seconds": s.get("yosys_seconds"),
            "blocks": {b: v.get("logic_ge") for b, v in s.get("blocks", {}).items()}}


def summarize(res: dict, scenes=None) -> dict:
    """Means over the scenes (those named, default all) of one point's result."""
    def psnr(v):
        if not v:
            return None
        p = v.get("psnr")
        if p is None or (isinstance(p, float) and (math.isinf(p) or math.isnan(p))):
            return PSNR_CAP if v.get("rms") == 0 else None
        return min(p, PSNR_CAP)
    sc = [v for k, v in res.get("scenes", {}).items() if scenes is None or k in scenes]
    ref = [psnr(s.get("vs_reference")) for s in sc]
    tru = [psnr(s.get("vs_truth")) for s in sc]
    rvt = [psnr(s.get("reference_vs_truth")) for s in sc]
    mean = lambda xs: (sum(xs) / len(xs)) if xs and None not in xs else None
    return {"psnr_ref": mean(ref), "psnr_ref_min": min(ref) if ref and None not in ref else None,
            "psnr_truth": mean(tru), "ref_vs_truth": mean(rvt)}


def psnr_vs_base(out: pathlib.Path, name: str, base: str, scenes: list):
    """PSNR (RGB) of the point's golden images against the base profile's golden images, the
    worst scene: what the change alone does, whatever the base's own error against the reference."""
    import matplotlib.image as mpimg
    vals = []
    for s in scenes:
        pa = out / "renders" / name / s / "golden.png"
        pb = out / "renders" / base / s / "golden.png"
        if not (pa.exists() and pb.exists()):
            return None
        a, b = mpimg.imread(str(pa)), mpimg.imread(str(pb))
        if a.shape != b.shape:
            return None
        mse = float(((a[..., :3].astype("float64") - b[..., :3]) ** 2).mean())
        vals.append(PSNR_CAP if mse == 0 else min(PSNR_CAP, -10 * math.log10(mse)))
    return min(vals) if vals else None


# ----------------------------------------------------------------------------------------------
# RTL subset

def rtl_check(a, out: pathlib.Path, base_name: str, chosen: list, rows: dict) -> dict:
    """Verilates the chosen points into build-sweep/ and runs pst regress on each."""
    results = {}
    rdir = out / "rtl"
    todo = []
    for name in chosen:
        cache = rdir / f"{name}.result.json"
        if cache.exists():
            c = json.loads(cache.read_text())
            if c.get("profile_sha") == rows[name]["profile_sha"]:
                results[name] = c
                say(f"[rtl] {name}: {c['summary']} (cached)")
                continue
        todo.append(name)
    if not todo:
        return results
    pdir = out / "rtl_points"
    pdir.mkdir(parents=True, exist_ok=True)
    for f in pdir.glob("*.toml"):
        if f.stem not in chosen:
            f.unlink()
    for name in chosen:
        text = pathlib.Path(rows[name]["profile"]).read_text()
        write_if_changed(pdir / f"{name}.toml", text)
    bdir = ROOT / "build-sweep"
    profiles = base_name if (ROOT / "rtl" / "configs" / f"{base_name}.toml").exists() else "reduced"
    t0 = time.time()
    say(f"[rtl] building {bdir.name} with {', '.join(chosen)} (verilating: minutes)")
    steps = [["cmake", "-S", ROOT, "-B", bdir, "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
              f"-DPST_PROFILES={profiles}", f"-DPST_EXTRA_PROFILE_DIR={pdir.resolve()}"],
             ["cmake", "--build", bdir, "--target", "pst", f"-j{a.jobs}"]]
    for cmd in steps:
        rc, so, se = run(cmd)
        if rc != 0:
            err = f"{' '.join(map(str, cmd[:3]))} exited {rc}:\n{tail(se + so)}"
            for name in todo:
                results[name] = {"passed": False, "summary": "build failed", "error": err}
            say(f"[rtl] build failed:\n{err}")
            return results
    say(f"[rtl] built in {time.time() - t0:.0f} s")
    rdir.mkdir(parents=True, exist_ok=True)
    for name in todo:
        t1 = time.time()
        jpath = rdir / f"{name}.regress.json"
        # The profile FILE (its stem names the verilated model): `--profile NAME` alone would look
        # for rtl/configs/NAME.toml for the golden side.
        rc, so, se = run([bdir / "pst", "regress", "--profile", pdir / f"{name}.toml", "--size", RTL_SIZE,
                          "-o", jpath])
        runs = []
        if jpath.exists():
            try:
                runs = json.loads(jpath.read_text())
            except ValueError:
                runs = []
        mism = sum(r.get("mismatches", 0) for r in runs)
        pixels = sum(r.get("pixels_checked", 0) for r in runs)
        passed = rc == 0 and runs and all(r.get("passed") for r in runs)
        summary = (f"pass: {len(runs)} scenes, {pixels} px, 0 mismatches" if passed else
                   f"FAIL: {mism} mismatches in {sum(not r.get('passed') for r in runs)}/{len(runs)} scenes"
                   if runs else f"FAIL: regress exited {rc}")
        r = {"name": name, "profile_sha": rows[name]["profile_sha"], "passed": bool(passed), "runs": len(runs),
             "pixels": pixels, "mismatches": mism, "summary": summary, "seconds": round(time.time() - t1, 1)}
        if not passed:
            r["error"] = tail(so + "\n" + se)
        else:
            atomic_write(rdir / f"{name}.result.json", json.dumps(r, indent=2) + "\n")
        results[name] = r
        say(f"[rtl] {name}: {summary} ({r['seconds']:.0f} s)")
    return results


# ----------------------------------------------------------------------------------------------
# Reports

def cheapest_within(rows: list, base: dict, knob: str, db: float = 1.0):
    """The cheapest setting of one knob (the base value included) whose mean PSNR vs reference
    is within `db` of the base's; cheapest = lowest logic GE, then ROM bits. None if no GE."""
    cands = [r for r in rows if r["knob"] == knob and r["status"] == "ok" and r["psnr_ref"] is not None]
    cands.append(dict(base, value=base["base_value"].get(knob)))
    ok = [r for r in cands if r["psnr_ref"] is not None and base["psnr_ref"] is not None
          and r["psnr_ref"] >= base["psnr_ref"] - db]
    if any(r["logic_ge"] is None for r in ok) or not ok:
        return None, ok
    return min(ok, key=lambda r: (r["logic_ge"], r["rom_bits"] or 0, r["ram_bits"] or 0)), ok


def plot_all(out: pathlib.Path, rows: list, base: dict, knobs: list, title: str) -> list:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    made = []
    colours = list(plt.get_cmap("tab10").colors) + ["#000000", "#a0522d", "#4b0082", "#808000"]
    markers = ["o", "s", "^", "v", "D", "P", "X", "<", ">", "h", "p", "*", "8"]
    for which, label in (("psnr_ref", "reference"), ("psnr_truth", "truth")):
        fig, ax = plt.subplots(figsize=(10, 6), dpi=110)
        missing = 0
        for i, k in enumerate(knobs):
            pts = [r for r in rows if r["knob"] == k and r["status"] == "ok"]
            good = [r for r in pts if r["logic_ge"] is not None and r[which] is not None]
            missing += len(pts) - len(good)
            if not good:
                continue
            xs = [r["logic_ge"] / 1000 for r in good]
            ys = [r[which] for r in good]
            ax.scatter(xs, ys, s=42, marker=markers[i % len(markers)], color=colours[i % len(colours)],
                       label=k, zorder=3, edgecolors="black", linewidths=0.4)
            for r, x, y in zip(good, xs, ys):
                ax.annotate(str(r["value"]), (x, y), textcoords="offset points", xytext=(4, 3), fontsize=7,
                            color="#333333")
        if base["logic_ge"] is not None and base[which] is not None:
            ax.scatter([base["logic_ge"] / 1000], [base[which]], s=260, marker="*", color="gold",
                       edgecolors="black", linewidths=1.0, zorder=4, label=f"base ({base['name']})")
            ax.axhline(base[which], color="gray", lw=0.8, ls=":", zorder=1)
            ax.axhline(base[which] - 1, color="gray", lw=0.6, ls="--", zorder=1)
            ax.annotate("base - 1 dB", (ax.get_xlim()[0], base[which] - 1), textcoords="offset points",
                        xytext=(4, -10), fontsize=7, color="gray")
        xs_all = [r["logic_ge"] for r in rows if r["logic_ge"]] + ([base["logic_ge"]] if base["logic_ge"] else [])
        if xs_all and max(xs_all) / min(xs_all) > 4:
            ax.set_xscale("log")
        ax.set_xlabel("logic (k gate equivalents, NAND2; ROM/RAM not included)")
        ax.set_ylabel(f"mean PSNR vs {label} (dB)")
        note = f"  ({missing} points without synthesis not shown)" if missing else ""
        ax.set_title(f"{title}: gates against PSNR vs {label}{note}", fontsize=10)
        ax.grid(True, which="both", alpha=0.3)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0)
        fig.tight_layout()
        path = out / f"ge_vs_psnr_{label}.png"
        fig.savefig(path)
        plt.close(fig)
        made.append(path)

    kdir = out / "knobs"
    kdir.mkdir(exist_ok=True)
    for k in knobs:
        pts = [r for r in rows if r["knob"] == k and r["status"] == "ok"]
        bv = base["base_value"].get(k)
        allp = pts + ([dict(base, value=bv)] if bv is not None else [])
        if not allp:
            continue
        numeric = all(isinstance(r["value"], int) for r in allp)
        if numeric:
            allp.sort(key=lambda r: r["value"])
            xs = [r["value"] for r in allp]
        else:
            order = KNOBS[k][1]
            allp.sort(key=lambda r: order.index(r["value"]) if r["value"] in order else 99)
            xs = list(range(len(allp)))
        fig, ax = plt.subplots(figsize=(5.2, 3.4), dpi=110)
        nan = lambda v: float("nan") if v is None else v
        ax.plot(xs, [nan(r["psnr_ref"]) for r in allp], "o-", color="tab:blue", label="PSNR vs reference")
        ax.plot(xs, [nan(r["psnr_truth"]) for r in allp], "s--", color="tab:green", label="PSNR vs truth")
        for r, x in zip(allp, xs):
            if r["value"] == bv:
                ax.axvline(x, color="gold", lw=6, alpha=0.35, zorder=0)
        ax.set_xlabel(f"{k}" + (" (bits)" if numeric and k not in ("octaves",) else ""))
        ax.set_ylabel("mean PSNR (dB)")
        ys = [v for r in allp for v in (r["psnr_ref"], r["psnr_truth"]) if v is not None]
        if ys and max(ys) - min(ys) < 3:          # a flat line stays flat: at least a 3 dB span
            mid = (max(ys) + min(ys)) / 2
            ax.set_ylim(mid - 1.75, mid + 1.75)
        if not numeric:
            ax.set_xticks(xs)
            ax.set_xticklabels([str(r["value"]) for r in allp], fontsize=8)
        ax.grid(True, alpha=0.3)
        ges = [r["logic_ge"] for r in allp]
        lines, labels = ax.get_legend_handles_labels()
        if any(g is not None for g in ges):
            ax2 = ax.twinx()
            gx = [x for x, g in zip(xs, ges) if g is not None]
            gy = [g / 1000 for g in ges if g is not None]
            ax2.plot(gx, gy, "^:", color="tab:red", label="logic GE")
            lo, hi = min(gy), max(gy)
            pad = max(0.05 * hi - (hi - lo), 0) / 2      # at least 5 % of the value: no magnified noise
            ax2.set_ylim(lo - pad - 0.05 * (hi - lo), hi + pad + 0.05 * (hi - lo))
            roms = [r["rom_bits"] for r in allp if r["logic_ge"] is not None]
            if len(set(roms)) > 1:
                for x, g, rb in zip(gx, gy, roms):
                    ax2.annotate(f"ROM {rb / 1000:.1f}k bits", (x, g), textcoords="offset points", xytext=(0, 6),
                                 fontsize=7, color="tab:red", ha="center")
            ax2.set_ylabel("logic (k GE)", color="tab:red")
            ax2.tick_params(axis="y", colors="tab:red")
            l2, lb2 = ax2.get_legend_handles_labels()
            lines, labels = lines + l2, labels + lb2
        ax.legend(lines, labels, fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.2), ncol=3,
                  frameon=False)
        ax.set_title(f"{title}: {k} (base = {bv}, shaded)", fontsize=9)
        path = kdir / f"{k}.png"
        fig.savefig(path, bbox_inches="tight")
        plt.close(fig)
        made.append(path)
    return made


def write_reports(a, out, base, rows, knobs, skipped, rtl, title, elapsed):
    scenes = a.scene_names
    # CSV: one row per point (the base first), per-scene PSNRs at the end.
    buf = io.StringIO()
    w = csv.writer(buf)
    head = ["point", "knob", "value", "status", "logic_ge", "rom_bits", "ram_bits", "flip_flops",
            "psnr_ref_mean", "psnr_ref_min", "psnr_truth_mean", "delta_psnr_ref", "delta_psnr_truth",
            "psnr_vs_base_min", "rtl_check"]
    head += [f"psnr_ref_{s}" for s in scenes] + [f"psnr_truth_{s}" for s in scenes]
    w.writerow(head)
    allrows = [base] + rows

    def delta(r, k):
        return None if r[k] is None or base[k] is None else r[k] - base[k]
    for r in allrows:
        sc = r.get("scenes", {})
        w.writerow([r["name"], r["knob"], r["value"], r["status"], r["logic_ge"], r["rom_bits"], r["ram_bits"],
                    r["flip_flops"], fnum(r["psnr_ref"], 3, ""), fnum(r["psnr_ref_min"], 3, ""),
                    fnum(r["psnr_truth"], 3, ""), fnum(delta(r, "psnr_ref"), 3, ""),
                    fnum(delta(r, "psnr_truth"), 3, ""), fnum(r.get("psnr_base"), 3, ""),
                    rtl.get(r["name"], {}).get("summary", "")]
                   + [fnum((sc.get(s, {}).get("vs_reference") or {}).get("psnr"), 3, "") for s in scenes]
                   + [fnum((sc.get(s, {}).get("vs_truth") or {}).get("psnr"), 3, "") for s in scenes])
    atomic_write(out / "sweep.csv", buf.getvalue())

    md = [f"# Precision sweep: base `{base['name']}`", "",
          f"One knob at a time around `{os.path.relpath(base['profile'], ROOT)}`. Golden-model renders of "
          f"{', '.join(scenes)} at {a.size} x {a.size}"
          + (f", ground truth {a.truth} x {a.truth} jittered samples per pixel" if a.truth else "")
          + ". PSNR over RGB in dB (means over the scenes; `min` = the worst scene). Logic in NAND2 gate "
          "equivalents (scripts/synth.py, Yosys; ROM/RAM bits outside the logic). "
          f"This invocation: {elapsed:.0f} s (points with a result are not recomputed); summed over the "
          f"points: renders {sum(r.get('render_seconds') or 0 for r in allrows):.0f} s, Yosys "
          f"{sum(r.get('yosys_seconds') or 0 for r in allrows if r['knob'] != 'filter'):.0f} s.", "",
          ("References: scene copies whose textures ask for each point's own noise variant and |grad| norm "
           "(--match-variant), so PSNR vs reference measures the fixed-point precision alone; for the "
           "interp / hash / corner / norm knobs it then says how exact that variant's hardware is, not how "
           "close the variant is to the scenes' texture." if a.match_variant else
           "References: the scenes' own textures (the noise variant and norm they ask for, Rayshade's by "
           "default): a profile with another variant is measured against that texture too."), "",
          f"Base: {cnt(base['logic_ge'])} GE, ROM {cnt(base['rom_bits'])} bits, RAM {cnt(base['ram_bits'])} bits, "
          f"PSNR vs reference {fnum(base['psnr_ref'])} dB (min {fnum(base['psnr_ref_min'])}), vs truth "
          f"{fnum(base['psnr_truth'])} dB. The double reference itself scores {fnum(base['ref_vs_truth'])} dB "
          "vs truth (the ceiling of the truth column).", "",
          "Columns: PSNR of the golden image against the double reference (`ref`, mean and worst scene) and "
          "against the supersampled ground truth (`truth`); Δ = change from the base; `vs base` = PSNR of "
          "the point's golden images against the base profile's, worst scene (what the change alone does, "
          "whatever the base's own error; `same` = bit-identical images).", "",
          "| knob | value | point | logic GE | ROM bits | RAM bits | PSNR ref mean | PSNR ref min | "
          "PSNR truth mean | Δ ref | Δ truth | vs base | RTL check |",
          "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|"]

    def vsb(r):
        v = r.get("psnr_base")
        return "" if r is base else "same" if v is not None and v >= PSNR_CAP else fnum(v, 1)

    def cell(v, fmt="{:,}"):
        return "-" if v is None else fmt.format(v)
    for r in allrows:
        dr, dt = delta(r, "psnr_ref"), delta(r, "psnr_truth")
        rc = rtl.get(r["name"], {}).get("summary", "")
        if r["status"] != "ok":
            md.append(f"| {r['knob']} | {r['value']} | {r['name']} | **failed** | | | | | | | | | {rc} |")
            continue
        ge = cell(r["logic_ge"]) + (" (=base)" if r["knob"] == "filter" and r["logic_ge"] is not None else "")
        md.append(f"| {r['knob']} | {r['value']} | {r['name']} | {ge} | {cell(r['rom_bits'])} | "
                  f"{cell(r['ram_bits'])} | {fnum(r['psnr_ref'])} | {fnum(r['psnr_ref_min'])} | "
                  f"{fnum(r['psnr_truth'])} | {'' if r is base else fnum(dr, 2)} | "
                  f"{'' if r is base else fnum(dt, 2)} | {vsb(r)} | {rc} |")
    md += ["", "## Cheapest setting within 1 dB of the base", "",
           "Per knob, among its values (the base's included) with mean PSNR vs reference >= the base's - 1 dB: "
           "the lowest logic GE, ties broken by ROM bits.", ""]
    lines = []
    for k in knobs if base["status"] == "ok" else []:
        if k == "filter":
            ok = [r for r in rows if r["knob"] == k and r["status"] == "ok" and r["psnr_truth"] is not None]
            if base["base_value"].get(k) and base["psnr_truth"] is not None:
                ok.append(dict(base, value=base["base_value"][k]))
            if ok:
                best = max(ok, key=lambda r: r["psnr_truth"])
                lines.append(f"- **filter**: no cost difference (the hardware holds every filter kind; GE = base). "
                             f"Best vs truth: `{best['value']}` ({fnum(best['psnr_truth'])} dB).")
            continue
        best, ok = cheapest_within(rows, base, k)
        if best is None and ok:
            lines.append(f"- **{k}**: values within 1 dB: {', '.join(str(r['value']) for r in ok)} "
                         "(no gate counts: run without --no-synth to rank them)")
        elif best is None:
            lines.append(f"- **{k}**: no value within 1 dB")
        else:
            dge = best["logic_ge"] - base["logic_ge"]
            drom = (best["rom_bits"] or 0) - (base["rom_bits"] or 0)
            lines.append(f"- **{k}**: `{best['value']}`"
                         + (" (the base value)" if best["value"] == base["base_value"].get(k) else
                            f" ({best['name']}): {best['logic_ge']:,} GE ({dge:+,} vs base)"
                            + (f", ROM {drom:+,} bits" if drom else "")
                            + f", PSNR vs reference {fnum(best['psnr_ref'])} dB "
                            f"(Δ {fnum(best['psnr_ref'] - base['psnr_ref'])}), vs truth {fnum(best['psnr_truth'])} dB "
                            f"(Δ {fnum(best['psnr_truth'] - base['psnr_truth'])}), images vs base "
                            + ("identical" if (best.get("psnr_base") or 0) >= PSNR_CAP else
                               f"{fnum(best.get('psnr_base'), 1)} dB (worst scene)")))
    md += lines or ["- (the base profile failed: nothing to compare with)"]
    failed = [r for r in allrows if r["status"] != "ok"]
    rtl_failed = [n for n, v in rtl.items() if not v.get("passed")]
    if failed or rtl_failed:
        md += ["", "## Failures", ""]
        for r in failed:
            md += [f"- `{r['name']}`:", "", "```", r.get("error", "").strip(), "```", ""]
        for n in rtl_failed:
            md += [f"- RTL check `{n}`: {rtl[n]['summary']}", "", "```", rtl[n].get("error", "").strip(), "```", ""]
    if skipped:
        md += ["", "## Skipped values", ""] + [f"- {k} = {v}: {why}" for k, v, why in skipped]
    notes = sorted({n for r in allrows for s in r.get("scenes", {}).values() for n in (s.get("notes") or [])})
    if notes:
        md += ["", "## Driver notes", "", "What the hardware did differently from the scenes' requests "
               "(octaves dropped, noise variant, ...):", ""] + [f"- {n}" for n in notes[:30]]
    md += ["", "## Plots", "", "- [GE vs PSNR vs reference](ge_vs_psnr_reference.png)",
           "- [GE vs PSNR vs truth](ge_vs_psnr_truth.png)"]
    md += [f"- [{k}](knobs/{k}.png)" for k in knobs if (out / "knobs" / f"{k}.png").exists()]
    atomic_write(out / "sweep.md", "\n".join(md) + "\n")
    return lines


# ----------------------------------------------------------------------------------------------

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
        a.base_doc = tomllib.loads(a.base_path.read_text())
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as e:
        ap.error(f"--base: {a.base_path}: {e}")
    problems = validate(a.base_doc)
    if problems:
        ap.error(f"--base: {a.base_path}: {'; '.join(problems)}")
    a.base_name = ident(a.base_path.stem)

    a.knob_list = [k.strip() for k in a.knobs.split(",") if k.strip()]
    unknown = [k for k in a.knob_list if k not in KNOBS]
    if unknown or not a.knob_list:
        ap.error(f"--knobs: unknown knob(s) {', '.join(unknown) or '(none given)'}; known: {', '.join(KNOBS)}")
    a.value_lists = {k: list(KNOBS[k][1]) for k in a.knob_list}
    for spec in a.values:
        m = re.fullmatch(r"(\w+)=([\w,]+)", spec.strip())
        if not m or m.group(1) not in KNOBS:
            ap.error(f"--values: expected KNOB=V1,V2,... with a known knob, got {spec!r}")
        k = m.group(1)
        vals = []
        for v in m.group(2).split(","):
            if isinstance(KNOBS[k][1][0], int):
                if not v.isdigit():
                    ap.error(f"--values: {k} takes integers, got {v!r}")
                vals.append(int(v))
            else:
                if v not in KNOBS[k][1]:
                    ap.error(f"--values: {k} takes {', '.join(KNOBS[k][1])}, got {v!r}")
                vals.append(v)
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


def set_texture_keys(text: str, keys: dict) -> str:
    """The scene with keys (name -> TOML value text) set in every [textures.NAME] table:
    replaced where the line exists, added under the table header where it does not."""
    doc = tomllib.loads(text)
    out = []
    section = None
    for line in text.splitlines():
        m = re.match(r"\s*\[(textures\.[A-Za-z0-9_\-]+)\]\s*(#.*)?$", line)
        if m:
            section = m.group(1).split(".", 1)[1]
            out.append(line)
            out += [f"{k} = {v}" for k, v in keys.items() if k not in doc["textures"][section]]
            continue
        if re.match(r"\s*\[", line):
            section = None
        km = re.match(r"\s*([A-Za-z_]+)\s*=", line)
        if section and km and km.group(1) in keys:
            out.append(f"{km.group(1)} = {keys[km.group(1)]}")      # a one-line value (checked below)
            continue
        out.append(line)
    new = "\n".join(out) + "\n"
    check = tomllib.loads(new)
    want = tomllib.loads("\n".join(f"{k} = {v}" for k, v in keys.items()))
    if any(t.get(k) != v for t in check.get("textures", {}).values() for k, v in want.items()):
        raise ValueError(f"could not set {', '.join(keys)} in every texture")
    return new


def variant_keys(doc: dict) -> dict:
    """The texture keys that make the reference use a profile's noise variant and |grad| norm."""
    n = doc["noise"]
    return {"noise": f'{{ interp = "{n["interp"]}", corner = "{n["corner"]}", hash = "{n["hash"]}" }}',
            "norm": f'"{doc["filter"]["norm"]}"'}


def point_scenes(a, pdir: pathlib.Path, name: str, keys: dict):
    """Scene copies with texture keys set (points/<name>/<scene>.toml), or the scenes themselves."""
    if not keys:
        return dict(a.scene_files), ""
    files, texts = {}, []
    for s, f in a.scene_files.items():
        text = set_texture_keys(f.read_text(), keys)
        p = pdir / name / f"{s}.toml"
        write_if_changed(p, text)
        files[s] = p
        texts.append(text)
    return files, "".join(texts)


def make_points(a, out: pathlib.Path):
    points, skipped = [], []
    pdir = out / "points"
    base_text = a.base_path.read_text()
    base_keys = variant_keys(a.base_doc) if a.match_variant else {}
    try:
        files, extra = point_scenes(a, pdir, a.base_name, base_keys)
    except (ValueError, KeyError, tomllib.TOMLDecodeError) as e:
        raise SystemExit(f"error: --match-variant: {e}")
    base = Point(a.base_name, "base", "-", a.base_path, base_text + extra, files, True)
    base.synth_name = a.base_name
    base_values = {k: KNOBS[k][3](a.base_doc) for k in KNOBS}
    kinds = {t.get("filter", "sat") for f in a.scene_files.values()
             for t in tomllib.loads(f.read_text()).get("textures", {}).values()}
    base_values["filter"] = kinds.pop() if len(kinds) == 1 else None
    for k in a.knob_list:
        desc, _, apply, _ = KNOBS[k]
        for v in a.value_lists[k]:
            name = ident(f"{a.base_name}_{k}_{v}")
            if v == base_values[k]:
                continue
            if k == "filter":
                doc, path, text, synth_name = a.base_doc, a.base_path, base_text, a.base_name
                keys = dict(base_keys, filter=f'"{v}"')
            else:
                doc = copy.deepcopy(a.base_doc)
                apply(doc, v)
                bad = validate(doc)
                if bad:
                    skipped.append((k, v, "; ".join(bad)))
                    continue
                change = f"{k} = {v} ({desc})"
                if k == "octaves":
                    change += f"; noise_units = {doc['pipeline']['noise_units']}"
                text = toml_text(doc, f"Sweep point {name}: profile {a.base_name} ({a.base_path.name}) with\n"
                                      f"{change}.\nWritten by scripts/sweep.py; see {a.base_path.name} for the keys.")
                path = pdir / f"{name}.toml"
                write_if_changed(path, text)
                synth_name = name
                keys = variant_keys(doc) if a.match_variant else {}
            try:
                files, extra = point_scenes(a, pdir, name, keys)
            except (ValueError, KeyError, tomllib.TOMLDecodeError) as e:
                skipped.append((k, v, f"scene copies: {e}"))
                continue
            pt = Point(name, k, v, path, text + extra, files)
            pt.synth_name = synth_name
            points.append(pt)
    return base, points, skipped, base_values


def row_of(res: dict, scenes: list, base_res: dict = None) -> dict:
    s = summarize(res, scenes)
    if res.get("status") != "ok":
        s = {k: None for k in s}
    syn = res.get("synth") or ((base_res or {}).get("synth") if res.get("knob") == "filter" else None)
    return {"name": res["name"], "knob": res["knob"], "value": res["value"], "status": res.get("status", "failed"),
            "error": res.get("error"), "profile": res.get("profile"), "profile_sha": res.get("profile_sha"),
            "scenes": {k: v for k, v in res.get("scenes", {}).items() if k in scenes},
            "logic_ge": syn and syn.get("logic_ge"), "rom_bits": syn and syn.get("rom_bits"),
            "ram_bits": syn and syn.get("ram_bits"), "flip_flops": syn and syn.get("flip_flops"),
            "yosys_seconds": syn and syn.get("yosys_seconds"), "render_seconds": res.get("render_seconds"), **s}


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

    results = {}
    n = len(todo)
    done = [0]

    def cached(pt):
        p = out / "results" / f"{pt.name}.json"
        if not p.exists():
            return None
        try:
            r = json.loads(p.read_text())
        except ValueError:
            return None
        if r.get("profile_sha") != pt.profile_sha or r.get("settings") != {"size": a.size, "truth": a.truth}:
            return None
        if set(a.scene_files) - set(r.get("scenes", {})):
            return None
        if r.get("status") != "ok":
            return None if a.retry_failed else r
        has_synth = r.get("synth") and r["synth"].get("sha") == pt.profile_sha
        if pt.knob != "filter" and not has_synth and (
                not a.no_synth or synth_cache_valid(a.synth_dir / f"{pt.synth_name}.json", pt.profile)):
            return None     # synthesis to run, or a cached one to pick up
        return r

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
        atomic_write(out / "results" / f"{pt.name}.json", json.dumps(r, indent=2) + "\n")
        return r

    interrupted = False
    def on_term(*_):
        raise KeyboardInterrupt
    prev = signal.signal(signal.SIGTERM, on_term)
    pool = concurrent.futures.ThreadPoolExecutor(max_workers=a.jobs)
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
            except Exception as e:     # a bug or an unreadable output: record it, keep going
                r = {"name": pt.name, "knob": pt.knob, "value": pt.value, "status": "failed",
                     "profile": str(pt.profile), "profile_sha": pt.profile_sha,
                     "settings": {"size": a.size, "truth": a.truth}, "scenes": {},
                     "error": f"{type(e).__name__}: {e}"}
                atomic_write(out / "results" / f"{pt.name}.json", json.dumps(r, indent=2) + "\n")
            results[pt.name] = r
            report(pt, r, "run")
    except KeyboardInterrupt:
        interrupted = True
        stop_children()
        pool.shutdown(wait=True, cancel_futures=True)
        shutil.rmtree(out / "tmp", ignore_errors=True)
        say("interrupted: finished points are kept in results/; rerun the same command to resume")
        return 130
    finally:
        if not interrupted:
            pool.shutdown(wait=True)
        signal.signal(signal.SIGTERM, prev)
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
    byname = {r["name"]: r for r in rows}

    # RTL subset: the cheapest point within 1 dB of N different knobs (else any passing point).
    rtl = {}
    if a.rtl_subset > 0:
        inf = float("inf")
        cost = lambda r: (r["logic_ge"] if r["logic_ge"] is not None else inf, r["rom_bits"] or 0)
        per_knob = []                  # each knob's cheapest point within 1 dB (not the base)
        for k in a.knob_list:
            if k == "filter":
                continue
            _, ok = cheapest_within(rows, base_row, k)
            ok = sorted((r for r in ok if r["name"] != base.name), key=cost)
            if ok:
                per_knob.append(ok[0])
        chosen = [r["name"] for r in sorted(per_knob, key=cost)[:a.rtl_subset]]   # the biggest savings
        for k in a.knob_list:      # not enough within 1 dB: take any rendered point of another knob
            if len(chosen) >= a.rtl_subset or k == "filter":
                continue
            if any(byname[c]["knob"] == k for c in chosen):
                continue
            cand = [r for r in rows if r["knob"] == k and r["status"] == "ok"]
            if cand:
                chosen.append(cand[0]["name"])
        if chosen:
            try:
                rtl = rtl_check(a, out, base.name, chosen, byname)
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
