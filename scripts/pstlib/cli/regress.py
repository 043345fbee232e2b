"""`pst regress` in shards, on local workers or as a SLURM job array, merged into one result.

    scripts/regress.py [SCENES...] [--size 64] [--profile P ...]            scenes x profiles
    scripts/regress.py --random N [--seed S] [--from K] [--chunk C] [--profile P ...]
                       [--jobs 2 | --backend slurm [--partition P] [--account A] [--time T] [--slurm-arg X]]
                       [--out out/regress] [--retries 1] [--shard NAME ...] [--pst build/pst] [--pst-arg=ARG ...]

The work is split as `pst regress --list` gives it: one shard per scene x profile, or per
profile and chunk of at least C random fragments, cut where a segment of the random stream
starts (`--random C --from K`: the shards simulate what one process would, each fragment once;
default C: 1M, or fewer so that each local worker gets at least two shards). Each shard is one `pst regress` with its own
JSON, JUnit and log in OUT/shards/ (scripts/pstlib/backends/regress_shards.py). A shard that leaves no
complete result (killed, crashed, timed out) is run again alone, up to --retries times; a
later run of the same command runs only the shards without a complete result (a shard that
failed with a mismatch or an RTL assertion has one: it is not re-run). --shard NAME runs
that shard again whatever it holds. The merged result: OUT/merged.json (every run, totals per
profile, the first failure: shard, seed, fragment, replay command, the assertion the
simulator named), OUT/merged.xml (JUnit: every shard's test cases, an error case per shard
without a result) and the summary on stdout.

--backend slurm submits the shards as an sbatch job array (scripts/pstlib/backends/slurm.py, shared
with scripts/search.py; run it from a checkout on a file system the compute nodes share) and
waits for it; --pst-arg passes an argument to every shard's `pst regress` (--pst-arg=--probes,
--pst-arg=--batch=512; scene shards: --pst-arg=--stall-rate=0.2, which --random refuses: its
segments draw their own gaps and stalls).

Exit status: 0 when every shard passed; 1 on a failure or a shard still without a result;
2 on bad arguments (nothing written); 130 when interrupted.
"""
import argparse
import json
import os
import pathlib
import shutil
import signal
import subprocess
import sys
import time

from .. import atomic
from ..backends import regress_shards as R
from ..backends import slurm
from ..paths import ROOT
from ..backends.local import run_points, say, stop_children


class ArgError(Exception):
    pass


