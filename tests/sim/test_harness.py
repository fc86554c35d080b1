"""The checking harness: packing, scheduling, and that it catches wrong hardware.

Deliberately wrong LIRPs (rounding by truncation, a data path one stage shorter
or longer than declared, a valid pipeline one stage too long) must be reported
at the cycle, with the input vector and the golden and RTL values, that can be
predicted from the golden model alone, on every back end.
"""

import dataclasses
import re
import shutil
import time

import numpy as np
import pytest
from amaranth.hdl import Module, Signal
from amaranth.lib import data, wiring
from amaranth.lib.wiring import In, Out

from phongfx.core.format import Format
from phongfx.core.registry import get_block
from phongfx.hdl.block import payload_layout
from phongfx.hdl.fixed import FixedValue, stage
from phongfx.hdl.lirp import Lirp
from phongfx.sim import build_cache, verilator_backend
from phongfx.sim.harness import HarnessMismatch, check, pack, run_backend, schedule, unpack

# ---------------------------------------------------------------- pack / unpack

PORTS = {
    "s": (Format.parse("S1.10"), 1),
    "v": (Format.parse("S2.5"), 3),
    "u": (Format.parse("1.10"), 1),
    "wide_s": (Format.parse("S31.32"), 1),  # 64 bits: the int64 extremes
    "wide_u": (Format.parse("31.32"), 1),
}


def _extremes(fmt):
    if fmt.signed:
        return [-(1 << (fmt.width - 1)), (1 << (fmt.width - 1)) - 1, -1, 0, 1]
    return [(1 << fmt.width) - 1, 0, 1, 1 << (fmt.width - 1), 5]


def _raw_extremes():
    raw = {}
    for name, (fmt, lanes) in PORTS.items():
        column = np.array(_extremes(fmt), dtype=np.int64)
        # lanes get the extremes in different orders, so each row mixes them
        lanes_ = [np.roll(column, lane) for lane in range(lanes)]
        raw[name] = np.stack(lanes_, axis=1) if lanes > 1 else column
    return raw


def test_pack_unpack_round_trip_extremes():
    raw = _raw_extremes()
    packed = pack(PORTS, raw)
    back = unpack(PORTS, packed)
    for name in PORTS:
        np.testing.assert_array_equal(back[name], raw[name], err_msg=name)
    assert max(packed).bit_length() > 64


def test_pack_is_lsb_first_in_layout_order():
    # The first field sits at bit 0, as in Amaranth's StructLayout.
    raw = {name: np.zeros((1, lanes) if lanes > 1 else 1, dtype=np.int64)
           for name, (fmt, lanes) in PORTS.items()}
    layout = payload_layout(PORTS)
    for name, (fmt, lanes) in PORTS.items():
        raw[name][...] = -1 if fmt.signed else (1 << fmt.width) - 1  # all ones
        ones = (1 << (fmt.width * lanes)) - 1
        assert pack(PORTS, raw) == [ones << layout[name].offset], name
        raw[name][...] = 0
    total = sum(fmt.width * lanes for fmt, lanes in PORTS.values())
    for name, (fmt, lanes) in PORTS.items():
        raw[name][...] = -1 if fmt.signed else (1 << fmt.width) - 1
    assert pack(PORTS, raw) == [(1 << total) - 1]
    assert total == layout.size > 64


def test_pack_refuses_ragged_inputs():
    raw = _raw_extremes()
    raw["u"] = raw["u"][:-1]
    with pytest.raises(ValueError, match=r"^input u has 4 vectors, others have 5$"):
        pack(PORTS, raw)


def test_unpack_sign_extends_min_negative():
    fmt = Format.parse("S31.32")
    ports = {"x": (fmt, 1)}
    assert unpack(ports, [1 << 63])["x"].tolist() == [-(1 << 63)]
    assert unpack(ports, [(1 << 64) - 1])["x"].tolist() == [-1]


# ---------------------------------------------------------------- schedule

