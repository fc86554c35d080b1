"""The compiler's work on several cores gives what it gives on one: the methods' width searches
in forked workers (their measured points journalled here), the witness's fresh chunks drawn and
measured by workers, in order."""

import multiprocessing
import os

import pytest

from phongfx.compiler.compile import scene_domain
from phongfx.explore.compile import search as searches
from phongfx.explore.compile import witness as witnesses
from phongfx.explore.compile import workers
from phongfx.explore.compile.measure import SceneEval
from phongfx.explore.compile.points import DomainPoints
from phongfx.explore.compile.workers import count, fork_map
from phongfx.scene.file import parse_scene
from tests.compiler.test_compile import TORUS
from tests.explore.compile.test_witness import NARROW
from tests.explore.sweep.test_run import alive


def _pid(_):
    return os.getpid()


def test_fork_map_keeps_the_order_and_raises_a_worker_s_error():
    assert fork_map(lambda x: x * x, range(7), 2) == [x * x for x in range(7)]
    assert os.getpid() not in fork_map(_pid, range(4), 2)
    assert fork_map(_pid, range(4), 1) == [os.getpid()] * 4
    with pytest.raises(ValueError, match="item 3"):
        fork_map(lambda x: x if x != 3 else int(f"item {x}"), range(5), 2)
    with pytest.raises(ValueError, match="positive integer"):
        count(0)


def _die(x):
    if x == 2:
        os._exit(3)
    return x


def test_a_worker_that_dies_is_an_error_and_an_early_stop_ends_every_worker():
    with pytest.raises(RuntimeError, match="ended without its result, exit code 3"):
        fork_map(_die, range(5), 2)
    # the consumer of fork_imap stopping while items run: every worker ends (workers under a
    # multiprocessing.Pool outlived their SIGTERM about one exit in 300, and the exit hung)
    for trial in range(60):
        taken = [x for _, x in zip(range(3), workers.fork_imap(lambda x: x * x, range(8), 2))]
        assert taken == [0, 1, 4]
        assert not multiprocessing.active_children()


def _scene(tmp_path, samples):
    spec = parse_scene(TORUS.format(error=1.0, against="phong"), name="tiny")
    scene = SceneEval(spec, journal=tmp_path)
    domain = scene_domain(spec, scene.geometries, samples=samples)
    scene.measure_domain(DomainPoints(spec, domain))
    return scene, domain


def test_a_pending_piece_of_work_runs_beside_this_process_and_gives_its_result():
    import time

    here = os.getpid()
    pending = workers.Pending(_pid, None)
    assert pending.process is not None and pending.result() not in (None, here)
    assert workers.Pending(_pid, None, fork=False).result() == here
    with pytest.raises(ValueError, match="item 4"):
        workers.Pending(lambda x: int(f"item {x}"), 4).result()
    with pytest.raises(RuntimeError, match=r"ended without its result, exit code 3"):
        workers.Pending(_die, 2).result()
    slow = workers.Pending(time.sleep, 60)
    start = time.perf_counter()
    slow.cancel()
    assert time.perf_counter() - start < workers.GRACE + 1 and slow.process.exitcode is not None
    assert not multiprocessing.active_children()


def _aside(_):
    before = os.nice(0)
    workers.step_aside()
    return os.nice(0) - before


def test_a_worker_steps_aside_and_the_process_that_forked_it_never_does():
    # a worker's lower priority is its own; the compile's own process keeps its priority for the
    # rest of its run, searches and witness alike
    here = os.nice(0)
    lowered = min(workers.NICE, 19 - here)  # the lowest priority is 19
    assert fork_map(_aside, range(2), 2) == [lowered] * 2
    assert workers.Pending(_aside, None).result() == lowered
    assert fork_map(_aside, range(2), 1) == [0, 0] and os.nice(0) == here


_BEGUN = _CHECKED = None  # barriers of the spare-core test, inherited by its workers


def _spare(wait):
    """Whether a core is spare once every item has begun, or (``wait``) once the others end."""
    import time

    _BEGUN.wait(10)
    if not wait:
        spare = workers.spare_core()
        _CHECKED.wait(10)  # no item ends before every one has looked
        return spare
    _CHECKED.wait(10)
    deadline = time.monotonic() + 10
    while not workers.spare_core() and time.monotonic() < deadline:
        time.sleep(0.01)
    return workers.spare_core()


def test_a_core_is_spare_in_a_worker_once_fewer_items_run_than_cores(monkeypatch):
    global _BEGUN, _CHECKED
    monkeypatch.setattr(workers, "count", lambda workers=None: 2 if workers is None else workers)
    assert not workers.spare_core()  # not a worker
    # two cores: none spare while three items run; one once the item beside it has ended
    _BEGUN, _CHECKED = multiprocessing.Barrier(3), multiprocessing.Barrier(3)
    assert fork_map(_spare, [False] * 3, 3) == [False] * 3
    _BEGUN, _CHECKED = multiprocessing.Barrier(2), multiprocessing.Barrier(2)
    assert fork_map(_spare, [False, True], 2) == [False, True]


def _spare_once_waited(_):
    import time

    early = workers.spare_core()
    _CHECKED.wait(10)  # the process that began it waits for it only after this look
    deadline = time.monotonic() + 10
    while not workers.spare_core() and time.monotonic() < deadline:
        time.sleep(0.01)
    return early, workers.spare_core()


def test_a_pending_piece_of_work_has_a_spare_core_once_it_is_waited_for(monkeypatch):
    global _CHECKED
    monkeypatch.setattr(workers, "count", lambda workers=None: 2 if workers is None else workers)
    _CHECKED = multiprocessing.Barrier(2)
    pending = workers.Pending(_spare_once_waited, None)
    _CHECKED.wait(10)
    assert pending.result() == (False, True)
    assert not workers.spare_core()


