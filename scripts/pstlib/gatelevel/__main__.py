"""Gate-level simulation of a profile's synthesized netlist against the golden model.

    scripts/gatelevel.py PROFILE [--work DIR] [--out DIR] [--size N] [--random N] [--seed S]
                         [--gap-rate R] [--stall-rate R] [--mutate MODULE] [--jobs N]
                         [--simulator verilator|iverilog] [--scene FILE|all ...]

Two simulators, both run by ctest (label gatelevel): --simulator verilator (compiled, fast enough
for every scene and 10^5 random fragments) and --simulator iverilog (event-driven, the default
here: a second opinion on the RTL's own port trace, about 80 times slower).

The netlist is the profile's synthesis (scripts/synth.py --keep, the one the silicon figures
count), made in OUT/synth/ unless --work names a kept synthesis folder. It is verilated with
qflow-tech-osu018's cell models (UDPs as modules) and behavioural memories in place of the
memory stand-ins into a build of `pst` of its own (OUT/build), as profile NAME_gl, and run
through `pst regress`: every scene (scenes/*.toml at --size) and --random fragments (random
textures), each with input gaps and output stalls. --mutate MODULE adds a mutant model (the
first two-input cell of MODULE, or of the smallest module of that base name, swapped for its
dual); its random regression must fail. Writes OUT/NAME.json and OUT/NAME.md (default OUT:
out/gatelevel). Method: scripts/pstlib/gatelevel/.

--simulator iverilog (the default; pstlib/gatelevel/replay.py): Icarus Verilog runs the netlist
on the RTL's own port trace of each --scene (default scenes/marble.toml; `--scene all`: every
scene of scenes/, those the profile refuses listed as refused) at --size (default 16 here), the
RTL run with --gap-rate input gaps and --stall-rate output stalls (default 0 here), and compares
every output with the RTL's, half clock by half clock; --jobs replays at a time; the mutant runs
on the first scene the profile renders. The RTL model is the main build's (build/pst). --simulator verilator: the verilated netlist through `pst regress` as above
(its -fno-const-bit-op-tree must follow -O3: rtl/CMakeLists.txt, docs/VERIFICATION.md).

Exit 0 when the netlist matches the golden model bit for bit on every run (and the mutant, if
any, does not), 1 otherwise, 2 on bad input.
"""
import argparse
import concurrent.futures
import json
import pathlib
import subprocess
import sys
import time

from .. import atomic, kept
from ..paths import ROOT, profile_path
from . import flow, replay


def _markdown(doc: dict) -> str:
    rows = ["| run | command | runs | failed | fragments | mismatches | seconds |", "|---|---|---|---|---|---|---|"]
    for key, r in doc["regressions"].items():
        rows.append(f"| {key} | `{r['command']}` | {r['runs']} | {r['failed']} | {r['fragments']:,} | "
                    f"{r['mismatches']:,} | {r['seconds']} |")
    head = [f"# Gate-level simulation: {doc['profile']}", "",
            f"Netlist: {doc['netlist']} ({doc['memories']} memories as behavioural models, cells from "
            f"{doc['cells_source']}). Build (verilate + compile): {doc['build_seconds']} s.", ""]
    verdict = [f"", f"Verdict: **{'bit-exact' if doc['passed'] else 'MISMATCH'}** on every run."]
    if "mutant" in doc:
        m = doc["mutant"]
        verdict.append(f"Mutant ({m['module']}, {m['change']}): "
                       f"{'caught' if m['caught'] else 'NOT caught'}.")
    return "\n".join(head + rows + verdict) + "\n"


def _replay_runs(a) -> list:
    """(model, scene) pairs of --simulator iverilog: the netlist on every --scene, the mutant on the
    first only (it has to differ once)."""
    scenes = []
    for s in a.scene or [str(ROOT / "scenes" / "marble.toml")]:
        scenes += sorted((ROOT / "scenes").glob("*.toml")) if s == "all" else [pathlib.Path(s)]
    return scenes