def test_schedule_is_deterministic_per_seed():
    a = schedule(500, 0.3, seed=11)
    np.testing.assert_array_equal(a, schedule(500, 0.3, seed=11))
    assert not np.array_equal(a, schedule(500, 0.3, seed=12))
    np.testing.assert_array_equal(a[a >= 0], np.arange(500))  # every vector once, in order
    bubbles = int(np.sum(a < 0))
    assert 100 < bubbles < 330  # about 500 * 0.3 / 0.7 = 214


def test_schedule_without_bubbles_is_back_to_back():
    np.testing.assert_array_equal(schedule(37, 0, seed=5), np.arange(37))


@pytest.mark.parametrize("bubbles", [1, 1.5, -0.1])
def test_schedule_refuses_bad_bubbles(bubbles):
    value = re.escape(str(bubbles))
    message = rf"^bubbles must be a probability in 0\.\.1 \(excluding 1\), not {value}$"
    with pytest.raises(ValueError, match=message):
        schedule(10, bubbles, seed=0)


# ---------------------------------------------------------------- wrong hardware

class TruncatingLirp(Lirp):
    """Rounds ``N'`` by truncation whatever the config says."""

    def datapath(self, m, i):
        cfg = self.config
        b = (FixedValue.const(1, cfg.a) - i["a"]).quantize(cfg.a, "truncate", "error")
        p0 = stage(m, i["n0"] * b, "p0")
        p1 = stage(m, i["n1"] * i["a"], "p1")
        return {"n": stage(m, (p0 + p1).quantize(cfg.out, "truncate", "error"), "n")}


class OverstatedLirp(Lirp):
    """Declares latency 3; its data path has the real LIRP's 2 stages."""

    latency = 3


class UnderstatedLirp(Lirp):
    """Declares latency 2; its data path has one stage more."""

    def datapath(self, m, i):
        return {"n": stage(m, super().datapath(m, i)["n"], "extra")}


class LateValidLirp(Lirp):
    """Declares latency 2 but builds a 3-stage valid pipeline.

    The harness reads ``latency`` before elaboration, the valid pipeline is made
    during it, so raising ``latency`` only while elaborating splits the two.
    """

    def elaborate(self, platform):
        self.latency = 3
        try:
            return super().elaborate(platform)
        finally:
            del self.latency


LIRP = get_block("lirp")


def _inputs(count=150, seed=3):
    """A seeded sample of the LIRP's test vectors (directed and random)."""
    every = LIRP.stimulus(count=200, seed=seed)
    pick = np.sort(np.random.default_rng(seed).choice(len(every["a"]), count, replace=False))
    return {name: value[pick] for name, value in every.items()}


def _with(component_class):
    return dataclasses.replace(LIRP, component_class=component_class)


def _row(inputs, index):
    return {"n0": inputs["n0"][index].tolist(), "n1": inputs["n1"][index].tolist(),
            "a": int(inputs["a"][index])}


def test_correct_lirp_has_no_mismatch(backend):
    result = check(LIRP, _inputs(), backend=backend, bubbles=0.2, seed=4)
    assert result.ok and result.mismatch_count == 0 and result.mismatches == []
    result.raise_on_mismatch()


def test_truncation_is_caught(backend):
    inputs = _inputs()
    golden = LIRP.golden(inputs)["n"]
    truncated = get_block("lirp", rounding="truncate").golden(inputs)["n"]
    differ = np.flatnonzero((golden != truncated).any(axis=1))
    assert len(differ) > 10  # the sample must exercise rounding
    first = int(differ[0])

    result = check(_with(TruncatingLirp), inputs, backend=backend, bubbles=0)
    assert result.mismatch_count == len(differ)
    mm = result.mismatches[0]
    assert (mm.cycle, mm.index, mm.what) == (first + 2, first, "payload differs")
    assert mm.inputs == _row(inputs, first)
    assert mm.expected == {"n": golden[first].tolist(), "overflow": 0}
    assert mm.got == {"n": truncated[first].tolist(), "overflow": 0}
    report = (f"cycle {first + 2}: payload differs; input #{first} {_row(inputs, first)}; "
              f"golden {{'n': {golden[first].tolist()}, 'overflow': 0}}; "
              f"rtl {{'n': {truncated[first].tolist()}, 'overflow': 0}}")
    assert report in result.describe()
    with pytest.raises(HarnessMismatch, match=re.escape(report)):
        result.raise_on_mismatch()


