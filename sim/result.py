"""What a check found: a :class:`Result` and the first :class:`Mismatch` records in detail.

Every back end reports this way; a payload mismatch is read back field by field from the
packed words (:mod:`phongfx.sim.vectors`), the RTL's overflow flag
(:data:`~phongfx.hdl.block.OVERFLOW`) among them.
"""

from dataclasses import dataclass, field

import numpy as np

from phongfx.hdl.block import OVERFLOW, checked_outputs

from .vectors import row_of, unpack

__all__ = ["Mismatch", "HarnessMismatch", "Result", "checked_expected", "payload_mismatch"]


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
    #: the simulation: on verilator the clocked run in the simulator, on verilator-fast the
    #: stream and the compiled check; never the build, so ``cycles_per_second`` is the simulator's
    seconds: float
    mismatches: list = field(default_factory=list)  # the first few, in detail
    mismatch_count: int = 0
    #: stream mode: cycles where a valid output waited for ``o.ready`` (the pipeline held)
    stall_cycles: int = 0
    #: stream mode: resets asserted, and vectors offered again after them (those lost in
    #: flight, and for a scanline block those replayed from the scanline's start)
    resets: int = 0
    resent: int = 0

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
        head = (f"{self.block} on {self.backend}: {self.vectors} vectors, {self.cycles} cycles, "
                f"{self.mismatch_count} mismatching cycle(s)")
        if self.stall_cycles or self.resets:
            head += f"; {self.stall_cycles} stall cycle(s), {self.resets} reset(s)"
            head += f" ({self.resent} vector(s) re-sent)" if self.resets else ""
        lines = [head]
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