def _replay(a, name: str, work: pathlib.Path, info: dict, out: pathlib.Path, t0: float) -> int:
    """--simulator iverilog: the netlist (and the mutant) on the RTL's port trace of every --scene,
    --jobs replays at a time (Icarus runs on one core)."""
    scenes, pst = _replay_runs(a), pathlib.Path(a.pst)
    size = a.size
    for f, what in [(s, "--scene") for s in scenes] + [(pst, "--pst")]:
        if not f.exists():
            print(f"error: {what} {f}: no such file", file=sys.stderr)
            return 2
    doc = {"profile": name, "simulator": "iverilog", "netlist": str(work / "netlist.v"), "memories": info["memories"],
           "cells_source": info["cells_source"], "gap_rate": a.gap_rate, "stall_rate": a.stall_rate, "sim_seed": a.seed}
    todo = [(f"{name}_gl", s) for s in scenes]

    def one(job):
        model, scene = job
        print(f"gatelevel: {model} on the RTL's trace of {scene.name} at {size} x {size} (Icarus)", flush=True)
        try:
            return replay.run(pst, name, out / "models", model, scene, size, out / f"{model}.{scene.stem}.replay",
                              gap_rate=a.gap_rate, stall_rate=a.stall_rate, sim_seed=a.seed)
        except replay.Refused as e:
            return {"model": model, "scene": str(scene), "refused": str(e)}

    try:
        with concurrent.futures.ThreadPoolExecutor(max_workers=a.jobs) as pool:
            runs = list(pool.map(one, todo))
        rendered = [pathlib.Path(r["scene"]) for r in runs if "refused" not in r]
        if a.mutate and rendered:
            runs.append(one((f"{name}_glmut", rendered[0])))
    except (replay.ReplayError, subprocess.TimeoutExpired) as e:
        print(f"error: {e}", file=sys.stderr)
        return 1
    doc["runs"] = runs
    gl = [r for r in runs if r["model"] == f"{name}_gl" and "refused" not in r]
    doc["passed"] = bool(gl) and all(r["passed"] for r in gl)
    if a.mutate:
        mut = runs[-1] if runs[-1]["model"] == f"{name}_glmut" else {}
        doc["mutant"] = {**info["mutant"], "caught": mut.get("mismatches", 0) > 0}
    doc["seconds"] = round(time.time() - t0, 1)
    atomic.write_text(out / f"{name}.json", json.dumps(doc, indent=1) + "\n")
    lines = [f"# Gate-level simulation: {name} (Icarus Verilog, the RTL's port trace)", "",
             f"Netlist: {doc['netlist']} ({doc['memories']} memories as behavioural models). Input gaps "
             f"{a.gap_rate:g}, output stalls {a.stall_rate:g} (seed {a.seed}).", "",
             "| model | scene | size | half clocks | outputs compared | pixels out | mismatches | simulate s |",
             "|---|---|---|---|---|---|---|---|"]
    for r in runs:
        if "refused" in r:
            lines.append(f"| {r['model']} | {pathlib.Path(r['scene']).name} | {size} | refused by the profile | | | | |")
            continue
        lines.append(f"| {r['model']} | {pathlib.Path(r['scene']).name} | {r['size']} | {r['half_clocks']:,} | "
                     f"{r['compared']:,} | {r['outputs_taken']} | {r['mismatches']:,} | {r['seconds']['simulate']} |")
    lines += ["", f"Verdict: **{'equal to the RTL' if doc['passed'] else 'MISMATCH'}** on every output of "
                  f"{len(gl)} scene(s)."]
    if a.mutate:
        lines.append(f"Mutant ({doc['mutant']['module']}, {doc['mutant']['change']}): "
                     f"{'caught' if doc['mutant']['caught'] else 'NOT caught'}.")
    md = "\n".join(lines) + "\n"
    atomic.write_text(out / f"{name}.md", md)
    print(md, end="")
    return 0 if doc["passed"] and (not a.mutate or doc["mutant"]["caught"]) else 1


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="scripts/gatelevel.py", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("profile")
    ap.add_argument("--work", help="a kept synthesis folder (scripts/synth.py --keep: OUT/NAME.work)")
    ap.add_argument("--out", default=str(ROOT / "out" / "gatelevel"))
    ap.add_argument("--size", type=int, default=None, help="image size of the scene runs (default 32; iverilog 16)")
    ap.add_argument("--random", type=int, default=100000, help="random fragments (default 100000; 0: none)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--gap-rate", type=float, default=None, help="input gap rate (default 0.2; iverilog 0)")
    ap.add_argument("--stall-rate", type=float, default=None, help="output stall rate (default 0.2; iverilog 0)")
    ap.add_argument("--mutate", metavar="MODULE", default="", help="also a mutant of MODULE that must fail")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--simulator", choices=("iverilog", "verilator"), default="iverilog")
    ap.add_argument("--scene", action="append", help="--simulator iverilog: a scene (repeatable; `all`: scenes/*.toml, "
                                                       "those the profile refuses listed as such; default scenes/marble.toml)")
    ap.add_argument("--pst", default=str(ROOT / "build" / "pst"), help="--simulator iverilog: the RTL's pst tool")
    a = ap.parse_args(argv)
    if a.size is None:
        a.size = 16 if a.simulator == "iverilog" else 32
    for k in ("gap_rate", "stall_rate"):
        if getattr(a, k) is None:
            setattr(a, k, 0.0 if a.simulator == "iverilog" else 0.2)
    if not 1 <= a.size <= 4096:
        ap.error("--size: must be in [1, 4096]")
    if not 0 <= a.random <= 1 << 32:
        ap.error("--random: must be in [0, 2^32]")
    for k in ("gap_rate", "stall_rate"):
        v = getattr(a, k)
        if not 0 <= v <= 0.95:
            ap.error(f"--{k.replace('_', '-')}: must be in [0, 0.95]")
    if not 1 <= a.jobs <= 256:
        ap.error("--jobs: must be in [1, 256]")
    prof = profile_path(a.profile)
    name = prof.stem
    out = pathlib.Path(a.out)
    t0 = time.time()
    try:
        if not prof.exists():
            raise kept.InputError(f"{a.profile}: no such profile ({prof})")
        work, _ = kept.synthesis(a.profile, out, a.work)
        if not (work / "mem.txt").exists() or not (work / "netlist.v").exists():
            raise kept.InputError(f"{work}: not a kept synthesis (no netlist.v, mem.txt)")
        info = flow.write_models(work, name, prof, out / "models", a.mutate)
    except (kept.InputError, flow.FlowError, ValueError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    if a.simulator == "iverilog":
        return _replay(a, name, work, info, out, t0)
    try:
        print(f"gatelevel: building {', '.join(info['models'])} in {out / 'build'}", flush=True)
        secs = flow.build(out / "models", out / "build", a.jobs)
        pst = out / "build" / "pst"
        gl = f"{name}_gl"
        common = ["--gap-rate", str(a.gap_rate), "--stall-rate", str(a.stall_rate), "--sim-seed", str(a.seed)]
        regs = {}
        print("gatelevel: scenes", flush=True)
        regs["scenes"] = flow.regress(pst, gl, out / f"{gl}.scenes", ["--size", str(a.size), *common])
        if a.random:
            print(f"gatelevel: {a.random} random fragments", flush=True)
            regs["random"] = flow.regress(pst, gl, out / f"{gl}.random",
                                          ["--random", str(a.random), "--seed", str(a.seed)])
        doc = {"profile": name, "netlist": str(work / "netlist.v"), "memories": info["memories"],
               "cells_source": info["cells_source"], "build_seconds": round(secs, 1), "regressions": regs}
        doc["passed"] = all(r["exit"] == 0 and r["failed"] == 0 and r["mismatches"] == 0 for r in regs.values())
        if a.mutate:
            print(f"gatelevel: mutant {info['mutant']['change']}", flush=True)
            mr = flow.regress(pst, f"{name}_glmut", out / f"{name}_glmut.random",
                              ["--random", str(min(a.random or 20000, 20000)), "--seed", str(a.seed)])
            mr_s = flow.regress(pst, f"{name}_glmut", out / f"{name}_glmut.scenes", ["--size", str(a.size), *common])
            doc["mutant"] = {**info["mutant"], "random": mr, "scenes": mr_s,
                             "caught": mr["exit"] != 0 or mr_s["exit"] != 0}
        doc["seconds"] = round(time.time() - t0, 1)
    except flow.FlowError as e:
        print(f"error: {e}", file=sys.stderr)
        return 1
    atomic.write_text(out / f"{name}.json", json.dumps(doc, indent=1) + "\n")
    md = _markdown(doc)
    atomic.write_text(out / f"{name}.md", md)
    print(md, end="")
    ok = doc["passed"] and (not a.mutate or doc["mutant"]["caught"])
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
