"""The SLURM backend: search points as a job array (pstlib/backends/slurm.py): the driver writes the array
job, submits it, follows it until no task is left, then reads the per-point results the tasks
wrote (OUT/results/NAME.json, atomic). A task that failed or was cancelled leaves no complete
result; the driver records the point as failed and the next run of the same command resubmits it.

Pointing it at a real cluster: run scripts/search.py with --backend slurm as pstlib/backends/slurm.py says
(the tasks run scripts/search.py worker with the same paths: build/pst, the ROM images, the
module cache, OUT)."""
import pathlib

from . import slurm
from ..paths import PY, ROOT


def job_script(out: pathlib.Path, batch: str, n: int, which, partition=None, account=None, time_limit=None,
               extra=(), python=PY) -> str:
    return slurm.array_script(f"pst-search-{batch}", n, f"{out}/slurm/{batch}_%a.log", _command(out, batch, which, python),
                              partition, account, time_limit, extra)


def _command(out, batch, which, python=PY) -> str:
    return f"{python} {ROOT / 'scripts' / 'search.py'} worker {out} {batch}.names {','.join(which)}"


def run_array(out: pathlib.Path, names: list, which, partition=None, account=None, time_limit=None,
              extra=()) -> str:
    """Evaluates NAMES as one array job (job_script's cluster options); returns its job id."""
    return slurm.run_array(out / "slurm", "pst-search", names, lambda batch: _command(out, batch, which),
                           "point(s)", partition, account, time_limit, extra)
