"""The harness's stream mode: back-pressure (``stalls``) and a reset (``reset_at``).

A correct :class:`~phongfx.hdl.handshake.Handshake` passes with and without a reset on
both stream back ends, which report the same run cycle for cycle; deliberately broken
wrappers (one whose pipeline ignores ``o.ready``, one that leaves its valid pipeline
ungated, one that ignores the reset) and a valid pipeline longer than declared are caught
at the cycle the plan predicts; the checker's own accounting (nothing lost, nothing
repeated) is pinned down on a Python model of a pipeline.
"""

import dataclasses
import re

import numpy as np
import pytest
from amaranth.hdl import ClockDomain, ClockSignal, DomainRenamer, EnableInserter, Module, Signal

from phongfx.core.registry import get_block
from phongfx.hdl.handshake import Handshake
from phongfx.hdl.lirp import Lirp
from phongfx.sim.harness import (BACKENDS, IDLE, LOST, PAYLOAD, READY, RESET, STREAM_BACKENDS, VALID,
                                 StreamChecker, check, plan_stream, restart_points)

LIRP = get_block("lirp")
TIMING = "counted in cycles where the pipeline moves"


@pytest.fixture(params=STREAM_BACKENDS)
def stream_backend(request):
    """The stream tests' back ends (the Verilator one marked at collection, in conftest)."""
    return request.param


def _inputs(count=120, seed=3):
    """A seeded sample of the LIRP's test vectors, in stimulus order."""
    every = LIRP.stimulus(count=200, seed=seed)
    pick = np.sort(np.random.default_rng(seed).choice(len(every["a"]), count, replace=False))
    return {name: value[pick] for name, value in every.items()}


def _wire(m, wrapper, enable):
    """The connections every Handshake makes, around an enable the caller drives."""
    block = wrapper.block
    m.d.comb += [
        wrapper.i.ready.eq(enable),
        block.i.valid.eq(wrapper.i.valid),
        block.i.payload.eq(wrapper.i.payload),
        wrapper.o.payload.eq(block.o.payload),
    ]


class IgnoresReady(Handshake):
    """Never gates its pipeline: a valid output not taken is overwritten at the next edge.
    Its ``i.ready`` is honest (always 1), so only the stall checks can see the bug."""

    def elaborate(self, platform):
        m = Module()
        m.submodules.block = self.block
        _wire(m, self, 1)
        m.d.comb += self.o.valid.eq(self.block.o.valid)
        return m


class UngatedValid(Handshake):
    """Gates the data path but not its own valid pipeline, which moves on every clock."""

    def elaborate(self, platform):
        m = Module()
        enable = Signal()
        m.submodules.block = EnableInserter(enable)(self.block)
        valid = self.i.valid & enable
        for stage in range(self.latency):
            register = Signal(name=f"valid{stage}")
            m.d.sync += register.eq(valid)
            valid = register
        m.d.comb += [enable.eq(self.o.ready | ~valid), self.o.valid.eq(valid)]
        _wire(m, self, enable)
        return m


class ForgetsReset(Handshake):
    """Runs the block in a clock domain without a reset: a reset leaves what was in flight."""

    def elaborate(self, platform):
        m = Module()
        m.domains.free = ClockDomain("free", reset_less=True, local=True)
        m.d.comb += ClockSignal("free").eq(ClockSignal("sync"))
        enable = Signal()
        m.submodules.block = DomainRenamer("free")(EnableInserter(enable)(self.block))
        m.d.comb += [enable.eq(self.o.ready | ~self.o.valid), self.o.valid.eq(self.block.o.valid)]
        _wire(m, self, enable)
        return m


class LateValidLirp(Lirp):
    """Declares latency 2 but builds a 3-stage valid pipeline (as in test_harness.py)."""

    def elaborate(self, platform):
        self.latency = 3
        try:
            return super().elaborate(platform)
        finally:
            del self.latency


def _first_stall(plan, start):
    """The first cycle from ``start`` on whose ``o.ready`` is low."""
    return start + int(np.flatnonzero(~plan.control[start:] & READY)[0])


# ---------------------------------------------------------------- the plan

