"""The stream mode of a check: back-pressure and a reset mid-stream.

:func:`phongfx.sim.harness.check`'s ``stalls`` and ``reset_at`` (on the ``amaranth`` and
``verilator-fast`` back ends): a block that never stalls is only half of what a user's design meets, whose
consumer may hold ``ready`` low and whose reset may come mid-stream.  In this *stream
mode* the block runs inside :class:`~phongfx.hdl.handshake.Handshake` and the schedule
can no longer be fixed in advance, since when a vector is taken depends on the design's
``i.ready``: a :class:`StreamPlan` fixes only the per-cycle decisions (``o.ready``, the
reset, whether to start a new vector or idle), drawn from numpy's seeded generator, and a
driver reacts to the design cycle by cycle (:class:`StreamChecker` here, its twin in
``fast_main.cpp``).  It offers each vector until it is taken and compares the transfers
(``o.valid & o.ready``) in order with the golden outputs; a stalled valid output must
stay valid and unchanged until taken; ``o.valid`` must come ``latency`` cycles *where the
pipeline moves* (``i.ready`` high) after each vector taken, so a reset leaves no valid
output until new vectors have gone through; the vectors in flight at a reset are lost by
design, the driver re-sends from the first not yet delivered, and every vector must come
out exactly once, before the reset or after it.  A scanline block (one with an ``init``
input: euler, gouraud, spherical) keeps state from pixel to pixel, which a reset clears and
its golden model builds up again only from an ``init``: the driver re-sends from the last
``init`` at or before the first vector not delivered, and the replayed outputs must match
the golden ones again (:func:`restart_points`).
"""

from dataclasses import dataclass

import numpy as np

from phongfx.hdl.block import checked_outputs

from .result import Mismatch, payload_mismatch
from .vectors import row_of, unpack

__all__ = ["READY", "IDLE", "RESET", "VALID", "PAYLOAD", "HELD", "EXTRA", "LOST", "StreamPlan", "stream_mode",
           "restart_points", "plan_stream", "StreamChecker", "stream_mismatch", "handshake_component"]

#: Bits of a :class:`StreamPlan`'s per-cycle control byte (also in ``fast_main.cpp``).
READY, IDLE, RESET = 1, 2, 4
#: Kinds of a stream-mode mismatch record (also in ``fast_main.cpp``).
VALID, PAYLOAD, HELD, EXTRA, LOST = range(5)


@dataclass(frozen=True)
class StreamPlan:
    """The per-cycle decisions of a stream-mode run, fixed before it (see the module docstring).

    Attributes
    ----------
    control : numpy.ndarray
        One uint8 per cycle, at most ``limit`` cycles: :data:`READY` (``o.ready`` high),
        :data:`IDLE` (if no vector is on offer, start none this cycle: a bubble),
        :data:`RESET` (``rst`` high).
    junk : tuple of int
        Payloads driven with ``i.valid`` low, ``junk[cycle % len(junk)]``.
    count, latency : int
        Vectors to deliver; the block's latency.
    interval : int
        The block's initiation interval: after taking a vector, ``i.ready`` is low for
        ``interval − 1`` cycles where the pipeline moves (``o.ready`` high or ``o.valid`` low).
    drain : int
        Cycles run after the last delivery, in which nothing more may come out.
    quiet_from : int
        The first cycle after the last reset: the run may not end before it.
    resume : numpy.ndarray
        For each vector ``k``, the vector to re-send from when a reset comes with ``k``
        the first not delivered: ``k`` itself, or a scanline's start (:func:`restart_points`).
    """

    control: np.ndarray
    junk: tuple
    count: int
    latency: int
    drain: int
    quiet_from: int
    resume: np.ndarray
    interval: int = 1

    @property
    def limit(self):
        """The most cycles the run may take; a vector not delivered by then counts as lost."""
        return len(self.control)


