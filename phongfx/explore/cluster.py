"""Independent jobs on Dask: a local cluster, or a running scheduler's address.

The sweeps (:mod:`phongfx.explore.sweep.run`, ``phongfx sweep --scheduler``) and the parallel
synthesis of candidates (:mod:`phongfx.explore.synth.parallel`) hand a list of independent jobs
to Dask the same way, through :func:`run_on_dask`: one client (a ``LocalCluster`` of
single-threaded worker processes, each job owning its process as a synthesis run needs, or the
scheduler at an address), every job submitted at once, each outcome handed back as it finishes,
and Ctrl-C cancelling what has not finished.  A job tells the caller where it is by
:func:`worker_event` (a Dask event on a topic, pushed to the client, so it works across
machines where a shared file would not); :func:`run_on_dask` subscribes the caller's handler.
"""

import contextlib
import logging
import time

__all__ = ["LOCAL", "dask_client", "run_on_dask", "worker_event"]

#: The ``scheduler`` that means a ``LocalCluster`` on this machine.
LOCAL = "local"
#: Seconds between two looks at the jobs' states.
_POLL = 0.1


@contextlib.contextmanager
def dask_client(scheduler=LOCAL, workers=None):
    """A Dask client for ``scheduler``: ``"local"`` (or None) a ``LocalCluster`` of
    ``workers`` single-threaded processes (default: Dask's, one per core), else the address of
    a running scheduler.  Closed (and the local cluster's processes ended) on leaving."""
    scheduler = scheduler or LOCAL
    try:
        from dask.distributed import Client, LocalCluster
    except ImportError:
        raise ValueError(f"scheduler {scheduler!r} needs Dask, which is not installed: "
                         f"pip install phongfx[cluster]") from None
    cluster = None
    try:
        if scheduler == LOCAL:
            cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                   dashboard_address=None, silence_logs=logging.ERROR)
            client = Client(cluster)
        else:
            try:
                client = Client(scheduler, timeout=10)
            except OSError as error:
                raise ValueError(f"cannot reach the Dask scheduler {scheduler!r}: {error}") from None
        try:
            yield client
        finally:
            client.close()
    finally:
        if cluster is not None:
            cluster.close()


def _outcome(future):
    """``(value, None)`` of a finished future, or ``(None, the exception it raised)``
    (a cancelled job's too)."""
    try:
        return future.result(), None
    except (KeyboardInterrupt, SystemExit):
        raise
    except BaseException as error:  # noqa: BLE001 - Dask's CancelledError is a BaseException
        return None, error


def run_on_dask(function, items, done, *, scheduler=LOCAL, workers=None, tick=None, every=1.0, events=None):
    """Run ``function(item)`` for every item of ``items`` on Dask (:func:`dask_client`).

    ``done(index, value, error)`` is called in this process as each job finishes, in the
    order they finish: ``error`` None and ``value`` what the job returned, or ``value`` None
    and ``error`` the exception it raised.  ``tick()``, when given, is called every ``every``
    seconds while jobs run; ``events``, ``(topic, handler)``, subscribes ``handler((time,
    message))`` to what jobs send by :func:`worker_event` on ``topic``.  Ctrl-C cancels every
    job not finished and is raised again.
    """
    with dask_client(scheduler, workers) as client:
        if events is not None:
            client.subscribe_topic(*events)
        futures = [client.submit(function, item, pure=False) for item in items]
        pending = dict(enumerate(futures))
        last = time.monotonic()
        try:
            while pending:
                finished = [index for index, future in pending.items() if future.done()]
                for index in finished:
                    done(index, *_outcome(pending.pop(index)))
                if tick is not None and time.monotonic() - last >= every:
                    last = time.monotonic()
                    tick()
                if pending and not finished:
                    time.sleep(_POLL)
        except KeyboardInterrupt:
            client.cancel(futures)
            raise
        finally:
            if events is not None:
                client.unsubscribe_topic(events[0])


def worker_event(topic, message):
    """Send ``message`` (picklable) on ``topic`` from inside a Dask job, to the handler
    :func:`run_on_dask` subscribed; nothing outside a Dask worker."""
    from distributed import get_worker

    try:
        worker = get_worker()
    except ValueError:  # not on a worker
        return
    worker.log_event(topic, message)