def test_plan_is_seeded_and_extends_with_the_run():
    short = plan_stream(100, 2, 30, stalls=0.3, bubbles=0.2, seed=7)
    again = plan_stream(100, 2, 30, stalls=0.3, bubbles=0.2, seed=7)
    long = plan_stream(1000, 2, 30, stalls=0.3, bubbles=0.2, seed=7)
    np.testing.assert_array_equal(short.control, again.control)
    np.testing.assert_array_equal(long.control[:short.limit], short.control)
    assert short.junk == long.junk and all(0 <= j < 1 << 30 for j in short.junk)
    assert not np.array_equal(short.control, plan_stream(100, 2, 30, stalls=0.3, bubbles=0.2, seed=8).control)
    stalled = np.mean(~long.control & READY)
    idle = np.mean(long.control & IDLE) / IDLE
    assert 0.27 < stalled < 0.33 and 0.17 < idle < 0.23
    assert not np.any(long.control & RESET)


def test_plan_resets_and_repeats_a_pattern():
    plan = plan_stream(50, 3, 8, stalls=[False, True, True], reset_at=20, reset_cycles=3)
    assert plan.control[:6].tolist() == [READY, 0, 0, READY, 0, 0]
    assert np.flatnonzero(plan.control & RESET).tolist() == [20, 21, 22]
    assert plan.quiet_from == 23 and plan.drain == 5
    assert plan.resume.tolist() == list(range(50))
    # 50 vectors at one cycle in three: the limit leaves room for twice that
    assert plan.limit > 2 * 150


@pytest.mark.parametrize("kwargs, message", [
    (dict(stalls=1.0), r"^stalls must be a probability in 0\.\.1 \(excluding 1\) or a pattern"),
    (dict(stalls=-0.1), r"^stalls must be a probability"),
    (dict(stalls=[True, True]), r"^a stall pattern must be a non-empty sequence of booleans"),
    (dict(stalls=[]), r"^a stall pattern must be a non-empty sequence of booleans"),
    (dict(bubbles=1), r"^bubbles must be a probability"),
    (dict(reset_at=-1), r"^reset_at must be a cycle number"),
    (dict(reset_at=2.5), r"^reset_at must be a cycle number"),
    (dict(reset_at=3, reset_cycles=0), r"^reset_cycles must be a positive integer, not 0$"),
])
def test_plan_refuses_bad_arguments(kwargs, message):
    with pytest.raises(ValueError, match=message):
        plan_stream(10, 2, 8, **kwargs)


def test_scanline_blocks_resume_from_an_init():
    euler = get_block("euler")
    inputs = euler.stimulus(count=50, seed=1)
    points = restart_points(euler.config, inputs)
    assert points[0] and np.array_equal(points[1:], inputs["init"][1:] != 0)
    plan = plan_stream(len(points), 1, 8, reset_at=5, restarts=points)
    starts = np.flatnonzero(points)
    k = int(starts[3]) + 2  # inside the fourth scanline
    assert plan.resume[k] == starts[3] and plan.resume[starts[3]] == starts[3]
    assert restart_points(LIRP.config, _inputs()) is None


# ---------------------------------------------------------------- the checker, on a Python pipeline

def _model_run(plan, packed_in, latency, fault=None):
    """Run a StreamChecker against an ideal Handshake pipeline in Python (``out = 3 * in``);
    ``fault(cycle, o_valid, o_payload)`` may change what the pipeline shows."""
    checker = StreamChecker(plan, packed_in, [3 * p for p in packed_in], max_report=100)
    pipe = [(0, 0)] * latency
    cycle = 0
    while True:
        rst, valid, payload, ready = checker.drive(cycle)
        o_valid, o_payload = pipe[-1]
        if fault:
            o_valid, o_payload = fault(cycle, o_valid, o_payload)
        i_ready = int(ready or not pipe[-1][0])
        going = checker.observe(cycle, i_ready, o_valid, o_payload)
        if rst:
            pipe = [(0, 0)] * latency
        elif i_ready:
            pipe = [(valid, 3 * payload)] + pipe[:-1]
        cycle += 1
        if not going:
            return checker


def test_checker_passes_an_ideal_pipeline_and_counts():
    packed = list(range(1000, 1200))
    plan = plan_stream(len(packed), 3, 12, stalls=0.4, bubbles=0.3, reset_at=150, seed=2)
    checker = _model_run(plan, packed, 3)
    assert checker.mismatch_count == 0, checker.records
    assert checker.delivered == len(packed) and checker.resets == 1 and checker.resent > 0
    assert checker.stall_cycles > 50
    assert checker.cycles < plan.limit  # it ended by draining, not by running out