def test_overstated_latency_is_caught(backend):
    # valid comes 3 cycles late as declared, the data 2: cycle k+3 shows vector k+1.
    inputs = _inputs()
    golden = LIRP.golden(inputs)["n"]
    count = len(golden)
    follows = np.concatenate([golden[1:], np.zeros((1, 3), np.int64)])  # idle input: zeros
    differ = np.flatnonzero((golden != follows).any(axis=1))
    first = int(differ[0])

    result = check(_with(OverstatedLirp), inputs, backend=backend, bubbles=0)
    assert result.cycles == count + 3
    assert result.mismatch_count == len(differ)
    mm = result.mismatches[0]
    assert (mm.cycle, mm.index, mm.what) == (first + 3, first, "payload differs")
    assert mm.inputs == _row(inputs, first)
    assert mm.expected == {"n": golden[first].tolist(), "overflow": 0}
    assert mm.got == {"n": golden[first + 1].tolist(), "overflow": 0}
    assert f"cycle {first + 3}: payload differs; input #{first} " in result.describe()


def test_understated_latency_is_caught(backend):
    # valid comes at 2 as declared, the data at 3: cycle 2 shows the reset value.
    inputs = _inputs()
    golden = LIRP.golden(inputs)["n"]
    before = np.concatenate([np.zeros((1, 3), np.int64), golden[:-1]])
    differ = np.flatnonzero((golden != before).any(axis=1))
    assert differ[0] == 0

    result = check(_with(UnderstatedLirp), inputs, backend=backend, bubbles=0)
    assert result.mismatch_count == len(differ)
    mm = result.mismatches[0]
    assert (mm.cycle, mm.index) == (2, 0)
    assert mm.expected == {"n": golden[0].tolist(), "overflow": 0}
    assert mm.got == {"n": [0, 0, 0], "overflow": 0}
    assert f"cycle 2: payload differs; input #0 {_row(inputs, 0)}; " in result.describe()


def test_late_valid_is_caught(backend):
    # Only cycle 2 misses its valid: from cycle 3 on, the late valid of vector k
    # lines up with the expected valid of vector k + 1, whose data is on time.
    inputs = _inputs()
    result = check(_with(LateValidLirp), inputs, backend=backend, bubbles=0)
    assert result.mismatch_count == 1
    mm = result.mismatches[0]
    assert (mm.cycle, mm.index, mm.inputs) == (2, 0, _row(inputs, 0))
    assert (mm.expected, mm.got) == ({"valid": 1}, {"valid": 0})
    assert mm.what == "o.valid is 0, expected 1 (latency 2)"
    assert "cycle 2: o.valid is 0, expected 1 (latency 2); input #0 " in result.describe()


# ---------------------------------------------------------------- back ends agree

class Mixed(wiring.Component):
    """A combinational path and a registered one, 70 bits wide.

    ``o.payload = i.payload ^ previous i.payload`` and ``o.valid = i.valid``:
    cycle ``t`` of any back end must show ``in[t] ^ in[t-1]`` (``in[-1] = 0``),
    which pins down "inputs applied, outputs settled, then the edge".
    """

    WIDTH = 70

    def __init__(self):
        layout = data.StructLayout({"x": self.WIDTH})
        stream = wiring.Signature({"valid": Out(1), "payload": Out(layout)})
        super().__init__({"i": In(stream), "o": Out(stream)})

    def elaborate(self, platform):
        m = Module()
        previous = Signal(self.WIDTH)
        m.d.sync += previous.eq(self.i.payload.x)
        m.d.comb += [self.o.valid.eq(self.i.valid),
                     self.o.payload.x.eq(self.i.payload.x ^ previous)]
        return m


