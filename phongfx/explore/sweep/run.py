"""Sweeps over methods and their bit widths: error against cost.

A sweep spec (TOML, see ``sweeps/README.md``) names reference scenes, optional
synthesis options, and ``[[grid]]`` tables (the cartesian product of their lists)
or ``[[points]]`` tables (one point each) over the methods of
:mod:`phongfx.explore.evaluate`.  :func:`run_sweep` runs :func:`phongfx.explore.evaluate.evaluate`
on every point, on a local process pool or a Dask cluster, and appends one JSON
record per finished point to ``<out>/points.jsonl`` at once (flushed and synced),
so an interrupted run loses nothing finished; a re-run skips points already
recorded ``ok`` and runs the rest, failed ones included.  ``<out>/points.csv`` is
rebuilt from the records at the end of every run.
"""

import csv
import functools
import json
import multiprocessing
import os
import signal
import sys
import threading
import time
from concurrent.futures import ProcessPoolExecutor, as_completed

from phongfx.core.files import atomic_write

from phongfx.explore.sweep.spec import SweepSpecError, expand, is_int, load_spec, point_id

__all__ = ["SweepSpecError", "load_spec", "expand", "point_id", "load_records", "write_csv",
           "run_sweep"]

def load_records(path):
    """The records of a ``points.jsonl``, one per point id, the last one written winning
    (a failed point re-run later); ``[]`` if there is no file.

    A last line that does not parse (a run killed while appending) is ignored; a bad line
    anywhere else raises ``ValueError`` naming the line.
    """
    try:
        with open(path, encoding="utf-8") as file:
            lines = file.read().rstrip("\n").split("\n")
    except FileNotFoundError:
        return []
    records = {}
    for number, line in enumerate(lines, 1):
        if not line.strip():
            continue
        try:
            record = json.loads(line)
        except ValueError as error:
            if number == len(lines):  # torn by an interrupted append
                break
            raise ValueError(f"{path} line {number} is not JSON ({error})") from None
        if isinstance(record, dict) and "id" in record:
            records.pop(record["id"], None)  # a re-run point moves to the end
            records[record["id"]] = record
    return list(records.values())


def _union(rows):
    seen = {}
    for row in rows:
        seen.update(dict.fromkeys(row))
    return list(seen)


def write_csv(records, path):
    """Write ``records`` as CSV, atomically: ``id, method, status, error, seconds``,
    ``param.<name>`` (the union over methods, blank where absent), the metric keys,
    then ``cost.<key>``."""
    params = _union(r.get("params") or {} for r in records)
    metrics = _union(r.get("metrics") or {} for r in records)
    costs = _union(r.get("cost") or {} for r in records)
    header = (["id", "method", "status", "error", "seconds"] + [f"param.{p}" for p in params]
              + metrics + [f"cost.{c}" for c in costs])

    def write(tmp):
        with open(tmp, "w", newline="", encoding="utf-8") as file:
            out = csv.writer(file)
            out.writerow(header)
            for r in records:
                p, m, c = r.get("params") or {}, r.get("metrics") or {}, r.get("cost") or {}
                out.writerow([r.get("id"), r.get("method"), r.get("status"), r.get("error") or "",
                              r.get("seconds")] + [p.get(k, "") for k in params]
                             + [m.get(k, "") for k in metrics] + [c.get(k, "") for k in costs])
    atomic_write(path, write)


def _trim_torn_tail(path):
    """Cut a last line without its newline (a run killed mid-write), so appends stay whole."""
    try:
        with open(path, "rb+") as file:
            data = file.read()
            if data and not data.endswith(b"\n"):
                file.truncate(data.rfind(b"\n") + 1)
    except FileNotFoundError:
        pass


def _one_line(error):
    lines = [line.strip() for line in str(error).splitlines() if line.strip()]
    text = f"{type(error).__name__}: {lines[0] if lines else ''}".rstrip(": ")
    return text if len(text) <= 300 else text[:297] + "..."


def _plain(value):
    return value.item() if hasattr(value, "item") else value  # numpy scalars -> JSON


