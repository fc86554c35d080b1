"""Parallel synthesis (phongfx.explore.synth.parallel): results in the jobs' order, failures
returned, progress that ticks while a job sleeps, in this process and on a Dask local cluster,
and a real pair of small syntheses giving the same numbers in parallel as one after another."""

import os
import re
import signal
import sys
import time

import pytest

from phongfx.explore.synth.parallel import synth_all


def fake_synth(name, *, seconds=0.0, fail=False, progress=None, **kwargs):
    """Stands for :func:`~phongfx.explore.synth.fpga.synth`: one stage, a sleep, a result."""
    progress("sleeping")
    time.sleep(seconds)
    if fail:
        raise RuntimeError(f"{name} failed on purpose")
    return {"block": name, "seconds": seconds, **kwargs}


@pytest.fixture
def by_value():
    """The fake pickled by value, so Dask's worker processes need not import this test file."""
    import cloudpickle

    module = sys.modules[fake_synth.__module__]
    cloudpickle.register_pickle_by_value(module)
    yield
    cloudpickle.unregister_pickle_by_value(module)


JOBS = [{"name": "lirp", "label": "slow one", "seconds": 1.6, "seed": 3},
        {"name": "shape", "label": "broken", "fail": True},
        {"name": "root", "seconds": 0.0}]


def _elapsed(lines, label):
    """The T of every "candidate i of N (label): sleeping, T s" line, in order."""
    pattern = re.compile(rf"^candidate \d of 3 \({re.escape(label)}\): sleeping, (\d+) s$")
    return [int(m.group(1)) for m in map(pattern.match, lines) if m]


def _check(results, lines):
    assert results[0] == {"block": "lirp", "seconds": 1.6, "seed": 3}
    assert isinstance(results[1], RuntimeError) and str(results[1]) == "shape failed on purpose"
    assert results[2] == {"block": "root", "seconds": 0.0}
    ticks = _elapsed(lines, "slow one")
    assert len(ticks) >= 4, lines  # the stage line, then a tick every 0.25 s of the 1.6 s sleep
    assert ticks == sorted(ticks) and ticks[-1] >= 1
    assert "candidate 2 of 3 (broken): failed, 0 s" in lines
    assert any(re.match(r"^candidate 3 of 3 \(root\): done, \d+ s$", line) for line in lines)
    assert any(re.match(r"^candidate 1 of 3 \(slow one\): done, [12] s$", line) for line in lines)


def test_in_process_ticks_while_a_job_sleeps():
    lines = []
    results = synth_all(JOBS, workers=1, progress=lines.append, synth=fake_synth, tick=0.25)
    _check(results, lines)


def test_dask_local_cluster_forwards_stages_and_ticks(by_value):
    lines = []
    results = synth_all(JOBS, workers=2, progress=lines.append, synth=fake_synth, tick=0.25)
    _check(results, lines)


def test_no_jobs_and_bad_arguments():
    assert synth_all([], synth=fake_synth) == []
    with pytest.raises(ValueError, match=r"^jobs\[0\] must be a dict of synth's keyword arguments with a "
                                         r"block \"name\", not \{'label': 'x'\}$"):
        synth_all([{"label": "x"}], synth=fake_synth)
    with pytest.raises(ValueError, match=r"^workers must be a positive integer, not 0$"):
        synth_all(JOBS, workers=0, synth=fake_synth)


def test_unreachable_scheduler_is_a_clear_error():
    with pytest.raises(ValueError, match=r"^cannot reach the Dask scheduler 'tcp://127.0.0.1:9': "):
        synth_all(JOBS, scheduler="tcp://127.0.0.1:9", synth=fake_synth)


@pytest.mark.needs_yosys
def test_real_pair_in_parallel_matches_serial(tmp_path):
    jobs = [{"name": "lirp", "label": f"lirp seed {seed}", "target": "ecp5", "seed": seed}
            for seed in (1, 2)]
    serial = synth_all([{**job, "workdir": tmp_path / "serial"} for job in jobs], workers=1)
    lines = []
    parallel = synth_all([{**job, "workdir": tmp_path / "parallel"} for job in jobs], workers=2,
                         progress=lines.append)
    keys = ("lut4", "ff", "carry", "dsp", "fmax_mhz", "latency", "block", "device")
    for one, other in zip(serial, parallel):
        assert not one["cached"] and not other["cached"]
        assert {k: one[k] for k in keys} == {k: other[k] for k in keys}
    assert serial[0]["lut4"] > 0 and serial[0]["fmax_mhz"] > 0
    stages = {m.group(1) for m in map(re.compile(r"^candidate \d of 2 \(lirp seed \d\): (\w+), \d+ s$").match,
                                      lines) if m}
    assert {"verilog", "yosys", "nextpnr", "done"} <= stages


def _interrupt_on_tick(line):
    """Ctrl-C, as a terminal sends it (to the main thread), once a job has slept a second."""
    if "sleeping" in line and not line.endswith(" 0 s"):
        os.kill(os.getpid(), signal.SIGINT)


@pytest.fixture
def interruptible():
    """SIGINT at Python's own handler and unblocked in this thread for the test: an xdist
    worker may have inherited it ignored or blocked (a pool or a Dask nanny of an earlier
    test in the same worker), and then the Ctrl-C the test sends would never arrive."""
    handler = signal.signal(signal.SIGINT, signal.default_int_handler)
    mask = signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT})
    yield
    signal.pthread_sigmask(signal.SIG_SETMASK, mask)
    signal.signal(signal.SIGINT, handler)


@pytest.mark.parametrize("workers", [1, 2])
def test_ctrl_c_cancels_the_jobs(workers, by_value, interruptible):
    jobs = [{"name": "lirp", "seconds": 3.0}, {"name": "shape", "seconds": 60.0}, {"name": "root", "seconds": 60.0}]
    start = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        synth_all(jobs, workers=workers, progress=_interrupt_on_tick, synth=fake_synth, tick=0.25)
    assert time.monotonic() - start < 45  # the 60 s jobs were not waited for
