"""Back end: the emitted Verilog under Verilator, checked in compiled code.

The fast path, for checking whole frames cycle by cycle in seconds (a 1080p frame
through Figure 7): no cocotb and no Python in the simulation loop.  Python packs the
per-cycle input words and the expected per-cycle output words with numpy into one
binary stream; a small C++ main (``fast_main.cpp``, linked with the Verilated design)
maps it, drives the design clock by clock, compares every cycle's ``o.valid`` and (when
valid) ``o.payload``, and writes back only a summary: the cycle count, the number of
mismatching cycles, and the first ``max_report`` of them with their cycle and words.

Words are 32-bit, least significant first, as Verilator's ``VlWide`` stores a
wide port, so payloads of any width (Figure 7's input is 204 bits) need no
special case: the simulated top is :mod:`phongfx.sim.fast_top`'s.

Back-pressure and reset (``stalls``, ``reset_at``: the stream mode of
:mod:`phongfx.sim.harness`) cannot be a precomputed per-cycle stream, since when a vector
is taken depends on the design's ``i.ready``.  The checker then runs the harness's
:class:`~phongfx.sim.stream.StreamChecker` in C++ (mode 2 of ``fast_main.cpp``): Python
passes the vectors, the expected outputs in order, where to resume after a reset, and one
control byte per cycle (the ``o.ready``, idle and reset decisions of a
:class:`~phongfx.sim.stream.StreamPlan`, drawn with numpy), so the C++ only follows them.  The simulated top is then
:class:`~phongfx.hdl.handshake.Handshake` around the block, with ``rst`` and ``o.ready``
on a ``ctl`` port; without stalls the top and the loop are the fast path's as before.

``vcd=PATH`` builds with Verilator's ``--trace`` (a flavour of its own in the cache) and
writes the waveform of the run.

Builds share :mod:`phongfx.sim.verilator_backend`'s tool environment and the build and
run-time object caches of :mod:`phongfx.sim.build_cache` (in a flavour of their own, as
the flags differ).
"""

import subprocess
import tempfile
import time
from pathlib import Path

import numpy as np

from phongfx.hdl.block import checked_outputs
from phongfx.hdl.emit import payload_widths

from .fast_build import EXECUTABLE, build
from .fast_top import words_of
from .result import Mismatch, Result, checked_expected, payload_mismatch
from .stream import handshake_component, plan_stream, restart_points, stream_mismatch, stream_mode
from .vectors import columns, payload_fields, row_of, schedule

__all__ = ["pack_words", "checked_build", "stream", "check",
           "check_timed", "run"]

_MAGIC = 0x3274736166786670  # "pfxfast2", as in fast_main.cpp
_HEADER = 16  # uint64 words