def _record(point, status, error, seconds, metrics, cost):
    record = {"id": point["id"], "method": point["method"], "params": point["params"],
              "status": status, "error": error, "seconds": seconds, "metrics": metrics,
              "cost": cost, "scenes": point["scenes"], "synth": point["synth"]}
    if point.get("scene_files"):
        record["scene_files"] = point["scene_files"]
    return record


#: Set in a pool worker by :func:`_worker_stop`; a point that sees it ends the worker.
_stopping = False
#: Whether this pool worker is inside a point (where a stop can unwind it cleanly).
_busy = False


def _worker_init():
    """A pool worker answers Ctrl-C through its parent, not itself: the parent stops the
    sweep and reports once (a terminal sends SIGINT to every process of the group, and a
    worker's own ``KeyboardInterrupt`` would print a traceback, or be taken for a failed
    point).  The parent's stop is SIGTERM, which unwinds a running point (the synthesis
    flow's tools killed, its half-run folder removed) and ends the worker."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, _worker_stop)


def _worker_stop(signum, frame):
    global _stopping
    _stopping = True
    if not _busy:  # between points: nothing to clean up, and no traceback wanted
        os._exit(0)
    raise KeyboardInterrupt


def _run_point(evaluate, point):
    """The record of one point: ``evaluate``'s result, or its error (one line)."""
    global _busy
    start = time.perf_counter()
    _busy = True
    try:
        files = point.get("scene_files") or {}  # a scene file is evaluated from its path
        scenes = tuple(files.get(scene, scene) for scene in point["scenes"])
        result = evaluate(point["method"], dict(point["params"]), scenes=scenes,
                          synth=point["synth"], proxy=point.get("proxy"))
        metrics = {key: float(value) for key, value in result["metrics"].items()}
        cost = result.get("cost")
        cost = None if cost is None else {key: _plain(value) for key, value in cost.items()}
    except Exception as error:  # recorded; KeyboardInterrupt is not caught
        return _record(point, "failed", _one_line(error), time.perf_counter() - start, {}, None)
    except KeyboardInterrupt:
        if _stopping:  # the parent stopped the sweep: the point's cleanup has run
            os._exit(0)
        raise
    finally:
        _busy = False
    return _record(point, "ok", None, time.perf_counter() - start, metrics, cost)


def _collect(future, point):
    """A finished future's record; a worker that died (not the point) is a failure too."""
    try:
        return future.result()
    except Exception as error:
        return _record(point, "failed", _one_line(error), 0.0, {}, None)


def _stop_workers(workers, grace=5.0):
    """End the pool's ``workers`` now: SIGTERM (each unwinds its point), then SIGKILL for any
    still alive after ``grace`` seconds in all."""
    for process in workers:
        process.terminate()
    deadline = time.monotonic() + grace
    for process in workers:
        process.join(max(0.0, deadline - time.monotonic()))
        if process.is_alive():
            process.kill()
            process.join()


def _execute_pool(evaluate, points, record, workers):
    if workers == 1:  # in this process: no pickling, easy to debug
        for point in points:
            record(_run_point(evaluate, point))
        return
    before, threads = set(multiprocessing.active_children()), set(threading.enumerate())
    with ProcessPoolExecutor(min(workers, len(points)), initializer=_worker_init) as pool:
        futures = {pool.submit(_run_point, evaluate, point): point for point in points}
        recorded = set()
        try:
            for future in as_completed(futures):
                record(_collect(future, futures[future]))
                recorded.add(future)
        except KeyboardInterrupt:
            # stop now: queued points are dropped and running ones abandoned (waiting for
            # them kept a sweep busy for minutes after Ctrl-C); what had finished is kept
            pool.shutdown(wait=False, cancel_futures=True)
            _stop_workers(set(multiprocessing.active_children()) - before)
            # the pool's manager thread closes its wake-up pipe once it sees the workers gone, and
            # Python's exit hook writes to that pipe unguarded: left running, the two raced and the
            # interrupted sweep ended on an EBADF traceback after its one-line message
            deadline = time.monotonic() + 5.0
            for thread in set(threading.enumerate()) - threads:
                thread.join(max(0.0, deadline - time.monotonic()))
            for future in futures:
                if future not in recorded and future.done() and not future.cancelled() \
                        and future.exception() is None:
                    record(future.result())
            raise