def _stall_pattern(stalls):
    """``(fraction of cycles with o.ready low, pattern or None)`` of a ``stalls`` argument."""
    if np.ndim(stalls) == 0:
        if not 0 <= stalls < 1:
            raise ValueError(f"stalls must be a probability in 0..1 (excluding 1) or a pattern of "
                             f"cycles with o.ready low, not {stalls}")
        return float(stalls), None
    pattern = np.asarray(stalls, dtype=bool)
    if pattern.ndim != 1 or not len(pattern) or pattern.all():
        raise ValueError("a stall pattern must be a non-empty sequence of booleans (True: o.ready "
                         "low), not all True")
    return float(pattern.mean()), pattern


def stream_mode(stalls, reset_at):
    """Whether ``check``'s ``stalls`` and ``reset_at`` ask for the stream mode."""
    return reset_at is not None or np.ndim(stalls) > 0 or bool(stalls)


def restart_points(config, inputs):
    """Where a re-send after a reset may start: a boolean per vector, or None (anywhere).

    A block with an ``init`` input keeps state across vectors (a scanline's registers),
    and its golden model assumes that state from the stream's start, zero before any
    ``init``.  A reset zeroes it in the middle of a scanline, so the golden outputs hold
    again only from an ``init`` (or from the first vector).
    """
    if "init" not in config.inputs:
        return None
    points = np.asarray(inputs["init"]).reshape(len(inputs["init"]), -1).any(axis=1)
    points[:1] = True
    return points


