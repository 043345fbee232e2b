"""The local backend: points evaluated on threads of this process, their child processes in
process groups an interrupt (Ctrl-C, SIGTERM) stops."""
import concurrent.futures
import signal

from ..procs import STOP, run, say, stop_children  # noqa: F401  (the backend's child processes and printing)

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