def test_checker_catches_a_repeated_and_a_lost_vector():
    packed = list(range(1000, 1040))
    plan = plan_stream(len(packed), 2, 12, seed=2)
    # back to back: vector k is shown at cycle k + 2; cycle 12 repeats vector 9 in place of 10
    repeat = _model_run(plan, packed, 2, lambda c, v, p: (v, 3 * 1009 if c == 12 else p))
    assert [record[:3] for record in repeat.records] == [(12, PAYLOAD, 10)]  # on vector 10's transfer
    assert repeat.delivered == 40
    # cycle 12 shows nothing: vector 10 is lost, so everything after it comes one vector early
    lost = _model_run(plan, packed, 2, lambda c, v, p: (0 if c == 12 else v, p))
    first = lost.records[0]
    assert first[:5] == (12, VALID, 10, 0, 3 * 1010)  # o.valid 0 where vector 10 was due
    assert lost.records[-1][1:3] == (LOST, 39)  # 39 transfers, so #39 is the first missing


# ---------------------------------------------------------------- a correct Handshake

def test_correct_handshake_passes_with_stalls_and_a_reset(stream_backend):
    result = check(LIRP, _inputs(), backend=stream_backend, stalls=0.4, bubbles=0.2, reset_at=90,
                   seed=4)
    assert result.ok, result.describe()
    assert result.vectors == 120 and result.resets == 1 and result.resent > 0
    assert result.stall_cycles > 20
    assert result.cycles > 120 / 0.6
    assert re.search(r"0 mismatching cycle\(s\); \d+ stall cycle\(s\), 1 reset\(s\) \(\d+ vector\(s\) "
                     r"re-sent\)$", result.describe())


@pytest.mark.needs_verilator
def test_stream_back_ends_agree_cycle_for_cycle():
    runs = [check(LIRP, _inputs(), backend=backend, stalls=0.5, bubbles=0.3, reset_at=60, seed=9,
                  handshake=IgnoresReady, max_report=50) for backend in STREAM_BACKENDS]
    amaranth, fast = runs
    assert amaranth.mismatch_count == fast.mismatch_count > 0
    assert (amaranth.cycles, amaranth.stall_cycles, amaranth.resets, amaranth.resent) == \
        (fast.cycles, fast.stall_cycles, fast.resets, fast.resent)
    assert [dataclasses.astuple(m) for m in amaranth.mismatches] == \
        [dataclasses.astuple(m) for m in fast.mismatches]


def test_cocotb_back_end_refuses_stalls():
    assert set(BACKENDS) - set(STREAM_BACKENDS) == {"verilator"}
    message = (r"^stalls are supported on the amaranth and verilator-fast back ends \(reset_at too\), "
               r"not on verilator$")
    with pytest.raises(ValueError, match=message):
        check(LIRP, _inputs(10), backend="verilator", stalls=0.2)
    with pytest.raises(ValueError, match=message):
        check(LIRP, _inputs(10), backend="verilator", reset_at=5)


class CombinationalLirp(Lirp):
    """Declares latency 0, as a block without registers would (no registered block has one)."""

    latency = 0


def test_latency_zero_is_refused():
    block = dataclasses.replace(LIRP, component_class=CombinationalLirp)
    with pytest.raises(ValueError, match=r"^lirp has latency 0: stalls and reset_at run it inside Handshake"):
        check(block, _inputs(10), stalls=0.2)


# ---------------------------------------------------------------- broken hardware

def test_pipeline_that_ignores_ready_is_caught(stream_backend):
    inputs = _inputs()
    plan = plan_stream(120, 2, 1, stalls=0.3, seed=5)
    # back to back, always taken: vector k shows at cycle k + 2, and the first stalled one
    # is replaced by the next at the following edge
    stall = _first_stall(plan, 2)
    golden = LIRP.golden(inputs)["n"]
    assert not np.array_equal(golden[stall - 2], golden[stall - 1])
    result = check(LIRP, inputs, backend=stream_backend, stalls=0.3, bubbles=0, seed=5,
                   handshake=IgnoresReady, max_report=1000)
    first = result.mismatches[0]
    assert (first.cycle, first.index) == (stall + 1, stall - 2)
    assert first.what == "a stalled valid output changed before it was taken"
    assert first.expected == {"n": golden[stall - 2].tolist(), "overflow": 0}
    assert first.got == {"n": golden[stall - 1].tolist(), "overflow": 0}
    assert re.fullmatch(r"\d+ of 120 vectors never came out \(lost\), the first #\d+",
                        result.mismatches[-1].what)
    assert result.stall_cycles > 0


