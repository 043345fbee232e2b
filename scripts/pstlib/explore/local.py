"""The local backend: points evaluated on threads of this process, their child processes in
process groups an interrupt (Ctrl-C, SIGTERM) stops."""
import concurrent.futures
import os
import signal
import subprocess
import threading

from ..paths import ROOT
from .store import read_json  # noqa: F401  (the backends' callers read results through it)

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
