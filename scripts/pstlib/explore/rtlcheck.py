"""The RTL check of a few points: verilated into one build directory (-DPST_EXTRA_PROFILE_DIR),
`pst regress` (the paper's scenes, RTL against the golden model bit for bit) on each. A point's
check is stored in OUT/rtl/NAME.json and reused while its profile and image size are the same
and it passed."""
import json
import pathlib
import time

from .. import atomic
from ..fmt import tail
from ..paths import ROOT
from ..backends.local import run, say
from ..pstjson import regress_runs
from .store import read_json


def regress_summary(runs: list, rc: int) -> dict:
    """Pass or fail of one `pst regress -o FILE` (its list of runs) and its exit status."""
    mism = sum(r.get("mismatches", 0) for r in runs)
    pixels = sum(r.get("pixels_checked", 0) for r in runs)
    passed = bool(rc == 0 and runs and all(r.get("passed") for r in runs))
    summary = (f"pass: {len(runs)} scenes, {pixels} px, 0 mismatches" if passed else
               f"FAIL: {mism} mismatches in {sum(not r.get('passed') for r in runs)}/{len(runs)} scenes"
               if runs else f"FAIL: regress exited {rc}")
    return {"passed": passed, "runs": len(runs), "pixels": pixels, "mismatches": mism, "summary": summary}


def rtl_check(out: pathlib.Path, points: dict, size: int, build_dir: pathlib.Path, jobs: int = 2,
              profiles: str = "reduced") -> dict:
    """POINTS: name -> (profile file, profile_sha). Verilates them into BUILD_DIR (with the named
    PROFILES, no test profiles) and runs `pst regress --size SIZE` on each: name -> result."""
    results, todo = {}, []
    rdir = out / "rtl"
    for name, (_, sha) in points.items():
        c = read_json(rdir / f"{name}.json")
        if c and c.get("profile_sha") == sha and c.get("size") == size and c.get("passed"):
            results[name] = c
            say(f"[rtl] {name}: {c['summary']} (cached)")
        else:
            todo.append(name)
    if not todo:
        return results
    pdir = out / "rtl_points"
    pdir.mkdir(parents=True, exist_ok=True)
    for f in pdir.glob("*.toml"):
        if f.stem not in points:
            f.unlink()
    for name, (profile, _) in points.items():
        atomic.write_if_changed(pdir / f"{name}.toml", pathlib.Path(profile).read_text())
    t0 = time.time()
    say(f"[rtl] verilating {', '.join(points)} into {build_dir.name}/ (minutes each)")
    for cmd in (["cmake", "-S", ROOT, "-B", build_dir, "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
                 f"-DPST_PROFILES={profiles}", "-DPST_TEST_PROFILES=none", f"-DPST_EXTRA_PROFILE_DIR={pdir.resolve()}"],
                ["cmake", "--build", build_dir, "--target", "pst", f"-j{jobs}"]):
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
        rc, so, se = run([build_dir / "pst", "regress", "--profile", pdir / f"{name}.toml", "--size", size, "-o", jpath])
        runs = regress_runs(read_json(jpath)) or []
        r = {"name": name, "profile_sha": points[name][1], "size": size, **regress_summary(runs, rc),
             "seconds": round(time.time() - t1, 1)}
        if not r["passed"]:
            r["error"] = tail(so + "\n" + se)
        atomic.write_text(rdir / f"{name}.json", json.dumps(r, indent=2) + "\n")
        results[name] = r
        say(f"[rtl] {name}: {r['summary']} ({r['seconds']:.0f} s)")
    return results
