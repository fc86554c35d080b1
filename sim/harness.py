"""One harness for every block: drive vectors clock by clock, compare every cycle.

Given a :class:`~phongfx.core.registry.Block` and raw input codes, :func:`check` builds a
per-cycle schedule (back to back, or with seeded random ``valid`` bubbles whose
payload is random junk), runs the component on a back end, and compares every
output cycle with the golden model: ``o.valid`` must rise exactly ``latency``
cycles after each valid input and nowhere else, and the payload of each valid
output must equal the golden output bit for bit, with the RTL's overflow flag
(:data:`~phongfx.hdl.block.OVERFLOW`) low: the assertion that no ``overflow="error"``
quantize met a value its format cannot hold.

Back ends (see :data:`BACKENDS`): ``amaranth`` (Amaranth's simulator, optional VCD),
``verilator`` (the emitted Verilog under cocotb + Verilator) and ``verilator-fast``
(Verilator with a compiled checker, :mod:`phongfx.sim.fast_backend`).  The first
two take and return packed payload integers, so packing, scheduling and comparing
live here once; the fast one packs with numpy and compares in C++, and :func:`check`
hands it the whole job.
"""

import time
from dataclasses import dataclass, field

import numpy as np

from phongfx.hdl.block import OVERFLOW, checked_outputs

__all__ = ["BACKENDS", "Mismatch", "Result", "HarnessMismatch", "payload_fields", "columns", "pack",
           "unpack", "schedule", "row_of", "checked_expected", "payload_mismatch", "check", "run_backend"]

BACKENDS = ("amaranth", "verilator", "verilator-fast")


def payload_fields(ports):
    """(name, lane, offset, width, signed) for each payload field, in layout order."""
    offset = 0
    out = []
    for name, (fmt, lanes) in ports.items():
        for lane in range(lanes):
            out.append((name, lane if lanes > 1 else None, offset, fmt.width, fmt.signed))
            offset += fmt.width
    return out, offset


def columns(ports, raw):
    """``(column, offset, width)`` of each payload field, ``column`` the int64 codes of
    that field (one lane of a vector port); all columns must have the same length."""
    fields_, _ = payload_fields(ports)
    count = None
    for name, lane, offset, width, _ in fields_:
        column = np.asarray(raw[name], dtype=np.int64)
        column = column[:, lane] if lane is not None else column
        count = len(column) if count is None else count
        if len(column) != count:
            raise ValueError(f"input {name} has {len(column)} vectors, others have {count}")
        yield column, offset, width


def pack(ports, raw):
    """Pack raw codes ``{name: array (count,) or (count, lanes)}`` into payload integers."""
    packed = None
    for column, offset, width in columns(ports, raw):
        mask = (1 << width) - 1
        bits = [(int(v) & mask) << offset for v in column.tolist()]
        packed = bits if packed is None else [p | b for p, b in zip(packed, bits)]
    return packed


def unpack(ports, packed):
    """Inverse of :func:`pack`: payload integers to raw codes (int64 arrays)."""
    fields_, _ = payload_fields(ports)
    out = {}
    for name, (fmt, lanes) in ports.items():
        out[name] = np.zeros((len(packed), lanes) if lanes > 1 else len(packed), dtype=np.int64)
    for name, lane, offset, width, signed in fields_:
        mask = (1 << width) - 1
        values = [(p >> offset) & mask for p in packed]
        if signed:
            values = [v - (1 << width) if v >> (width - 1) else v for v in values]
        column = np.array(values, dtype=np.int64)
        if lane is None:
            out[name][:] = column
        else:
            out[name][:, lane] = column
    return out


def row_of(ports, raw, index):
    """``{name: code or [codes]}`` of vector ``index`` of ``raw``: one row of a mismatch report."""
    row = {}
    for name, (fmt, lanes) in ports.items():
        value = raw[name][index]
        row[name] = value.tolist() if lanes > 1 else int(value)
    return row


def schedule(count, bubbles, seed):
    """Per-cycle index of the vector driven, ``-1`` for a bubble (``valid`` low).

    ``bubbles`` is the probability of a bubble before each vector (0: back to back).
    """
    if not 0 <= bubbles < 1:
        raise ValueError(f"bubbles must be a probability in 0..1 (excluding 1), not {bubbles}")
    rng = np.random.default_rng(seed)
    slots = []
    for index in range(count):
        while bubbles and rng.random() < bubbles:
            slots.append(-1)
        slots.append(index)
    return np.array(slots, dtype=np.int64)


@dataclass
class Mismatch:
    cycle: int
    index: int  # input vector index, -1 if none was expected
    inputs: dict
    expected: dict
    got: dict
    what: str


class HarnessMismatch(AssertionError):
    pass