def parse_args(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scenes", nargs="*", help="scene files (default: pst's, scenes/*.toml)")
    ap.add_argument("--size", type=int, default=64, help="image size of the scene runs")
    ap.add_argument("--profile", action="append", default=[], help="profile (repeatable; default every verilated one)")
    ap.add_argument("--random", type=int, default=0, metavar="N", help="N constrained-random fragments per profile")
    ap.add_argument("--seed", type=int, default=1, help="seed of --random")
    ap.add_argument("--from", dest="first", type=int, default=0, metavar="K", help="first fragment index of --random")
    ap.add_argument("--chunk", type=int, default=0, metavar="C", help="random fragments per shard (at least; whole segments)")
    ap.add_argument("--batch", type=int, default=0, help="most fragments per random texture (pst's --batch; default pst's)")
    slurm.add_backend_args(ap, "04:00:00")
    ap.add_argument("--retries", type=int, default=1, help="re-runs of a shard that left no result")
    ap.add_argument("--shard", action="append", default=[], help="run this shard again (repeatable)")
    ap.add_argument("--timeout", type=float, default=0, help="seconds a local shard may run (0: no limit)")
    ap.add_argument("--pst", default=str(ROOT / "build" / "pst"))
    ap.add_argument("--pst-arg", action="append", default=[], help="argument for every shard's pst regress")
    ap.add_argument("--out", default=str(ROOT / "out" / "regress"))
    return ap.parse_args(argv)


def check(a):
    """Bad arguments: ArgError("--flag: what") before anything is written."""
    if a.size < 1:
        raise ArgError(f"--size: must be >= 1, got {a.size}")
    if a.random < 0:
        raise ArgError(f"--random: must be >= 1, got {a.random}")
    if a.random and a.scenes:
        raise ArgError("--random: takes no scene files")
    if a.first < 0:
        raise ArgError(f"--from: must be >= 0, got {a.first}")
    if a.chunk < 0 or (a.chunk and not a.random):
        raise ArgError("--chunk: a positive fragment count, with --random")
    if a.batch < 0 or (a.batch and not a.random):
        raise ArgError("--batch: a positive fragment count, with --random")
    if a.jobs < 1:
        raise ArgError(f"--jobs: must be >= 1, got {a.jobs}")
    if a.retries < 0:
        raise ArgError(f"--retries: must be >= 0, got {a.retries}")
    if a.timeout < 0:
        raise ArgError(f"--timeout: must be >= 0, got {a.timeout}")
    if not os.access(a.pst, os.X_OK):
        raise ArgError(f"--pst: '{a.pst}' is not an executable (build it: cmake --build build --target pst)")
    out = pathlib.Path(a.out)
    if out.exists() and not out.is_dir():
        raise ArgError(f"--out: '{out}' is a file; give a folder")
    if a.backend == "slurm" and not shutil.which("sbatch"):
        raise ArgError("--backend: slurm needs sbatch and squeue on PATH (Debian's slurm-client)")
    for x in a.pst_arg:
        if x.split("=")[0] in ("-o", "--out", "--junit", "--html", "--images", "--list", "--random", "--from",
                               "--seed", "--size", "--profile", "--batch"):
            raise ArgError(f"--pst-arg: '{x}' is the launcher's to set")


def make_plan(a) -> list:
    """The shards, from `pst regress --list` (which also checks the scenes and profiles)."""
    cmd = [a.pst, "regress", "--list", *a.scenes]
    for p in a.profile:
        cmd += ["--profile", p]
    if a.random:
        cmd += ["--random", str(a.random), "--seed", str(a.seed), "--from", str(a.first)]
        if a.batch:
            cmd += ["--batch", str(a.batch)]
    r = subprocess.run(cmd, capture_output=True, text=True, env=dict(os.environ, PST_SOURCE_DIR=str(ROOT)))
    if r.returncode != 0:
        raise ArgError((r.stderr.strip() or r.stdout.strip()).removeprefix("error: ") or f"pst regress --list exited {r.returncode}")
    if a.random:
        chunk = a.chunk or R.default_chunk(a.random, a.jobs if a.backend == "local" else 64)
        profiles, starts = R.parse_list(r.stdout, True)
        return R.plan_random(profiles, starts, a.random, a.seed, a.first, chunk, a.batch, a.pst_arg)
    return R.plan_scenes(R.parse_list(r.stdout, False), a.size, a.pst_arg)


def run_local(a, out, todo, attempts):
    def work(s):
        attempts[s.name] = attempts.get(s.name, 0) + 1
        return R.run_shard(out, s, a.pst, timeout=a.timeout or None)

    def failed(s, e):
        return {"name": s.name, "complete": False, "rc": None, "error": str(e)}

    def report(s, rec, how):
        state = "done" if rec.get("complete") else f"NO RESULT (exit {rec.get('rc')})"
        say(f"  {s.name}: {state}, {rec.get('seconds', 0):.1f} s")

    run_points(todo, a.jobs, lambda s: None, work, failed, report)


def run_slurm(a, out, todo, attempts):
    for s in todo:
        attempts[s.name] = attempts.get(s.name, 0) + 1
    slurm.run_array(out / "slurm", "pst-regress", [s.name for s in todo],
                    lambda batch: f"/usr/bin/python3 {ROOT / 'scripts' / 'regress.py'} worker {out} {batch}.names",
                    "shard(s)", a.partition, a.account, a.time_limit, a.slurm_arg)
    for s in todo:
        say(f"  {s.name}: {'done' if R.complete(out, s) else 'NO RESULT'}")


def sharded(argv=None) -> int:
    a = parse_args(sys.argv[1:] if argv is None else argv)
    try:
        check(a)
        plan = make_plan(a)
        if not plan:
            raise ArgError("--profile: no runs to shard (pst regress --list printed none)")
        names = {s.name for s in plan}
        for n in a.shard:
            if n not in names:
                raise ArgError(f"--shard: '{n}' is not a shard of this plan (see {a.out}/plan.json)")
    except ArgError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    out = pathlib.Path(a.out).resolve()
    a.pst = os.path.abspath(a.pst)       # the SLURM tasks and the replay command run it from elsewhere
    out.mkdir(parents=True, exist_ok=True)
    state_file = out / "state.json"
    state = R.read_state(state_file, plan)
    attempts = state["attempts"]
    atomic.write_text(out / "plan.json", json.dumps({"pst": a.pst, "shards": [s.to_json() for s in plan]}, indent=1) + "\n")
    forced = set(a.shard)
    todo = [s for s in plan if s.name in forced or R.complete(out, s) is None]
    say(f"{len(plan)} shards, {len(plan) - len(todo)} with a complete result, {len(todo)} to run "
        f"({a.backend}{', ' + str(a.jobs) + ' jobs' if a.backend == 'local' else ''}) -> {out}")
    t0 = time.time()
    try:
        for attempt in range(a.retries + 1):
            if not todo:
                break
            if attempt:
                say(f"re-running {len(todo)} shard(s) without a result, alone: {', '.join(s.name for s in todo)}")
            (run_slurm if a.backend == "slurm" else run_local)(a, out, todo, attempts)
            atomic.write_text(state_file, json.dumps(state, indent=1) + "\n")
            todo = [s for s in todo if R.complete(out, s) is None]
    except KeyboardInterrupt:
        stop_children()
        atomic.write_text(state_file, json.dumps(state, indent=1) + "\n")
        print("interrupted; the same command resumes", file=sys.stderr)
        return 130
    m = R.merge(out, plan, a.pst, attempts)
    m["seconds"] = round(time.time() - t0, 1)
    atomic.write_text(out / "merged.json", json.dumps(m, indent=1) + "\n")
    suite = "pst regress --random (sharded)" if a.random else "pst regress (sharded)"
    atomic.write_text(out / "merged.xml", R.merge_junit(out, plan, suite))
    say(R.summary(m))
    say(f"merged: {out / 'merged.json'}, {out / 'merged.xml'} ({m['seconds']} s)")
    return 0 if m["passed"] else 1


def worker(out: pathlib.Path, names_file: str) -> int:
    """A SLURM array task: the shard on line SLURM_ARRAY_TASK_ID of OUT/slurm/NAMES_FILE."""
    # scancel (or a time limit) sends SIGTERM: stop pst too (it runs in its own process group).
    signal.signal(signal.SIGTERM, lambda *_: (stop_children(), sys.exit(143)))
    names = (out / "slurm" / names_file).read_text().split()
    name = names[int(os.environ.get("SLURM_ARRAY_TASK_ID", "0"))]
    plan = json.loads((out / "plan.json").read_text())
    shard = next(R.Shard.from_json(d) for d in plan["shards"] if d["name"] == name)
    rec = R.run_shard(out, shard, plan["pst"])
    print(f"{name}: exit {rec['rc']}, {rec['seconds']} s, {'complete' if rec['complete'] else 'NO RESULT'}")
    return 0 if rec["complete"] else 1



def main(argv=None) -> int:
    """The command: a SLURM array task (`worker OUT NAMES`) or the sharded regression."""
    argv = sys.argv[1:] if argv is None else list(argv)
    if argv and argv[0] == "worker":      # scripts/regress.py worker OUT NAMES
        return worker(pathlib.Path(argv[1]), argv[2])
    return sharded(argv)


if __name__ == "__main__":
    sys.exit(main())
