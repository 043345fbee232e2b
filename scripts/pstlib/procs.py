"""Child processes an interrupt stops: each runs in its own process group, registered while it
runs, so stop_children() (Ctrl-C, SIGTERM of a sweep or a search) ends them and their own
children (Yosys' ABC) at once; once STOP is set no new one starts."""
import os
import signal
import subprocess
import threading

from .paths import ROOT

STOP = threading.Event()
_procs = set()
_procs_lock = threading.Lock()
def run(cmd, cwd=ROOT, timeout=None, on_start=None):
    """Runs a command in its own process group (so an interrupt can stop its children too):
    (exit status, stdout, stderr); KeyboardInterrupt once STOP is set. on_start(pid) is called
    once it runs."""
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


_print_lock = threading.Lock()


def say(msg: str) -> None:
    """One line of progress, whole, from any thread (the backends' and the jobs' printing)."""
    with _print_lock:
        print(msg, flush=True)
