"""The SLURM backend: search points as a job array: the driver writes the array job, submits it with sbatch,
follows it with squeue until no task is left, then reads the per-point results the tasks wrote
(OUT/results/NAME.json, atomic). A task that failed or was cancelled leaves no complete result;
the driver records the point as failed and the next run of the same command resubmits it.

Pointing it at a real cluster: run scripts/search.py with --backend slurm on a login node whose
sbatch/squeue reach the cluster (SLURM_CONF or /etc/slurm/slurm.conf), from a checkout on a
file system the compute nodes share (the tasks run scripts/search.py worker with the same
paths: build/pst, the ROM images, the module cache, OUT); --partition, --account, --time
(per task) and --slurm-arg (any other sbatch option, e.g. --mem=4G or --qos=...) go into the
job script's #SBATCH lines."""
import pathlib
import re
import subprocess
import time

from .. import atomic
from ..paths import PY, ROOT
from .local import STOP, say

POLL_S = 2.0


def job_script(out: pathlib.Path, batch: str, n: int, which, partition=None, account=None, time_limit=None,
               extra=(), python=PY) -> str:
    lines = ["#!/bin/sh", f"#SBATCH --job-name=pst-search-{batch}", f"#SBATCH --array=0-{n - 1}",
             f"#SBATCH --output={out}/slurm/{batch}_%a.log", "#SBATCH --cpus-per-task=1"]
    if partition:
        lines.append(f"#SBATCH --partition={partition}")
    if account:
        lines.append(f"#SBATCH --account={account}")
    if time_limit:
        lines.append(f"#SBATCH --time={time_limit}")
    lines += [f"#SBATCH {x}" for x in extra]
    lines += [f"cd {ROOT}", f"exec {python} {ROOT / 'scripts' / 'search.py'} worker {out} {batch}.names "
              f"{','.join(which)}"]
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


def run_array(out: pathlib.Path, names: list, which, partition=None, account=None, time_limit=None,
              extra=()) -> str:
    """Evaluates NAMES as one array job (job_script's cluster options); returns its job id."""
    sdir = out / "slurm"
    sdir.mkdir(parents=True, exist_ok=True)
    batch = f"b{int(time.time() * 1000) % 10**10}"
    atomic.write_text(sdir / f"{batch}.names", "\n".join(names) + "\n")
    script = sdir / f"{batch}.sh"
    atomic.write_text(script, job_script(out, batch, len(names), which, partition, account, time_limit, extra))
    job = submit(script)
    say(f"    sbatch: job {job}, array of {len(names)} point(s) ({script.name})")
    wait(job)
    return job