def test_ungated_valid_pipeline_is_caught(stream_backend):
    plan = plan_stream(120, 2, 1, stalls=0.3, seed=6)
    stall = _first_stall(plan, 2)
    result = check(LIRP, _inputs(), backend=stream_backend, stalls=0.3, bubbles=0, seed=6,
                   handshake=UngatedValid)
    first = result.mismatches[0]
    # the valid register moved on at the stalled edge: one cycle later the output has no valid
    assert first.cycle == stall + 2
    assert (first.expected, first.got) == ({"valid": 1}, {"valid": 0})
    assert first.what == f"o.valid is 0, expected 1 (latency 2, {TIMING})"


def test_wrapper_that_ignores_the_reset_is_caught(stream_backend):
    result = check(LIRP, _inputs(), backend=stream_backend, stalls=0.0, bubbles=0, reset_at=50,
                   reset_cycles=1, handshake=ForgetsReset, max_report=1000)
    first = result.mismatches[0]
    # the reset's edge should have emptied the pipeline; vector 49 is still there, and taken
    assert (first.cycle, first.index) == (51, -1)
    assert first.what == f"o.valid is 1, expected 0 (latency 2, {TIMING})"
    assert result.resets == 1
    assert any(m.what == "a transfer beyond the 120 vectors: one came out twice" for m in result.mismatches)


def test_late_valid_is_caught_in_moving_cycles(stream_backend):
    inputs = _inputs()
    block = dataclasses.replace(LIRP, component_class=LateValidLirp)
    result = check(block, inputs, backend=stream_backend, stalls=0.5, bubbles=0, seed=2)
    first = result.mismatches[0]
    assert (first.cycle, first.index, first.inputs["a"]) == (2, 0, int(inputs["a"][0]))
    assert (first.expected, first.got) == ({"valid": 1}, {"valid": 0})
    assert first.what == f"o.valid is 0, expected 1 (latency 2, {TIMING})"


@pytest.mark.needs_verilator
def test_fast_vcd_is_written(tmp_path):
    path = tmp_path / "lirp.vcd"
    result = check(LIRP, _inputs(20), backend="verilator-fast", stalls=0.3, reset_at=10, vcd=path)
    assert result.ok, result.describe()
    text = path.read_text()
    assert "$enddefinitions" in text and " i_ready " in text and "#10" in text
    plain = tmp_path / "plain.vcd"
    check(LIRP, _inputs(20), backend="verilator-fast", vcd=plain).raise_on_mismatch()
    assert "$enddefinitions" in plain.read_text()


# ---------------------------------------------------------------- the command line

@pytest.mark.needs_verilator
def test_cli_sim_takes_stalls_and_a_reset(capsys, tmp_path):
    from phongfx.cli import main

    argv = ["sim", "lirp", "--vectors", "20", "--backend", "amaranth", "--stalls", "0.3",
            "--reset-at", "40"]
    assert main(argv) == 0
    assert re.search(r"0 mismatching cycle\(s\); \d+ stall cycle\(s\), 1 reset\(s\) "
                     r"\(\d+ vector\(s\) re-sent\)", capsys.readouterr().out)
    for argv, message in [
        (["--backend", "verilator", "--stalls", "0.3"],
         "stalls are supported on the amaranth and verilator-fast back ends (reset_at too), "
         "not on verilator"),
        (["--netlist", "ecp5", "--reset-at", "9"],
         "--stalls and --reset-at run the RTL inside Handshake; a --netlist has no ready"),
        (["--stalls", "1"], "--stalls must be a probability in [0, 1) (at 1 nothing would move), not 1"),
    ]:
        assert main(["sim", "lirp", "--vectors", "5", *argv]) == 2
        assert f"phongfx: error: {message}" in capsys.readouterr().err


@pytest.mark.needs_verilator
def test_cli_sim_writes_a_cocotb_vcd(capsys, tmp_path):
    from phongfx.cli import main

    path = tmp_path / "lirp.vcd"
    assert main(["sim", "lirp", "--vectors", "5", "--backend", "verilator", "--vcd", str(path)]) == 0
    assert "$enddefinitions" in path.read_text()


@pytest.mark.needs_verilator
def test_cli_sim_writes_a_fast_vcd(capsys, tmp_path):
    from phongfx.cli import main

    path = tmp_path / "lirp.vcd"
    assert main(["sim", "lirp", "--vectors", "5", "--stalls", "0.2", "--vcd", str(path)]) == 0
    assert "lirp on verilator-fast: " in capsys.readouterr().out
    assert "$enddefinitions" in path.read_text()
