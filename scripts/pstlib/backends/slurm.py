"""SLURM job arrays for the scripts: a job script with one task per name, submitted with sbatch
and followed with squeue until no task is left. Each task writes its own result (atomically);
the caller reads them afterwards, and what a failed or cancelled task did not write is the
caller's to retry. Used by the design-space search (search_job_script, run_search_array below) and the sharded
regression (regress_shards.py).

Pointing it at a real cluster: run the script on a login node whose sbatch/squeue reach the
cluster (SLURM_CONF or /etc/slurm/slurm.conf), from a checkout on a file system the compute
nodes share (the tasks run the same script with the same paths: build/pst, the output folder);
--partition, --account, --time (per task) and --slurm-arg (any other sbatch option, e.g.
--mem=4G or --qos=...) go into the job script's #SBATCH lines."""
import pathlib
import re
import subprocess
import time

from .. import atomic
from ..paths import ROOT
from ..paths import PY
from ..procs import STOP, say

POLL_S = 2.0


def add_backend_args(ap, time_limit: str) -> None:
    """The command lines' backend options: --jobs (local workers), --backend, and the SLURM
    job's --partition, --account, --time (per task, default TIME_LIMIT) and --slurm-arg."""
    ap.add_argument("--jobs", type=int, default=2, help="workers in parallel (local backend)")
    ap.add_argument("--backend", choices=["local", "slurm"], default="local")
    ap.add_argument("--partition", help="SLURM partition")
    ap.add_argument("--account", help="SLURM account")
    ap.add_argument("--time", dest="time_limit", default=time_limit, help="SLURM time limit per task")
    ap.add_argument("--slurm-arg", action="append", default=[], help="extra sbatch argument (repeatable)")


def array_script(name: str, n: int, log: str, command: str, partition=None, account=None, time_limit=None,
                 extra=()) -> str:
    """An array job of N tasks (SLURM_ARRAY_TASK_ID 0..N-1), each running COMMAND from the
    repository root, its output in LOG (%a: the task's index)."""
    lines = ["#!/bin/sh", f"#SBATCH --job-name={name}", f"#SBATCH --array=0-{n - 1}",
             f"#SBATCH --output={log}", "#SBATCH --cpus-per-task=1"]
    if partition:
        lines.append(f"#SBATCH --partition={partition}")
    if account:
        lines.append(f"#SBATCH --account={account}")
    if time_limit:
        lines.append(f"#SBATCH --time={time_limit}")
    lines += [f"#SBATCH {x}" for x in extra]
    lines += [f"cd {ROOT}", f"exec {command}"]
    return "\n".join(lines) + "\n"


def _sh(cmd):
    return subprocess.run(cmd, capture_output=True, text=True)


def submit(script: pathlib.Path) -> str:
    r = _sh(["sbatch", "--parsable", str(script)])
    if r.returncode != 0:
        raise RuntimeError(f"sbatch {script} exited {r.returncode}: {r.stderr.strip()}")
    m = re.match(r"(\d+)", r.stdout.strip())
    if not m:
        raise RuntimeError(f"sbatch printed no job id: {r.stdout!r}")
    return m.group(1)


def wait(job_id: str, timeout_s=None) -> None:
    """Until squeue lists no task of the job (done, failed or cancelled)."""
    t0 = time.time()
    while True:
        if STOP.is_set():
            _sh(["scancel", job_id])
            raise KeyboardInterrupt
        r = _sh(["squeue", "-h", "-j", job_id, "-o", "%i %T"])
        if r.returncode != 0 and "Invalid job id" not in r.stderr:
            raise RuntimeError(f"squeue -j {job_id}: {r.stderr.strip()}")
        if not r.stdout.strip():
            return
        if timeout_s and time.time() - t0 > timeout_s:
            _sh(["scancel", job_id])
            raise RuntimeError(f"job {job_id}: still running after {timeout_s} s (cancelled)")
        time.sleep(POLL_S)


def run_array(sdir: pathlib.Path, prefix: str, names: list, command, what="task(s)", partition=None, account=None,
              time_limit=None, extra=()) -> str:
    """Runs one task per name as an array job and waits for it; returns its job id. The names go
    to SDIR/BATCH.names (task i takes line i), the job script to SDIR/BATCH.sh, the tasks' output
    to SDIR/BATCH_<i>.log; command(batch) is the task's command line; the cluster options go
    into the job script as array_script says."""
    sdir.mkdir(parents=True, exist_ok=True)
    batch = f"b{int(time.time() * 1000) % 10**10}"
    atomic.write_text(sdir / f"{batch}.names", "\n".join(names) + "\n")
    script = sdir / f"{batch}.sh"
    atomic.write_text(script, array_script(f"{prefix}-{batch}", len(names), f"{sdir}/{batch}_%a.log",
                                           command(batch), partition, account, time_limit, extra))
    job = submit(script)
    say(f"    sbatch: job {job}, array of {len(names)} {what} ({script.name})")
    wait(job)
    return job


# The design-space search's points as a job array: the driver writes the array job, submits it,
# follows it until no task is left, then reads the per-point results the tasks wrote
# (OUT/results/NAME.json, atomic). A task that failed or was cancelled leaves no complete
# result; the driver records the point as failed and the next run of the same command
# resubmits it. The tasks run scripts/search.py worker with the same paths (build/pst, the ROM
# images, the module cache, OUT).
def search_job_script(out: pathlib.Path, batch: str, n: int, which, partition=None, account=None, time_limit=None,
               extra=(), python=PY) -> str:
    return array_script(f"pst-search-{batch}", n, f"{out}/slurm/{batch}_%a.log", _search_command(out, batch, which, python),
                              partition, account, time_limit, extra)


def _search_command(out, batch, which, python=PY) -> str:
    return f"{python} {ROOT / 'scripts' / 'search.py'} worker {out} {batch}.names {','.join(which)}"


def run_search_array(out: pathlib.Path, names: list, which, partition=None, account=None, time_limit=None,
              extra=()) -> str:
    """Evaluates NAMES as one array job (search_job_script's cluster options); returns its job id."""
    return run_array(out / "slurm", "pst-search", names, lambda batch: _search_command(out, batch, which),
                           "point(s)", partition, account, time_limit, extra)
