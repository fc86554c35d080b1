"""The compiler's independent pieces of work on the machine's cores: forked workers, ordered results.

The width searches of different methods share nothing but the scene and its domain sample,
and the witness search's chunks of fresh points are drawn each from its own seeded
generator: each piece gives the same result in any process, so :func:`fork_map` runs them
in worker processes forked from this one (which inherit the scene, the sample and the
function without pickling them) and returns the results in the order of the items, the
same as ``[function(item) for item in items]``.  Only the results travel back (pickled).

How many workers: ``workers`` as given, else the cores this process may run on
(:func:`count`); one, or a single item, runs in this process.  Small work (the tests'
samples) is not worth a fork: the callers go parallel only from :data:`MIN_POINTS` points.
"""

import multiprocessing
import os
import signal

__all__ = ["MIN_POINTS", "count", "fork_imap", "fork_map"]

#: Domain points from which a measurement or a search is worth worker processes.
MIN_POINTS = 1 << 17

_JOB = None  # the function of the running fork_map, inherited by its forked workers


def count(workers=None):
    """Worker processes to use: ``workers`` (a positive integer) when given, else the cores
    this process may run on."""
    if workers is not None:
        if isinstance(workers, bool) or not isinstance(workers, int) or workers < 1:
            raise ValueError(f"workers must be a positive integer, not {workers!r}")
        return workers
    try:
        return max(len(os.sched_getaffinity(0)), 1)
    except AttributeError:  # no affinity on this platform
        return os.cpu_count() or 1


_IN_JOB = False  # a worker is running an item (not waiting for one)


def _call(item):
    global _IN_JOB
    _IN_JOB = True
    try:
        return _JOB(item)
    except KeyboardInterrupt:  # cleaned up on its way here: the worker ends quietly
        raise SystemExit(130) from None
    finally:
        _IN_JOB = False


def _interrupted(signum, frame):
    if not _IN_JOB:
        os._exit(130)  # nothing half-made: no traceback, no cleanup needed
    raise KeyboardInterrupt


def _worker_start():
    # this process, interrupted (Ctrl-C), ends the pool's workers by SIGTERM; a terminal's
    # Ctrl-C sends them SIGINT too: either, inside an item, is a KeyboardInterrupt there, so
    # the half-made cache entries of the worker are removed as they would be here
    signal.signal(signal.SIGTERM, _interrupted)
    signal.signal(signal.SIGINT, _interrupted)


def fork_imap(function, items, workers=None):
    """``function(item)`` of each of ``items``, in order, as each is ready, computed by up to
    :func:`count` ``(workers)`` forked processes (module docstring); an exception in a
    worker is raised here."""
    global _JOB
    items = list(items)
    workers = min(count(workers), len(items))
    if (workers <= 1 or "fork" not in multiprocessing.get_all_start_methods()
            or multiprocessing.current_process().daemon):  # a worker has no workers of its own
        yield from (function(item) for item in items)
        return
    _JOB = function
    try:
        with multiprocessing.get_context("fork").Pool(workers, initializer=_worker_start) as pool:
            yield from pool.imap(_call, items)
    finally:
        _JOB = None


def fork_map(function, items, workers=None):
    """``[function(item) for item in items]`` by :func:`fork_imap`."""
    return list(fork_imap(function, items, workers))