def _execute_dask(evaluate, points, record, workers, scheduler):
    from phongfx.explore.cluster import run_on_dask

    def done(index, value, error):  # a worker that died (not the point) is a failure too
        record(value if error is None else _record(points[index], "failed", _one_line(error), 0.0, {}, None))

    run_on_dask(functools.partial(_run_point, evaluate), points, done, scheduler=scheduler, workers=workers)


def run_sweep(spec, *, out="build/sweep", workers=None, scheduler=None, progress=True,
              evaluate=None, rerun_failed=True):
    """Run every point of ``spec`` not yet recorded ``ok`` in ``<out>/points.jsonl``.

    Parameters
    ----------
    spec : path or dict
        A sweep spec (:func:`load_spec`).
    out : path
        Output folder: ``points.jsonl`` (appended, one record per finished point)
        and ``points.csv`` (rebuilt at the end).
    workers : int, optional
        Worker processes (default ``os.cpu_count()``); 1 runs in this process.
    scheduler : str, optional
        A Dask scheduler address, or ``"local"`` for a ``LocalCluster`` of
        ``workers`` processes; needs the ``cluster`` extra (``dask[distributed]``).
    progress : bool
        Show a progress bar (points done / total, time left) on stderr.
    evaluate : callable, optional
        Instead of :func:`phongfx.explore.evaluate.evaluate` (same signature; picklable
        when run on a pool or a cluster).
    rerun_failed : bool
        Run again points recorded ``failed`` (default); ``ok`` points never re-run.

    Returns
    -------
    dict
        ``total``, ``skipped`` (already recorded: ok, or failed without ``rerun_failed``),
        ``ran``, ``ok``, ``failed`` (this run),
        ``seconds``, ``jsonl``, ``csv``.

    Raises
    ------
    SweepSpecError
        For a bad spec, before anything runs.
    ValueError
        For a bad ``workers``, or a ``scheduler`` without Dask installed.
    KeyboardInterrupt
        Re-raised after the points finished so far are recorded and the CSV written.
    """
    if workers is not None and (not is_int(workers) or workers < 1):
        raise ValueError(f"workers must be a positive integer, not {workers!r}")
    if evaluate is None:
        from phongfx.explore.evaluate import evaluate
    points = load_spec(spec)["points"]
    jsonl, csv_path = os.path.join(out, "points.jsonl"), os.path.join(out, "points.csv")
    os.makedirs(out, exist_ok=True)
    _trim_torn_tail(jsonl)
    previous = {r["id"]: r.get("status") for r in load_records(jsonl)}
    done = {"ok"} if rerun_failed else {"ok", "failed"}
    todo = [p for p in points if previous.get(p["id"]) not in done]
    todo.sort(key=lambda p: p["synth"] is None)  # slow synthesis first: a shorter tail on the pool
    summary = {"total": len(points), "skipped": len(points) - len(todo), "ran": 0, "ok": 0,
               "failed": 0, "seconds": 0.0, "jsonl": jsonl, "csv": csv_path}
    start = time.monotonic()
    bar = None
    if progress:
        from tqdm import tqdm
        bar = tqdm(total=len(points), initial=summary["skipped"], unit="point", file=sys.stderr,
                   dynamic_ncols=True)

    def record(result):
        line = json.dumps(result) + "\n"
        with open(jsonl, "a", encoding="utf-8") as file:
            file.write(line)
            file.flush()
            os.fsync(file.fileno())
        summary["ran"] += 1
        summary[result["status"]] += 1
        if bar is not None:
            bar.update(1)
            bar.set_postfix(failed=summary["failed"], refresh=False)

    try:
        if todo:
            workers = workers or os.cpu_count() or 1
            if scheduler is None:
                _execute_pool(evaluate, todo, record, workers)
            else:
                _execute_dask(evaluate, todo, record, workers, scheduler)
    finally:
        if bar is not None:
            bar.close()
        summary["seconds"] = time.monotonic() - start
        write_csv(load_records(jsonl), csv_path)
    return summary
