"""The compiler's independent pieces of work on the machine's cores: forked workers, ordered results.

The width searches of different methods share nothing but the scene and its domain sample,
and the witness search's chunks of fresh points are drawn each from its own seeded
generator: each piece gives the same result in any process, so :func:`fork_map` runs them
in worker processes forked from this one (which inherit the scene, the sample and the
function without pickling them) and returns the results in the order of the items, the
same as ``[function(item) for item in items]``.  Only the items go out and the results come
back (pickled), each worker on a pipe of its own.

How many workers: ``workers`` as given, else the cores this process may run on
(:func:`count`); one, or a single item, runs in this process.  Small work (the tests'
samples) is not worth a fork: the callers go parallel only from :data:`MIN_POINTS` points.

:class:`Pending` is one piece of work begun in a forked process now and waited for later,
while this process does another (the chosen design's RTL check simulator during its witness);
once this process waits for it, it has a spare core.
:class:`Twin` is a copy of a worker that shares its work item by item while a core is idle
(:func:`spare_core`): the last width search running alone bounds half of each round's boxes
there (:func:`phongfx.certify.branch.bound_boxes`), measures half of each width point's
domain sample (:meth:`phongfx.explore.compile.points.DomainPoints.error`), and prices every
other of its designs (:func:`fork_imap` inside a worker).
"""

import contextlib
import multiprocessing
import multiprocessing.connection
import os
import signal

__all__ = ["GRACE", "MIN_POINTS", "NICE", "count", "spare_core", "step_aside", "fork_imap", "fork_map", "Pending",
           "Twin"]

#: Domain points from which a measurement or a search is worth worker processes.
MIN_POINTS = 1 << 17

_JOB = None  # the function of a worker being started (:func:`_start`), inherited by its fork


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
_RUNNING = None  # in a worker of fork_imap: how many of its workers are running an item


def spare_core():
    """Whether this process may take one more core now: it is a worker of :func:`fork_imap`
    and fewer of its workers are running an item than this process has cores (the others have
    ended: the last ones run alone), or it computes a :class:`Pending` that the process which
    began it waits for (on a machine of two cores or more).  False anywhere else."""
    return _RUNNING is not None and _RUNNING.value < count()

#: How much a worker lowers its priority when it steps aside (:func:`step_aside`).
NICE = 10


def step_aside():
    """Lower this process's priority by :data:`NICE` when it is a forked worker of
    :func:`fork_imap` or a :class:`Pending` (never the process that forked it, whose priority
    would stay low for the rest of its run): work that is not likely to be the last to end
    yields the cores to work that is, the cores being shared by weight, and what each computes
    is the same.  Nothing happens where the priority cannot be lowered."""
    if _is_worker():
        try:
            os.nice(NICE)
        except OSError:
            pass


#: Seconds a worker is given to end after SIGTERM before it is killed.
GRACE = 5


def _call(item):
    global _IN_JOB
    _IN_JOB = True
    _count(1)
    try:
        return _JOB(item)
    except KeyboardInterrupt:  # cleaned up on its way here: the worker ends quietly
        raise SystemExit(130) from None
    finally:
        _IN_JOB = False
        _count(-1)


def _count(step):
    if _RUNNING is not None:
        with _RUNNING.get_lock():
            _RUNNING.value += step


def _interrupted(signum, frame):
    if not _IN_JOB:
        os._exit(130)  # nothing half-made: no traceback, no cleanup needed
    raise KeyboardInterrupt


