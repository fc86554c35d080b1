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

Back-pressure and reset (``stalls``, ``reset_at``; the ``amaranth`` and ``verilator-fast``
back ends) run the *stream mode* of :mod:`phongfx.sim.stream`.  The vocabulary shared by
every back end lives below this module: :mod:`phongfx.sim.vectors` (payload words, the
per-cycle schedule), :mod:`phongfx.sim.result` (:class:`Result`, :class:`Mismatch`) and
:mod:`phongfx.sim.stream`; this module re-exports their names, so ``from
phongfx.sim.harness import pack`` keeps working.
"""

import time

import numpy as np

from phongfx.hdl.block import checked_outputs

from .result import HarnessMismatch, Mismatch, Result, checked_expected, payload_mismatch
from .stream import (EXTRA, HELD, IDLE, LOST, PAYLOAD, READY, RESET, VALID, StreamChecker, StreamPlan,
                     handshake_component, plan_stream, restart_points, stream_mismatch, stream_mode)
from .vectors import columns, pack, payload_fields, row_of, schedule, unpack

__all__ = ["BACKENDS", "STREAM_BACKENDS", "READY", "IDLE", "RESET", "VALID", "PAYLOAD", "HELD", "EXTRA",
           "LOST", "Mismatch", "Result", "HarnessMismatch", "payload_fields", "columns", "pack", "unpack",
           "schedule", "StreamPlan", "stream_mode", "restart_points", "plan_stream", "StreamChecker",
           "stream_mismatch", "handshake_component", "row_of", "checked_expected", "payload_mismatch",
           "check", "run_backend"]

BACKENDS = ("amaranth", "verilator", "verilator-fast")
#: The back ends that run the stream mode (``stalls``, ``reset_at``).
STREAM_BACKENDS = ("amaranth", "verilator-fast")


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
          count=1000, max_report=10, stalls=0.0, reset_at=None, reset_cycles=2, handshake=None,
          **options):
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
    stalls : float or sequence of bool
        Probability that ``o.ready`` is low in a cycle, or a pattern of such cycles (True:
        low) repeated over the run.  Non-zero, it runs the stream mode (module docstring):
        the block inside :class:`~phongfx.hdl.handshake.Handshake`, a driver that offers
        each vector until taken, transfers compared in order, stalled outputs held.
    reset_at : int, optional
        A cycle at which ``rst`` rises for ``reset_cycles`` cycles (stream mode too): the
        vectors in flight are lost and re-sent, each vector must still come out once (a
        scanline block's from its ``init`` again, :func:`restart_points`).  Two cycles by
        default, so that the check sees ``o.valid`` stay low while the reset is held.
    handshake : type, optional
        The stream-mode wrapper class (default ``Handshake``; a test passes a broken one).
    options
        Passed to the back end (``vcd=PATH``, a waveform, on every back end; ``build_dir`` ...).

    ``stalls`` and ``reset_at`` run on the ``amaranth`` and ``verilator-fast`` back ends
    (:data:`STREAM_BACKENDS`); the cocotb one, whose testbench feeds the design fixed
    windows of cycles without looking at its outputs, raises ``ValueError``.

    Returns
    -------
    Result
        With stalls or a reset, ``cycles`` is how long the run took (it ends ``latency + 2``
        cycles after the last delivery), ``stall_cycles``, ``resets`` and ``resent`` count
        what the stream mode exercised.
    """
    streaming = stream_mode(stalls, reset_at)
    if streaming and backend not in STREAM_BACKENDS:
        if backend in BACKENDS:
            raise ValueError(f"stalls are supported on the amaranth and verilator-fast back ends "
                             f"(reset_at too), not on {backend}")
        raise ValueError(f"backend must be one of {', '.join(BACKENDS)}, not {backend!r}")
    if backend == "verilator-fast":
        from .fast_backend import check as fast_check

        stream = dict(stalls=stalls, reset_at=reset_at, reset_cycles=reset_cycles, handshake=handshake) \
            if streaming else {}
        return fast_check(block, inputs, expected=expected, bubbles=bubbles, seed=seed,
                          count=count, max_report=max_report, **stream, **options)
    config = block.config
    if inputs is None:
        inputs = block.stimulus(count=count, seed=seed)
    if expected is None:
        expected = block.golden(inputs)
    packed_in = pack(config.inputs, inputs)
    packed_out = pack(checked_outputs(config), checked_expected(expected))
    count = len(packed_in)
    if streaming:
        return _check_stream(block, inputs, expected, packed_in, packed_out, bubbles=bubbles, seed=seed,
                             stalls=stalls, reset_at=reset_at, reset_cycles=reset_cycles,
                             handshake=handshake, max_report=max_report, **options)

    component = block.component()
    slots = schedule(count, bubbles, seed, component.interval)
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
            junk = int.from_bytes(rng.bytes((in_width + 7) // 8), "little")
            in_payload[cycle] = junk & ((1 << in_width) - 1)
    for cycle in range(len(slots), cycles):
        in_payload[cycle] = 0

    # the cocotb back end times its clocked run itself: a wall clock here would also count
    # the Verilator build (minutes uncached) and the simulator's start
    timing = {} if backend == "verilator" else None
    start = time.perf_counter()
    out_valid, out_payload = run_backend(backend, component, in_valid, in_payload, cycles,
                                         **options, **({"timing": timing} if timing is not None else {}))
    seconds = (timing or {}).get("simulate", time.perf_counter() - start)

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


def _check_stream(block, inputs, expected, packed_in, packed_out, *, bubbles, seed, stalls, reset_at,
                  reset_cycles, handshake, max_report, **options):
    """:func:`check`'s stream mode on the amaranth back end."""
    from .amaranth_backend import run_stream

    config = block.config
    component = handshake_component(block, handshake)
    _, in_width = payload_fields(config.inputs)
    plan = plan_stream(len(packed_in), component.latency, in_width, stalls=stalls, bubbles=bubbles,
                       reset_at=reset_at, reset_cycles=reset_cycles, seed=seed,
                       restarts=restart_points(config, inputs), interval=component.interval)
    checker = StreamChecker(plan, packed_in, packed_out, max_report)
    start = time.perf_counter()
    run_stream(component, checker, **options)
    seconds = time.perf_counter() - start
    result = Result(block.name, "amaranth", plan.count, checker.cycles, seconds,
                    mismatch_count=checker.mismatch_count, stall_cycles=checker.stall_cycles,
                    resets=checker.resets, resent=checker.resent)
    result.mismatches = [stream_mismatch(config, inputs, expected, plan, *record)
                         for record in checker.records]
    return result