def _twin_pids(items):
    twin = workers.Twin(lambda x: (os.getpid(), x * x))
    try:
        twin.send(items[0])
        mine = (os.getpid(), items[1] * items[1])
        theirs = twin.result()
        twin.send("not a number")
        with pytest.raises(TypeError):
            twin.result()
        return mine, theirs
    finally:
        twin.close()


def test_a_twin_computes_beside_its_worker_and_raises_its_errors_there():
    (me, mine), (twin, theirs) = _twin_pids((3, 4))
    assert (mine, theirs) == (16, 9) and me == os.getpid() != twin
    # a worker (daemonic: no multiprocessing children) has a twin of its own
    (worker, _), (its_twin, _) = fork_map(_twin_pids, [(1, 2), (5, 6)], 2)[0]
    assert len({worker, its_twin, os.getpid()}) == 3
    assert not multiprocessing.active_children()


def _inner_map(_):
    return list(workers.fork_imap(lambda x: (os.getpid(), x * x), range(5), 1))


def test_a_worker_with_a_spare_core_shares_its_own_items_with_a_twin(monkeypatch):
    monkeypatch.setattr(workers, "spare_core", lambda: True)
    # here (no worker: workers=1 runs in this process) the twin is used as in a worker
    out = _inner_map(None)
    assert [x for _, x in out] == [0, 1, 4, 9, 16]
    assert {pid for pid, _ in out[::2]} == {os.getpid()} and os.getpid() not in {pid for pid, _ in out[1::2]}
    (inside,) = fork_map(_inner_map, [None, None], 2)[:1]
    assert [x for _, x in inside] == [0, 1, 4, 9, 16] and len({pid for pid, _ in inside}) == 2
    with pytest.raises(ValueError, match="item 3"):
        list(workers.fork_imap(lambda x: x if x != 3 else int(f"item {x}"), range(5), 1))
    assert not multiprocessing.active_children()
    monkeypatch.setattr(workers, "spare_core", lambda: False)
    assert {pid for pid, _ in _inner_map(None)} == {os.getpid()}


def _half_built(seconds):
    import time

    from amaranth.hdl import Module

    module = Module()  # never elaborated: collected at the end, Amaranth warns of it
    time.sleep(seconds)
    return module


def test_an_interrupted_pending_piece_of_work_ends_without_a_word(capfd):
    """Ctrl-C reaches the forked worker too: it ends with 130 and writes nothing (the parent
    prints the one line)."""
    import signal
    import time

    pending = workers.Pending(_half_built, 30)
    time.sleep(0.5)
    os.kill(pending.process.pid, signal.SIGINT)
    with pytest.raises(RuntimeError, match="exit code 130"):
        pending.result()
    assert capfd.readouterr().err == ""


def test_the_width_searches_in_workers_are_those_in_this_process(tmp_path, monkeypatch):
    monkeypatch.setattr(searches, "MIN_POINTS", 1000)
    methods = ["fig7", "conventional"]
    alone, _ = _scene(tmp_path / "alone", 3000)
    one = searches.search_all(alone, methods, workers=1)
    forked, _ = _scene(tmp_path / "forked", 3000)
    two = searches.search_all(forked, methods, workers=2)
    assert two == one and one["fig7"][0]["feasible"] and one["conventional"][0]["feasible"]
    assert forked.cache == alone.cache and forked.failed == alone.failed
    again, _ = _scene(tmp_path / "forked", 3000)
    assert again.resumed == forked.points_measured > 5 and again.cache == forked.cache


def test_the_witness_of_forked_chunks_is_that_of_one_process(tmp_path, monkeypatch):
    monkeypatch.setattr(witnesses, "MIN_POINTS", 1000)
    monkeypatch.setattr(witnesses, "CHUNK", 1 << 16)  # the sampler's, as the chunks are drawn
    scene, domain = _scene(tmp_path, 2000)
    spec = scene.spec
    kwargs = dict(samples=140_000, analysis=scene.analysis, rounds=2)
    one = witnesses.search("fig7", NARROW, spec, domain, workers=1, **kwargs)
    two = witnesses.search("fig7", NARROW, spec, domain, workers=2, **kwargs)
    one.pop("seconds"), two.pop("seconds")
    assert two == one and one["error_levels"] >= 2 and workers.MIN_POINTS == 1 << 17


def test_workers_end_when_their_parent_is_killed(tmp_path):
    """A parent killed outright (SIGKILL: no clean-up of its own) leaves no worker waiting."""
    import signal
    import subprocess
    import sys
    import time

    script = ("import os, sys, time\n"
              "from phongfx.explore.compile.workers import fork_imap\n"
              "def job(x):\n"
              "    open(os.path.join(sys.argv[1], f'{os.getpid()}.pid'), 'w').close()\n"
              "    return x\n"
              "for x in fork_imap(job, range(2), 2):\n"
              "    time.sleep(60)\n")
    parent = subprocess.Popen([sys.executable, "-c", script, str(tmp_path)])
    deadline = time.monotonic() + 30
    while len(list(tmp_path.glob("*.pid"))) < 2 and time.monotonic() < deadline:
        time.sleep(0.05)
    pids = [int(p.stem) for p in tmp_path.glob("*.pid")]
    assert len(pids) == 2
    parent.send_signal(signal.SIGKILL)
    parent.wait()
    deadline = time.monotonic() + 10
    while any(alive(pid) for pid in pids) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert not any(alive(pid) for pid in pids)

