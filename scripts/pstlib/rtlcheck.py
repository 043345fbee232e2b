"""The RTL check of a few sweep points: verilated into build-sweep/, `pst regress` on each."""
import json
import pathlib
import time

from . import atomic
from .fmt import tail
from .paths import ROOT
from .runner import run, say

RTL_SIZE = 64


def regress_summary(runs: list, rc: int) -> dict:
    """Pass or fail of one `pst regress -o FILE` (its list of runs) and its exit status."""
    mism = sum(r.get("mismatches", 0) for r in runs)
    pixels = sum(r.get("pixels_checked", 0) for r in runs)
    passed = bool(rc == 0 and runs and all(r.get("passed") for r in runs))
    summary = (f"pass: {len(runs)} scenes, {pixels} px, 0 mismatches" if passed else
               f"FAIL: {mism} mismatches in {sum(not r.get('passed') for r in runs)}/{len(runs)} scenes"
               if runs else f"FAIL: regress exited {rc}")
    return {"passed": passed, "runs": len(runs), "pixels": pixels, "mismatches": mism, "summary": summary}


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
        atomic.write_if_changed(pdir / f"{name}.toml", pathlib.Path(rows[name]["profile"]).read_text())
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
        r = {"name": name, "profile_sha": rows[name]["profile_sha"], **regress_summary(runs, rc),
             "seconds": round(time.time() - t1, 1)}
        if not r["passed"]:
            r["error"] = tail(so + "\n" + se)
        else:
            atomic.write_text(rdir / f"{name}.result.json", json.dumps(r, indent=2) + "\n")
        results[name] = r
        say(f"[rtl] {name}: {r['summary']} ({r['seconds']:.0f} s)")
    return results