def plan_stream(count, latency, in_width, *, stalls=0.0, bubbles=0.0, reset_at=None, reset_cycles=2,
                seed=0, restarts=None, interval=1):
    """The :class:`StreamPlan` of ``count`` vectors through a block of ``latency`` cycles.

    ``stalls`` is the probability that ``o.ready`` is low in a cycle, or a pattern (a
    sequence of booleans, True where it is low) repeated over the run; ``bubbles`` the
    probability of an idle cycle before each vector is offered; ``reset_at`` the first of
    ``reset_cycles`` cycles with ``rst`` high (None: no reset).  Each of the ready, idle
    and junk draws has a generator of its own, seeded by ``seed``, so a longer run
    extends a shorter one's pattern rather than reshuffling it.  ``restarts`` (see
    :func:`restart_points`) marks the vectors a re-send may start from.
    """
    stall_fraction, pattern = _stall_pattern(stalls)
    if not 0 <= bubbles < 1:
        raise ValueError(f"bubbles must be a probability in 0..1 (excluding 1), not {bubbles}")
    if reset_at is not None and (int(reset_at) != reset_at or reset_at < 0):
        raise ValueError(f"reset_at must be a cycle number (a non-negative integer) or None, not {reset_at}")
    if int(reset_cycles) != reset_cycles or reset_cycles < 1:
        raise ValueError(f"reset_cycles must be a positive integer, not {reset_cycles}")
    index = np.arange(count, dtype=np.int64)
    resume = index if restarts is None else np.maximum.accumulate(np.where(restarts, index, 0))
    # A scanline replayed after a reset is as long as the longest one.
    replay = int(np.max(index - resume, initial=0))
    # Twice the expected length, so a correct design is never cut short by chance; a
    # wrong one that loses or holds vectors meets the limit and is reported.
    per_vector = interval / (1 - stall_fraction) + bubbles / (1 - bubbles)
    expected = count * per_vector + (latency + 2) / (1 - stall_fraction)
    quiet_from = 0
    if reset_at is not None:
        quiet_from = int(reset_at) + reset_cycles
        expected = max(expected, quiet_from) + (latency + 2 + replay) * per_vector + reset_cycles
    drain = latency + 2
    limit = int(2 * expected) + 64 + drain
    if pattern is not None:
        ready = ~np.resize(pattern, limit)
    else:
        ready = np.random.default_rng([seed, 1]).random(limit) >= stall_fraction
    idle = np.random.default_rng([seed, 2]).random(limit) < bubbles
    control = (ready * READY | idle * IDLE).astype(np.uint8)
    if reset_at is not None:
        control[int(reset_at):quiet_from] |= RESET
    rng = np.random.default_rng([seed, 3])
    junk = tuple(int.from_bytes(rng.bytes((in_width + 7) // 8), "little") & ((1 << in_width) - 1)
                 for _ in range(64))
    return StreamPlan(control, junk, count, latency, drain, quiet_from, resume, interval)


class StreamChecker:
    """Driver and checks of a stream-mode run, one cycle at a time.

    The amaranth back end calls :meth:`drive` for a cycle's inputs, then :meth:`observe`
    with the settled outputs, until it returns False; ``fast_main.cpp`` is the same
    machine in C++, so both back ends report the same mismatches at the same cycles.

    The timing model: the pipeline moves on the edges where ``i.ready`` is high (the
    design says so itself, as a Handshake's ready is its enable; one that moves while it
    claims not to, or the reverse, shows its output at the wrong cycle), and the output of
    a cycle is what entered ``latency`` moves before, a vector or a bubble; a reset empties
    it.  A design that moves while honestly ready but ignores ``o.ready`` is caught by the
    stalled output changing, and by the vectors it loses.  A block of interval ``I`` > 1
    holds ``i.ready`` low for the ``I − 1`` moves after it takes a vector, moving where
    ``o.ready`` is high or ``o.valid`` low (its Handshake's enable): the model counts those
    moves too.  ``records`` holds the first ``max_report``
    mismatches as ``(cycle, kind, index, got_valid, got_payload, want_valid, want_payload)``.
    """

    def __init__(self, plan, packed_in, packed_out, max_report=10):
        self.plan = plan
        self.vectors = packed_in
        self.expected = packed_out
        self.max_report = max_report
        self.next = 0  # the vector to offer next
        self.offering = False  # i.valid is high with vector ``next``, held until taken
        self.delivered = 0  # the vector the next transfer out must be
        self.held = None  # payload of a valid output that was not taken at the last edge
        self.moves = 0  # edges where the pipeline moved since the last reset
        self.busy = 0  # moves before the block takes its next vector (its interval)
        self.ring = [-1] * (plan.latency + 1)  # what entered at each of the last moves
        self.in_reset = False
        self.drain = None
        self.cycles = 0
        self.stall_cycles = self.resets = self.resent = 0
        self.records = []
        self.mismatch_count = 0

    def drive(self, cycle):
        """``(rst, i.valid, i.payload, o.ready)`` of ``cycle``."""
        ctl = int(self.plan.control[cycle])
        junk = self.plan.junk[cycle % len(self.plan.junk)]
        ready = int(bool(ctl & READY))
        if ctl & RESET:
            self.offering = False
            return 1, 0, junk, ready
        if not self.offering and self.next < self.plan.count and not ctl & IDLE:
            self.offering = True
        return 0, int(self.offering), self.vectors[self.next] if self.offering else junk, ready

    def _record(self, *record):
        self.mismatch_count += 1
        if len(self.records) < self.max_report:
            self.records.append(record)

    def observe(self, cycle, i_ready, o_valid, o_payload):
        """Check the settled outputs of ``cycle``, then clock the model; False when the run is over."""
        plan = self.plan
        ctl = int(plan.control[cycle])
        rst, ready = bool(ctl & RESET), bool(ctl & READY)
        k = self.moves - plan.latency
        source = self.ring[k % len(self.ring)] if k >= 0 else -1
        want_valid = int(source >= 0)
        transfer = o_valid and ready and not rst
        if o_valid != want_valid:
            self._record(cycle, VALID, source, o_valid, o_payload, want_valid, 0)
        elif self.held is not None and (not o_valid or o_payload != self.held):
            self._record(cycle, HELD, self.delivered, o_valid, o_payload, 1, self.held)
        elif transfer and self.delivered >= plan.count:
            self._record(cycle, EXTRA, -1, o_valid, o_payload, 0, 0)
        elif transfer and o_payload != self.expected[self.delivered]:
            self._record(cycle, PAYLOAD, self.delivered, o_valid, o_payload, 1,
                         self.expected[self.delivered])

        if rst:
            # what was in flight is lost: offer it again, from a scanline's start if need be
            resume = int(plan.resume[self.delivered]) if self.delivered < plan.count else self.delivered
            if not self.in_reset:
                self.resets += 1
                self.resent += max(0, self.next - resume)
            self.in_reset = True
            self.next = self.delivered = resume
            self.moves = 0
            self.busy = 0
            self.held = None
        else:
            self.in_reset = False
            taken = self.offering and i_ready
            # the pipeline moves where the design is ready, or busy with a vector's turns
            moving = i_ready or (self.busy > 0 and (ready or not o_valid))
            if moving:
                self.ring[self.moves % len(self.ring)] = self.next if taken else -1
                self.moves += 1
            if taken:
                self.busy = plan.interval - 1
            elif moving and self.busy:
                self.busy -= 1
            if taken:
                self.next += 1
                self.offering = False
            self.delivered += transfer
            stalled = o_valid and not ready
            self.stall_cycles += stalled
            self.held = o_payload if stalled else None

        self.cycles = cycle + 1
        if self.drain is not None:
            self.drain -= 1
        elif self.delivered >= plan.count and self.cycles >= plan.quiet_from:
            self.drain = plan.drain
        if self.drain == 0 or self.cycles == plan.limit:
            if self.delivered < plan.count:
                self._record(cycle, LOST, self.delivered, 0, 0, 0, 0)
            return False
        return True


def stream_mismatch(config, inputs, expected, plan, cycle, kind, index, got_valid, got_payload,
                    want_valid, want_payload):
    """The :class:`Mismatch` of a stream-mode record (see :class:`StreamChecker`)."""
    ports = checked_outputs(config)

    def output(payload):
        return row_of(ports, unpack(ports, [payload]), 0)

    row = row_of(config.inputs, inputs, index) if index >= 0 else {}
    if kind == VALID:
        return Mismatch(cycle, index, row, {"valid": want_valid}, {"valid": got_valid},
                        f"o.valid is {got_valid}, expected {want_valid} (latency {plan.latency}, "
                        f"counted in cycles where the pipeline moves)")
    if kind == PAYLOAD:
        return payload_mismatch(config, inputs, expected, index, cycle, got_payload)
    if kind == HELD and not got_valid:
        return Mismatch(cycle, index, row, {"valid": 1}, {"valid": 0},
                        "a stalled valid output was withdrawn before it was taken")
    if kind == HELD:
        return Mismatch(cycle, index, row, output(want_payload), output(got_payload),
                        "a stalled valid output changed before it was taken")
    if kind == EXTRA:
        return Mismatch(cycle, index, row, {}, output(got_payload),
                        f"a transfer beyond the {plan.count} vectors: one came out twice")
    if kind == LOST:
        return Mismatch(cycle, index, row, {}, {},
                        f"{plan.count - index} of {plan.count} vectors never came out (lost), "
                        f"the first #{index}")
    raise ValueError(f"unknown stream mismatch kind {kind}")


def handshake_component(block, handshake=None):
    """``block``'s component inside ``handshake`` (default :class:`~phongfx.hdl.handshake.Handshake`),
    with a message naming the block if its latency is 0 (no registered ``o.valid`` to stall on)."""
    from phongfx.hdl.block import unbuilt
    from phongfx.hdl.handshake import Handshake

    component = block.component()
    if component.latency < 1:
        unbuilt(component)
        raise ValueError(f"{block.name} has latency 0: stalls and reset_at run it inside Handshake, "
                         f"which needs at least one register (o.valid from a register)")
    return (handshake or Handshake)(component)
