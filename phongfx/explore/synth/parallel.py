"""Synthesis of many candidates at once, on Dask, with progress that keeps ticking.

A ``compile --synth`` weighs several designs, each minutes of Yosys and nextpnr; one after
another they took 39 minutes for two candidates on a loaded 2-core machine.  The runs are
independent, so :func:`synth_all` hands them to Dask through the helper the sweeps use
(:func:`phongfx.explore.cluster.run_on_dask`: a local cluster by default, a scheduler's
address when given) and gives back every result in the jobs' order.

A tool run is minutes without a word, and a line that does not move reads as hung.  So
every job forwards its flow's own stages (``verilog``, ``yosys``, ``nextpnr``; ``sta`` on
standard cells: the ``progress`` callback of :func:`~phongfx.explore.synth.fpga.synth`) to
this process as Dask events, and while any job runs ``progress(text)`` is called at least
every :data:`TICK_SECONDS` with one line per running candidate: ``candidate i of N (label):
<stage>, T s``, T its seconds since it started.

Ctrl-C cancels the jobs not finished.  A run cut short leaves no cache entry: a result is
renamed into the cache only once whole (:func:`phongfx.core.cache.make_entry`).
"""

import os
import threading
import time
import uuid

from phongfx.explore.cluster import run_on_dask, worker_event

__all__ = ["TICK_SECONDS", "synth_all"]

#: The longest wait between two progress lines while a job runs.
TICK_SECONDS = 5.0


class _Board:
    """Where each job is (its stage and start time), and the lines that say so."""

    def __init__(self, jobs, progress, clock=time.monotonic):
        self.labels = [job.get("label") or job["name"] for job in jobs]
        self.progress, self.clock = progress, clock
        self.stages, self.started, self.finished = {}, {}, set()
        self.lock = threading.Lock()

    def stage(self, index, stage):
        with self.lock:
            if index in self.finished:  # an event that arrived after the result
                return
            self.started.setdefault(index, self.clock())
            self.stages[index] = stage
        self.say(index)

    def finish(self, index, error):
        with self.lock:
            self.stages[index] = "failed" if error is not None else "done"
            self.finished.add(index)
            self.started.setdefault(index, self.clock())
        self.say(index)
        with self.lock:
            self.started.pop(index, None)

    def line(self, index):
        seconds = self.clock() - self.started.get(index, self.clock())
        return (f"candidate {index + 1} of {len(self.labels)} ({self.labels[index]}): "
                f"{self.stages.get(index, 'queued')}, {seconds:.0f} s")

    def say(self, index):
        if self.progress is not None:
            self.progress(self.line(index))

    def tick(self):
        with self.lock:
            running = sorted(self.started)
        for index in running:
            self.say(index)


def _kwargs(job):
    kwargs = {k: v for k, v in job.items() if k not in ("name", "label", "progress")}
    return job["name"], kwargs


def _check(jobs, workers):
    for i, job in enumerate(jobs):
        if not isinstance(job, dict) or not isinstance(job.get("name"), str):
            raise ValueError(f"jobs[{i}] must be a dict of synth's keyword arguments with a block "
                             f"\"name\", not {job!r}")
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int) or workers < 1):
        raise ValueError(f"workers must be a positive integer, not {workers!r}")


def _default_synth():
    from phongfx.explore.synth.fpga import synth

    return synth


class _Job:
    """One job as a Dask task: its flow's stages sent on ``topic``, tagged with its index."""

    def __init__(self, synth, topic):
        self.synth, self.topic = synth, topic

    def __call__(self, item):
        index, job = item
        name, kwargs = _kwargs(job)
        worker_event(self.topic, (index, "started"))
        return self.synth(name, **kwargs, progress=lambda stage: worker_event(self.topic, (index, stage)))


def _in_process(jobs, synth, board, tick):
    """Every job in this process, one after another, a thread ticking beside them."""
    results, stop = [], threading.Event()

    def ticker():
        while not stop.wait(tick):
            board.tick()

    thread = threading.Thread(target=ticker, name="synth_all-ticker", daemon=True)
    thread.start()
    try:
        for index, job in enumerate(jobs):
            name, kwargs = _kwargs(job)
            board.stage(index, "started")
            try:
                results.append(synth(name, **kwargs, progress=lambda stage, i=index: board.stage(i, stage)))
                board.finish(index, None)
            except Exception as error:  # the job's outcome; Ctrl-C is not caught
                results.append(error)
                board.finish(index, error)
    finally:
        stop.set()
        thread.join()
    return results


def synth_all(jobs, *, scheduler=None, workers=None, progress=None, synth=None, tick=TICK_SECONDS):
    """Synthesize every job; returns, in the jobs' order, each result dict or the exception
    its run raised.

    Parameters
    ----------
    jobs : list of dict
        Keyword arguments of :func:`phongfx.explore.synth.fpga.synth` (``config``, ``target``,
        ``device``, ``freq``, ``seed``, ``workdir``) plus ``"name"`` (the block) and
        ``"label"`` (how progress names the candidate; default the name).
    scheduler : str, optional
        A Dask scheduler's address; default a ``LocalCluster`` on this machine.
    workers : int, optional
        Worker processes of the local cluster (default: one per job, at most one per core);
        1 without a ``scheduler`` runs the jobs in this process, one after another, without Dask.
    progress : callable, optional
        ``progress(text)``: a line as each job starts, changes stage and ends, and every
        ``tick`` seconds (:data:`TICK_SECONDS`) one per running job:
        ``candidate i of N (label): <stage>, T s``.
    synth : callable, optional
        Instead of :func:`~phongfx.explore.synth.fpga.synth` (same signature; picklable when
        run on Dask).
    tick : float
        The seconds between two progress lines of a running job (:data:`TICK_SECONDS`).

    Raises
    ------
    ValueError
        For a job without a block name, a bad ``workers``, a scheduler that cannot be reached
        or Dask not installed.
    KeyboardInterrupt
        After cancelling the jobs not finished.
    """
    _check(jobs, workers)
    jobs = list(jobs)
    synth = synth or _default_synth()
    board = _Board(jobs, progress)
    if not jobs:
        return []
    if workers == 1 and scheduler is None:
        return _in_process(jobs, synth, board, tick)
    results = [None] * len(jobs)

    def done(index, value, error):
        results[index] = value if error is None else error
        board.finish(index, error)

    def event(message):
        index, stage = message[1]
        board.stage(index, stage)

    topic = f"phongfx-synth-{uuid.uuid4().hex}"
    workers = workers or (min(len(jobs), os.cpu_count() or 1) if scheduler is None else None)
    run_on_dask(_Job(synth, topic), list(enumerate(jobs)), done, scheduler=scheduler, workers=workers,
                tick=board.tick, every=tick, events=(topic, event))
    return results