def _serve(link):
    # this process, interrupted (Ctrl-C), ends its workers by SIGTERM; a terminal's Ctrl-C
    # sends them SIGINT too: either, inside an item, is a KeyboardInterrupt there, so the
    # half-made cache entries of the worker are removed as they would be here
    signal.signal(signal.SIGTERM, _interrupted)
    signal.signal(signal.SIGINT, _interrupted)
    # a killed parent closes no pipe of a worker forked before another (whose fork holds a copy
    # of the first one's end): its sentinel ends the wait instead of leaving the worker behind
    waited = [link, multiprocessing.parent_process().sentinel]
    while True:
        if link not in multiprocessing.connection.wait(waited):
            return
        try:
            message = link.recv()
        except EOFError:  # this process is gone
            return
        if message is None:
            return
        index, item = message
        try:
            outcome = (True, _call(item))
        except SystemExit as stop:
            # interrupted, its half-made cache entries removed on the way here: it ends now,
            # before the half-built objects its traceback holds are collected (Amaranth warns of
            # each unelaborated one on stderr, where this process prints its one line)
            os._exit(stop.code if isinstance(stop.code, int) else 1)
        except Exception as error:
            outcome = (False, error)
        try:
            link.send((index, outcome))
        except Exception as error:  # a result or an error that does not pickle
            link.send((index, (False, RuntimeError(f"{type(error).__name__}: {error}"))))


def _is_worker():
    """Whether this process is a worker of :func:`fork_imap` or a :class:`Pending` (daemonic)."""
    return multiprocessing.current_process().daemon


def _context():
    """The ``fork`` context, or None where this process forks no workers (the platform cannot,
    or this is a worker: a worker has no workers of its own)."""
    if "fork" not in multiprocessing.get_all_start_methods() or _is_worker():
        return None
    return multiprocessing.get_context("fork")


def _start(context, function):
    """``(process, link)``: a worker serving ``function`` (inherited by the fork) on a pipe of its own."""
    global _JOB
    before, _JOB = _JOB, function
    try:
        here, there = context.Pipe()
        process = context.Process(target=_serve, args=(there,), daemon=True)
        process.start()
    finally:
        _JOB = before
    there.close()
    return process, here


def _lost(process):
    """The error of a worker that ended without its result."""
    process.join(GRACE)
    return RuntimeError(f"a compile worker (pid {process.pid}) ended without its result, "
                        f"exit code {process.exitcode}")


def _stop(processes, links, finished):
    # each worker has its own pipe, so no worker waits on a lock another holds (a shared
    # queue's read lock and a SIGTERM that lands just before a blocking wait made
    # multiprocessing.Pool's exit hang one time in a few hundred); finished workers end
    # on None, others on SIGTERM, and one that outlives it by GRACE seconds is killed
    for process, link in zip(processes, links):
        try:
            if finished:
                link.send(None)
            else:
                process.terminate()
        except (OSError, ValueError):
            pass
    for process in processes:
        process.join(GRACE)
        if process.exitcode is None:
            process.kill()
            process.join()
    for link in links:
        link.close()


def fork_imap(function, items, workers=None):
    """``function(item)`` of each of ``items``, in order, as each is ready, computed by up to
    :func:`count` ``(workers)`` forked processes (module docstring); an exception in a
    worker is raised here, and a worker that dies without its result is a RuntimeError.
    Inside a worker, which has no workers of its own, a :class:`Twin` computes every other
    item while a core is idle (:func:`spare_core`)."""
    items = list(items)
    workers = min(count(workers), len(items))
    context = _context() if workers > 1 else None
    if context is None:
        yield from _beside_twin(function, items)
        return
    processes, links, finished = [], [], False
    try:
        with _counting(context, 0):  # no item runs yet
            for _ in range(workers):
                process, link = _start(context, function)
                processes.append(process)
                links.append(link)
        yield from _ordered(items, processes, links)
        finished = True
    finally:
        _stop(processes, links, finished)


@contextlib.contextmanager
def _counting(context, running):
    """Processes forked inside inherit a count of running items (beginning at ``running``)
    for :func:`spare_core`; this process keeps its own; yields the count."""
    global _RUNNING
    before, _RUNNING = _RUNNING, context.Value("i", running)
    try:
        yield _RUNNING
    finally:
        _RUNNING = before