@dataclass
class Result:
    block: str
    backend: str
    vectors: int
    cycles: int
    seconds: float
    mismatches: list = field(default_factory=list)  # the first few, in detail
    mismatch_count: int = 0

    def _add(self, mismatch, limit):
        self.mismatch_count += 1
        if len(self.mismatches) < limit:
            self.mismatches.append(mismatch)

    @property
    def ok(self):
        return not self.mismatch_count

    @property
    def cycles_per_second(self):
        return self.cycles / self.seconds if self.seconds else float("inf")

    def describe(self, limit=5):
        lines = [f"{self.block} on {self.backend}: {self.vectors} vectors, {self.cycles} cycles, "
                 f"{self.mismatch_count} mismatching cycle(s)"]
        for mm in self.mismatches[:limit]:
            lines.append(f"  cycle {mm.cycle}: {mm.what}; input #{mm.index} {mm.inputs}; "
                         f"golden {mm.expected}; rtl {mm.got}")
        return "\n".join(lines)

    def raise_on_mismatch(self):
        if self.mismatch_count:
            raise HarnessMismatch(self.describe())


def checked_expected(expected):
    """The golden outputs and :data:`~phongfx.hdl.block.OVERFLOW` all 0: the golden model
    raises on an undeclared overflow, so every output it gives must come without one."""
    count = len(np.asarray(next(iter(expected.values()))))
    return {**expected, OVERFLOW: np.zeros(count, dtype=np.int64)}


def payload_mismatch(config, inputs, expected, index, cycle, got_packed):
    """The :class:`Mismatch` of a valid output whose packed payload differs from golden."""
    ports = checked_outputs(config)
    got = row_of(ports, unpack(ports, [got_packed]), 0)
    want = row_of(ports, checked_expected(expected), index)
    what = "payload differs"
    if got[OVERFLOW] and {k: v for k, v in got.items() if k != OVERFLOW} == \
            {k: v for k, v in want.items() if k != OVERFLOW}:
        what = "RTL overflow that the golden model did not predict"
    elif got[OVERFLOW]:
        what = "payload differs, and the RTL overflowed where the golden model did not"
    return Mismatch(cycle, index, row_of(config.inputs, inputs, index), want, got, what)


def run_backend(backend, component, in_valid, in_payload, cycles, **options):
    """Run ``component`` for ``cycles`` clocks; returns (out_valid, out_payload) lists."""
    if backend == "amaranth":
        from .amaranth_backend import run
    elif backend == "verilator":
        from .verilator_backend import run
    elif backend == "verilator-fast":
        from .fast_backend import run
    else:
        raise ValueError(f"backend must be one of {', '.join(BACKENDS)}, not {backend!r}")
    return run(component, in_valid, in_payload, cycles, **options)


def check(block, inputs=None, *, expected=None, backend="amaranth", bubbles=0.25, seed=0,
          count=1000, max_report=10, **options):
    """Check ``block`` cycle by cycle against its golden model.

    Parameters
    ----------
    block : phongfx.core.registry.Block
    inputs : dict of raw code arrays, optional
        Defaults to ``block.stimulus(count, seed)``.
    expected : dict of raw code arrays, optional
        The golden outputs of ``inputs`` when the caller has them already.
    backend : {"amaranth", "verilator", "verilator-fast"}
    bubbles : float
        Probability of an idle (``valid`` low, junk payload) cycle before each vector.
    options
        Passed to the back end (``vcd=PATH`` for ``amaranth``, ``build_dir`` ...).
    """
    if backend == "verilator-fast":
        from .fast_backend import check as fast_check

        return fast_check(block, inputs, expected=expected, bubbles=bubbles, seed=seed,
                          count=count, max_report=max_report, **options)
    config = block.config
    if inputs is None:
        inputs = block.stimulus(count=count, seed=seed)
    if expected is None:
        expected = block.golden(inputs)
    packed_in = pack(config.inputs, inputs)
    packed_out = pack(checked_outputs(config), checked_expected(expected))
    count = len(packed_in)

    slots = schedule(count, bubbles, seed)
    component = block.component()
    latency = component.latency
    cycles = len(slots) + latency
    rng = np.random.default_rng(seed + 1)
    _, in_width = payload_fields(config.inputs)
    in_valid = [0] * cycles
    in_payload = [0] * cycles
    for cycle, index in enumerate(slots):
        if index >= 0:
            in_valid[cycle] = 1
            in_payload[cycle] = packed_in[index]
        else:
            in_payload[cycle] = int.from_bytes(rng.bytes((in_width + 7) // 8), "little") & ((1 << in_width) - 1)
    for cycle in range(len(slots), cycles):
        in_payload[cycle] = 0

    start = time.perf_counter()
    out_valid, out_payload = run_backend(backend, component, in_valid, in_payload, cycles, **options)
    seconds = time.perf_counter() - start

    result = Result(block.name, backend, count, cycles, seconds)
    for cycle in range(cycles):
        source = cycle - latency
        index = int(slots[source]) if source >= 0 else -1
        want_valid = int(index >= 0)
        if out_valid[cycle] != want_valid:
            result._add(Mismatch(
                cycle, index, row_of(config.inputs, inputs, index) if index >= 0 else {},
                {"valid": want_valid}, {"valid": out_valid[cycle]},
                f"o.valid is {out_valid[cycle]}, expected {want_valid} (latency {latency})"),
                max_report)
        elif want_valid and out_payload[cycle] != packed_out[index]:
            result._add(payload_mismatch(config, inputs, expected, index, cycle, out_payload[cycle]),
                        max_report)
    return result