def pack_words(ports, raw, valid=True):
    """Pack raw codes into the words ``{payload, valid}``, vectorized.

    Parameters
    ----------
    ports : dict
        ``{name: (Format, lanes)}``, as a block config's ``inputs`` or ``outputs``.
    raw : dict of int64 arrays
        ``{name: (count,) or (count, lanes)}``.
    valid : bool
        Value of bit 0 of every word.

    Returns
    -------
    numpy.ndarray
        ``(count, words_of(width + 1))`` uint32, bit ``k`` of the payload at bit
        ``k + 1``, as :func:`phongfx.sim.vectors.pack` shifted left by one.
    """
    _, width = payload_fields(ports)
    out = None
    for column, offset, bits in columns(ports, raw):
        if out is None:
            out = np.zeros((len(column), words_of(width + 1)), dtype=np.uint32)
            out[:, 0] = int(valid)
        # two's complement bits of the code: the int64 to uint64 cast wraps
        value = column.astype(np.uint64) & np.uint64((1 << bits) - 1)
        start = offset + 1
        first, shift = divmod(start, 32)
        # a field of up to 64 bits spans up to three words
        for word in range(first, (start + bits - 1) // 32 + 1):
            amount = 32 * (word - first) - shift
            part = value << np.uint64(-amount) if amount < 0 else value >> np.uint64(amount)
            out[:, word] |= (part & np.uint64(0xFFFFFFFF)).astype(np.uint32)
    return out


def _to_int(words):
    return int.from_bytes(np.ascontiguousarray(words, dtype="<u4").tobytes(), "little")


def checked_build(block, streaming, *, handshake=None, build_dir=None, design=None, vcd=None, optimize=True):
    """``(latency, interval, Build)``: the simulator :func:`check_timed` runs ``block`` on (inside
    ``handshake`` when ``streaming``; :func:`build`'s arguments), built or found in the cache, so
    that a caller may build it ahead of the check (the compiler does, beside its witness search)."""
    component = handshake_component(block, handshake) if streaming else block.component()
    return component.latency, component.interval, build(component, build_dir=build_dir, design=design,
                                                        trace=bool(vcd), optimize=optimize)


def _execute(compiled, header, arrays, vcd=None):
    """Write the stream, run the checker on it (writing waveform ``vcd`` if given: a
    ``trace`` build); returns (result bytes, seconds split)."""
    run_dir = Path(tempfile.mkdtemp(prefix="fast-", dir=compiled.directory))
    stream_, result = run_dir / "stream.bin", run_dir / "result.bin"
    start = time.perf_counter()
    with open(stream_, "wb") as file:
        file.write(np.array(list(header) + [0] * (_HEADER - len(header)), dtype="<u8").tobytes())
        for array in arrays:
            file.write(memoryview(np.ascontiguousarray(array, dtype="<u4")).cast("B"))
    written = time.perf_counter()
    done = subprocess.run([str(compiled.directory / EXECUTABLE), str(stream_), str(result),
                           *([str(Path(vcd).resolve())] if vcd else [])],
                          capture_output=True, text=True)
    simulated = time.perf_counter()
    if done.returncode:
        raise RuntimeError(f"Verilator fast check of {compiled.top} failed (exit "
                           f"{done.returncode}); run directory {run_dir}:\n{done.stderr[-2000:]}")
    data = result.read_bytes()
    for file in (stream_, result):
        file.unlink()
    run_dir.rmdir()
    return data, {"write": written - start, "simulate": simulated - written}


def stream(block, inputs, expected, slots, latency, seed):
    """Per-cycle input and expected output words of a ``slots`` schedule (see :func:`check`)."""
    config = block.config
    _, in_width = payload_fields(config.inputs)
    vectors = pack_words(config.inputs, inputs)
    results = pack_words(checked_outputs(config), checked_expected(expected))
    cycles = len(slots) + latency
    in_words = np.zeros((cycles, vectors.shape[1]), dtype=np.uint32)
    busy = slots >= 0
    in_words[:len(slots)][busy] = vectors[slots[busy]]
    idle = np.flatnonzero(~busy)
    if len(idle):
        # junk payload (valid low) on bubbles, to show the design ignores it
        rng = np.random.default_rng(seed + 1)
        junk = rng.integers(0, 1 << 32, size=(len(idle), vectors.shape[1]), dtype=np.uint32)
        ones = np.zeros(32 * vectors.shape[1], dtype=np.uint8)
        ones[1:in_width + 1] = 1
        mask = np.packbits(ones, bitorder="little").view("<u4")
        in_words[idle] = junk & mask
    want = np.zeros((cycles, results.shape[1]), dtype=np.uint32)
    # the vector whose result is due at each cycle, -1 if none
    source = np.full(cycles, -1, dtype=np.int64)
    source[latency:] = slots
    live = source >= 0
    want[live] = results[source[live]]
    return in_words, want


def check_timed(block, inputs=None, *, expected=None, bubbles=0.25, seed=0, count=1000,
                max_report=10, build_dir=None, design=None, stalls=0.0, reset_at=None, reset_cycles=2,
                handshake=None, vcd=None, optimize=True):
    """:func:`check`, also returning the seconds spent in each step; ``optimize``: as
    :func:`build`'s.

    Returns
    -------
    (Result, dict)
        The dict has ``vectors``, ``golden``, ``build``, ``pack``, ``write``,
        ``simulate`` (simulation and comparison in the C++ checker) and ``report``.
    """
    config = block.config
    streaming = stream_mode(stalls, reset_at)
    if streaming and design is not None:
        raise ValueError("stalls and reset_at run the RTL inside Handshake; a netlist design has no "
                         "ready to stall")
    times = {}
    start = time.perf_counter()
    if inputs is None:
        inputs = block.stimulus(count=count, seed=seed)
    times["vectors"] = time.perf_counter() - start
    start = time.perf_counter()
    if expected is None:
        expected = block.golden(inputs)
    times["golden"] = time.perf_counter() - start

    start = time.perf_counter()
    latency, interval, compiled = checked_build(block, streaming, handshake=handshake, build_dir=build_dir,
                                                design=design, vcd=vcd, optimize=optimize)
    times["build"] = time.perf_counter() - start
    if streaming:
        return _check_stream(block, inputs, expected, compiled, (latency, interval), times, bubbles=bubbles, seed=seed,
                             max_report=max_report, stalls=stalls, reset_at=reset_at,
                             reset_cycles=reset_cycles, vcd=vcd)

    start = time.perf_counter()
    count = len(np.asarray(next(iter(inputs.values()))))
    slots = schedule(count, bubbles, seed, interval)
    in_words, want = stream(block, inputs, expected, slots, latency, seed)
    cycles, ni = in_words.shape
    no = want.shape[1]
    times["pack"] = time.perf_counter() - start

    data, split = _execute(compiled, [_MAGIC, cycles, ni, no, max_report, 0], [in_words, want], vcd)
    times.update(split)
    start = time.perf_counter()
    ran, mismatches, recorded = np.frombuffer(data[:24], dtype="<u8").tolist()
    if ran != cycles:
        raise RuntimeError(f"Verilator fast check ran {ran} cycles, expected {cycles}")
    result = Result(block.name, "verilator-fast", count, cycles,
                    times["write"] + times["simulate"])
    record = np.dtype([("cycle", "<u8"), ("got", "<u4", no), ("want", "<u4", no)])
    for entry in np.frombuffer(data[24:], dtype=record, count=recorded):
        cycle = int(entry["cycle"])
        index = int(slots[cycle - latency]) if cycle >= latency else -1
        got_valid, want_valid = int(entry["got"][0] & 1), int(entry["want"][0] & 1)
        if got_valid != want_valid:
            result.mismatches.append(Mismatch(
                cycle, index, row_of(config.inputs, inputs, index) if index >= 0 else {},
                {"valid": want_valid}, {"valid": got_valid},
                f"o.valid is {got_valid}, expected {want_valid} (latency {latency})"))
        else:
            result.mismatches.append(payload_mismatch(config, inputs, expected, index, cycle,
                                                      _to_int(entry["got"]) >> 1))
    result.mismatch_count = int(mismatches)
    times["report"] = time.perf_counter() - start
    return result, times


def _check_stream(block, inputs, expected, compiled, timing, times, *, bubbles, seed, max_report, stalls,
                  reset_at, reset_cycles, vcd):
    """:func:`check_timed`'s stream mode: the plan's decisions in, mode 2 of ``fast_main.cpp``;
    ``timing`` the component's ``(latency, interval)``."""
    config = block.config
    latency, interval = timing
    start = time.perf_counter()
    vectors = pack_words(config.inputs, inputs)
    results = pack_words(checked_outputs(config), checked_expected(expected))
    count, ni = vectors.shape
    no = results.shape[1]
    _, in_width = payload_fields(config.inputs)
    plan = plan_stream(count, latency, in_width, stalls=stalls, bubbles=bubbles, reset_at=reset_at,
                       reset_cycles=reset_cycles, seed=seed, restarts=restart_points(config, inputs),
                       interval=interval)
    junk = np.frombuffer(b"".join((j << 1).to_bytes(4 * ni, "little") for j in plan.junk), dtype="<u4")
    control = np.zeros(-(-plan.limit // 4) * 4, dtype=np.uint8)
    control[:plan.limit] = plan.control
    times["pack"] = time.perf_counter() - start

    header = [_MAGIC, plan.limit, ni, no, max_report, 2, count, len(plan.junk), latency, plan.quiet_from,
              plan.drain, plan.interval]
    data, split = _execute(compiled, header, [vectors, results, junk, plan.resume.astype("<u4"),
                                              control.view("<u4")], vcd)
    times.update(split)
    start = time.perf_counter()
    cycles, mismatches, recorded, _, stall_cycles, resets, resent, _ = \
        np.frombuffer(data[:64], dtype="<u8").tolist()
    result = Result(block.name, "verilator-fast", count, cycles, times["write"] + times["simulate"],
                    mismatch_count=mismatches, stall_cycles=stall_cycles, resets=resets, resent=resent)
    record = np.dtype([("cycle", "<u8"), ("kind", "<u8"), ("index", "<i8"), ("got", "<u4", no),
                       ("want", "<u4", no)])
    for entry in np.frombuffer(data[64:], dtype=record, count=recorded):
        got, want = _to_int(entry["got"]), _to_int(entry["want"])
        result.mismatches.append(stream_mismatch(config, inputs, expected, plan, int(entry["cycle"]),
                                                 int(entry["kind"]), int(entry["index"]), got & 1, got >> 1,
                                                 want & 1, want >> 1))
    times["report"] = time.perf_counter() - start
    return result, times


def check(block, inputs=None, *, expected=None, bubbles=0.25, seed=0, count=1000,
          max_report=10, build_dir=None, design=None, stalls=0.0, reset_at=None, reset_cycles=2,
          handshake=None, vcd=None, optimize=True):
    """:func:`phongfx.sim.harness.check` on the fast path; same arguments and :class:`Result`;
    ``optimize``: as :func:`build`'s.

    ``Result.seconds`` covers writing the stream and the compiled simulate-and-compare
    run, not the golden model, packing or the build (see :func:`check_timed`).
    """
    return check_timed(block, inputs, expected=expected, bubbles=bubbles, seed=seed,
                       count=count, max_report=max_report, build_dir=build_dir, design=design,
                       stalls=stalls, reset_at=reset_at, reset_cycles=reset_cycles,
                       handshake=handshake, vcd=vcd, optimize=optimize)[0]


def run(component, in_valid, in_payload, cycles, *, build_dir=None):
    """The :func:`phongfx.sim.harness.run_backend` contract: per-cycle outputs, no comparing.

    Returns
    -------
    (list of int, list of int)
        ``o.valid`` and packed ``o.payload`` of each cycle.
    """
    if cycles == 0:
        return [], []
    if len(in_valid) < cycles or len(in_payload) < cycles:
        raise ValueError(f"need {cycles} cycles of stimulus, got {len(in_valid)} valid "
                         f"and {len(in_payload)} payload values")
    in_width, out_width = payload_widths(component)
    ni, no = words_of(in_width + 1), words_of(out_width + 1)
    mask = (1 << in_width) - 1
    data = b"".join(((int(p) & mask) << 1 | int(v) & 1).to_bytes(4 * ni, "little")
                    for v, p in zip(in_valid[:cycles], in_payload[:cycles]))
    compiled = build(component, build_dir=build_dir)
    out, _ = _execute(compiled, [_MAGIC, cycles, ni, no, 0, 1], [np.frombuffer(data, dtype="<u4")])
    words = np.frombuffer(out, dtype="<u4").reshape(cycles, no)
    values = [_to_int(row) for row in words]
    return [w & 1 for w in values], [w >> 1 for w in values]
