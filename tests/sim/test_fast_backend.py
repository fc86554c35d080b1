"""The ``verilator-fast`` back end: numpy-packed streams, compared in compiled code.

It must keep the harness contract (same :class:`Result`, mismatches at the cycle
predicted from the schedule and the latency alone) for narrow, wide (> 64-bit)
and stateful blocks, with and without bubbles.
"""

import re

import numpy as np
import pytest

from phongfx.core.format import Format
from phongfx.core.registry import get_block
from phongfx.sim import fast_backend, fast_top
from phongfx.sim.harness import check, pack, run_backend, schedule

pytestmark = pytest.mark.needs_verilator

PORTS = {
    "s": (Format.parse("S1.10"), 1),
    "v": (Format.parse("S2.5"), 3),
    "wide_s": (Format.parse("S31.32"), 1),  # 64 bits, straddling three words
    "wide_u": (Format.parse("31.32"), 1),
}


def test_pack_words_equals_harness_pack_shifted():
    rng = np.random.default_rng(7)
    raw = {}
    for name, (fmt, lanes) in PORTS.items():
        low = -(1 << (fmt.width - 1)) if fmt.signed else 0
        high = (1 << (fmt.width - 1)) - 1 if fmt.signed else (1 << min(fmt.width, 63)) - 1
        shape = (50, lanes) if lanes > 1 else (50,)
        column = rng.integers(low, high, size=shape, dtype=np.int64, endpoint=True)
        column.flat[:2] = [low, high]  # the extremes, all ones and the sign bit alone
        raw[name] = column
    words = fast_backend.pack_words(PORTS, raw)
    as_ints = [int.from_bytes(row.astype("<u4").tobytes(), "little") for row in words]
    assert as_ints == [p << 1 | 1 for p in pack(PORTS, raw)]
    assert words.shape == (50, fast_top.words_of(1 + 11 + 3 * 8 + 64 + 63))


@pytest.mark.parametrize("name", ["lirp", "shape", "euler"])
@pytest.mark.parametrize("bubbles", [0.0, 0.3])
def test_blocks_pass_with_and_without_bubbles(name, bubbles):
    block = get_block(name)
    result = check(block, backend="verilator-fast", count=300, bubbles=bubbles, seed=5)
    latency = block.component().latency
    assert result.backend == "verilator-fast"
    assert result.cycles == len(schedule(result.vectors, bubbles, 5)) + latency
    assert (result.cycles > result.vectors + latency) == bool(bubbles)
    assert result.mismatch_count == 0, result.describe()
    assert result.seconds > 0 and result.cycles_per_second == result.cycles / result.seconds


def _corrupt(block, count, seed, field, indices, bit=0):
    inputs = block.stimulus(count=count, seed=seed)
    golden = block.golden(inputs)
    expected = {name: value.copy() for name, value in golden.items()}
    expected[field][indices] ^= 1 << bit
    return inputs, golden, expected


@pytest.mark.parametrize("name, field, bit", [("lirp", "n", 0), ("fig7", "diff1", 7)])
def test_wrong_expected_value_is_reported_at_its_cycle(name, field, bit):
    # fig7's diff1 is the last field: its bits lie in the second 32-bit output word
    block = get_block(name)
    inputs, golden, expected = _corrupt(block, 200, 3, field, [57], bit)
    result = check(block, inputs, expected=expected, backend="verilator-fast", bubbles=0.25,
                   seed=3)
    slots = schedule(len(golden[field]), 0.25, 3)
    cycle = int(np.flatnonzero(slots == 57)[0]) + block.component().latency
    assert result.mismatch_count == 1
    (mismatch,) = result.mismatches
    assert (mismatch.cycle, mismatch.index, mismatch.what) == (cycle, 57, "payload differs")
    assert mismatch.got[field] == golden[field][57].tolist()
    assert mismatch.expected[field] == expected[field][57].tolist()
    assert re.search(rf"^  cycle {cycle}: payload differs; input #57 ", result.describe(), re.M)


def test_mismatch_count_exceeds_the_detailed_report():
    block = get_block("shape")
    inputs, _, expected = _corrupt(block, 100, 1, "spec", [3, 10, 11, 40, 99])
    result = check(block, inputs, expected=expected, backend="verilator-fast", bubbles=0,
                   max_report=2)
    latency = block.component().latency
    assert result.mismatch_count == 5
    assert [m.cycle for m in result.mismatches] == [3 + latency, 10 + latency]


def test_an_unoptimized_build_checks_the_same_and_is_kept_apart(tmp_path):
    """``optimize=False`` (the compile's one-frame RTL check) builds at -O0 without Verilator's
    merge of conditionals in its own cache entry, with run-time objects of its own (-O0 too), and
    finds the same mismatches."""
    block = get_block("shape")
    inputs, _, expected = _corrupt(block, 100, 1, "spec", [3, 10, 40])
    found = [check(block, inputs, expected=expected, backend="verilator-fast", bubbles=0.2, seed=2,
                   build_dir=tmp_path, optimize=optimize) for optimize in (True, False)]
    assert [r.mismatch_count for r in found] == [3, 3]
    assert [[m.cycle for m in r.mismatches] for r in found[1:]] == [[m.cycle for m in found[0].mismatches]]
    flags = sorted(line.split()[1] for path in tmp_path.glob("*/build.log")
                   for line in path.read_text().splitlines() if "-o Vtop__ALL.o" in line)
    assert flags == ["-O0", "-O2"]
    # unoptimized, Verilator skips its merge of conditionals (most of a shader's verilation)
    merged = sorted("-fno-merge-cond" in path.read_text().splitlines()[1]
                    for path in tmp_path.glob("*/Vtop__verFiles.dat"))
    assert merged == [False, True]
    assert len(list(tmp_path.glob("runtime-*"))) == 2
    compiled = sorted(line.split()[1] for path in tmp_path.glob("*/build.log")
                      for line in path.read_text().splitlines() if "-o verilated.o" in line)
    assert compiled == ["-O0", "-Os"]


def test_fig7_wide_payload_back_to_back():
    block = get_block("fig7")
    result = check(block, backend="verilator-fast", count=500, bubbles=0, seed=11)
    assert result.mismatch_count == 0, result.describe()
    assert result.cycles == result.vectors + block.component().latency


def test_run_matches_amaranth_cycle_for_cycle():
    # the run_backend contract (per-cycle outputs), including junk on bubbles
    block = get_block("euler")
    component = block.component()
    rng = np.random.default_rng(2)
    cycles = 120
    width = len(component.i.payload.as_value())
    valid = rng.integers(0, 2, size=cycles).tolist()
    payload = [int.from_bytes(rng.bytes((width + 7) // 8), "little") & ((1 << width) - 1)
               for _ in range(cycles)]
    fast = run_backend("verilator-fast", component, valid, payload, cycles)
    slow = run_backend("amaranth", block.component(), valid, payload, cycles)
    assert fast == slow
    assert sum(fast[0]) == sum(valid)


def test_short_stimulus_is_refused():
    with pytest.raises(ValueError, match=r"^need 3 cycles of stimulus, got 2 valid and 3 payload"):
        fast_backend.run(get_block("lirp").component(), [1, 0], [0, 0, 0], 3)