def _beside_twin(function, items):
    # the last width search's pricing (two designs, seconds of elaboration each) ran alone
    # with a core idle: the twin takes the odd items, this process the even ones
    if len(items) < 2 or not spare_core():
        yield from (function(item) for item in items)
        return
    twin = Twin(function)
    try:
        for index in range(0, len(items), 2):
            pair = index + 1 < len(items)
            if pair:
                twin.send(items[index + 1])
            yield function(items[index])
            if pair:
                yield twin.result()
    finally:
        twin.close()


def _ordered(items, processes, links):
    # items handed out one at a time to whichever worker is free; results yielded in order
    queue, busy, done, ready = iter(enumerate(items)), set(), {}, 0

    def hand(link):
        job = next(queue, None)
        if job is not None:
            link.send(job)
            busy.add(link)

    for link in links:
        hand(link)
    while True:
        while ready in done:
            ok, value = done.pop(ready)
            if not ok:
                raise value
            yield value
            ready += 1
        if ready == len(items):
            return
        for link in multiprocessing.connection.wait(list(busy)):
            try:
                index, outcome = link.recv()
            except EOFError:
                raise _lost(processes[links.index(link)]) from None
            busy.discard(link)
            done[index] = outcome
            hand(link)


class Pending:
    """``function(item)``, begun now in a forked worker (with ``fork`` True and where this
    process forks workers, else computed here when asked for); :meth:`result` waits for it and
    gives it (an exception in the worker is raised here, a worker that dies without its result
    is a RuntimeError), :meth:`cancel` ends it unfinished, and does nothing once it has ended."""

    def __init__(self, function, item, fork=True):
        self.function, self.item, self.process, self.link, self.ended = function, item, None, None, False
        context = _context() if fork else None
        if context is not None:
            # this process counts as running until it waits in result(): the work then has a
            # spare core (:func:`spare_core`), as the last width search has
            with _counting(context, 1) as self.running:
                self.process, self.link = _start(context, function)
            self.link.send((0, item))

    def result(self):
        if self.process is None:
            return self.function(self.item)
        try:
            with self.running.get_lock():
                self.running.value -= 1
            _, (ok, value) = self.link.recv()
        except EOFError:
            raise _lost(self.process) from None
        except BaseException:  # interrupted while waiting: the worker too
            self.cancel()
            raise
        self._end(True)
        if not ok:
            raise value
        return value

    def cancel(self):
        self._end(False)

    def _end(self, finished):
        if self.process is not None and not self.ended:
            self.ended = True
            _stop([self.process], [self.link], finished)


def fork_map(function, items, workers=None):
    """``[function(item) for item in items]`` by :func:`fork_imap`."""
    return list(fork_imap(function, items, workers))


class Twin:
    """A copy of this process, forked now, that computes ``function(item)`` for each item
    :meth:`send` gives it while this process computes something else; :meth:`result` waits
    for it (an exception there is raised here), :meth:`close` ends the copy.  ``os.fork``, not a
    ``multiprocessing`` child, since a worker (daemonic) may not have those; the copy ends when
    it reads the end of its pipe, or is interrupted, and never returns into this process's
    code."""

    def __init__(self, function):
        self.link, there = multiprocessing.Pipe()
        self.pid = os.fork()
        if self.pid == 0:  # the copy
            self.link.close()
            status = 0
            try:
                while True:
                    item = there.recv()
                    try:
                        outcome = (True, function(item))
                    except Exception as error:
                        outcome = (False, error)
                    there.send(outcome)
            except EOFError:  # this process is done with it, or gone
                pass
            except BaseException:  # interrupted, or its pipe broken
                status = 1
            finally:
                os._exit(status)
        there.close()

    def send(self, item):
        self.link.send(item)

    def result(self):
        try:
            ok, value = self.link.recv()
        except EOFError:
            raise RuntimeError(f"a twin of a compile worker (pid {self.pid}) ended without its result") from None
        if not ok:
            raise value
        return value

    def close(self):
        self.link.close()
        try:
            os.kill(self.pid, signal.SIGKILL)  # idle, or its item is no longer wanted
        except ProcessLookupError:
            pass
        os.waitpid(self.pid, 0)