def _stimulus(cycles, width, seed):
    rng = np.random.default_rng(seed)
    valid = rng.integers(0, 2, cycles).tolist()
    payload = [int.from_bytes(rng.bytes((width + 7) // 8), "little") & ((1 << width) - 1)
               for _ in range(cycles)]
    return valid, payload


@pytest.mark.needs_verilator
def test_back_ends_sample_alike():
    cycles = 3 * verilator_backend.BLOCK + 5  # several testbench windows and a partial one
    valid, payload = _stimulus(cycles, Mixed.WIDTH, seed=8)
    expected = [p ^ q for p, q in zip(payload, [0] + payload[:-1])]
    for backend in ("amaranth", "verilator"):
        out_valid, out_payload = run_backend(backend, Mixed(), valid, payload, cycles)
        assert out_valid == valid, backend
        assert out_payload == expected, backend


@pytest.mark.needs_verilator
def test_back_ends_give_identical_outputs():
    inputs = _inputs()
    packed = pack(LIRP.config.inputs, inputs)
    slots = schedule(len(packed), 0.3, seed=9)
    cycles = len(slots) + 2
    valid = [int(s >= 0) for s in slots] + [0, 0]
    payload = [packed[s] if s >= 0 else 12345 for s in slots] + [0, 0]
    amaranth = run_backend("amaranth", LIRP.component(), valid, payload, cycles)
    verilator = run_backend("verilator", LIRP.component(), valid, payload, cycles)
    assert amaranth == verilator
    assert sum(amaranth[0]) == len(packed)


# ---------------------------------------------------------------- Verilator specifics

@pytest.mark.needs_verilator
def test_verilator_build_is_cached():
    component = LIRP.component()
    first = verilator_backend.build(component)
    executable = first.directory / first.top
    stamp = executable.stat().st_mtime_ns
    start = time.perf_counter()
    second = verilator_backend.build(LIRP.component())
    assert not second.built
    assert second.directory == first.directory and second.top == "lirp_tb"
    assert time.perf_counter() - start < 5  # a compile takes far longer
    check(LIRP, _inputs(20), backend="verilator").raise_on_mismatch()
    assert executable.stat().st_mtime_ns == stamp
    assert verilator_backend.build(_with(TruncatingLirp).component()).directory != first.directory


@pytest.mark.needs_verilator
def test_verilator_speed_is_the_simulation_alone(monkeypatch):
    """``make sim``'s cocotb cycles/s once counted the Verilator build (71 to 1,321 cycles/s
    from run to run, by the state of the cache): a slow build must not change the figure."""
    build = verilator_backend.build

    def slow_build(*args, **kwargs):
        time.sleep(1.5)
        return build(*args, **kwargs)

    monkeypatch.setattr(verilator_backend, "build", slow_build)
    start = time.perf_counter()
    result = check(LIRP, _inputs(20), backend="verilator", bubbles=0.0)
    wall = time.perf_counter() - start
    assert result.ok and wall > 1.5
    assert 0 < result.seconds < 1.0 and result.seconds < wall - 1.5
    assert result.cycles_per_second == result.cycles / result.seconds


@pytest.mark.needs_verilator
def test_verilator_build_failure_raises_with_log(monkeypatch, tmp_path):
    monkeypatch.setattr(build_cache, "verilog", lambda *args, **kwargs: "module broken(;\n")
    with pytest.raises(RuntimeError, match=r"(?s)^Verilator build of lirp failed .*%Error") as info:
        verilator_backend.build(LIRP.component(), build_dir=tmp_path)
    assert "lirp_tb.v" in str(info.value) and f"log {tmp_path / 'failed'}" in str(info.value)
    # nothing cached: the failed build's folder, log included, is kept apart under failed/
    assert [p.name for p in tmp_path.iterdir()] == ["failed"]


@pytest.mark.needs_verilator
def test_verilator_run_failure_raises_with_log(monkeypatch):
    monkeypatch.setattr(verilator_backend, "TB_MODULE", "phongfx.sim.no_such_testbench")
    with pytest.raises(RuntimeError, match=r"^Verilator run of lirp_tb failed: ") as info:
        verilator_backend.run(LIRP.component(), [1, 0], [0, 0], 2)
    assert "No module named 'phongfx.sim.no_such_testbench'" in str(info.value)  # the log tail
    # A failed run keeps its directory for inspection; this one is known.
    shutil.rmtree(re.search(r"; log (\S+)/sim\.log:", str(info.value)).group(1))
