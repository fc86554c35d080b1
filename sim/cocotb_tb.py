"""cocotb test run inside the simulator by :mod:`phongfx.sim.verilator_backend`.

It is not a pytest module: ``cocotb_tools.runner`` names it as the test module and
the simulator imports it.  ``$PHONGFX_TB_DIR`` names the run directory, which holds
``stimulus.txt`` (first line: the cycle count; then one line per cycle,
``valid hex_payload``) and receives ``results.txt`` in the same format, written
only once every cycle has run, so the caller never sees partial results.  Before it,
``seconds.txt`` receives the seconds the clocked run took: the simulation alone, without
the Verilator build, the simulator's start or the reading and writing of the files, so
that cycles per second measure the simulator (they varied 20-fold with the build's cache).

The simulated top is the back end's wrapper (see
:func:`phongfx.sim.verilator_backend.wrapper`): ``stim`` holds the input words
``{i.payload, i.valid}`` of ``$PHONGFX_TB_BLOCK`` consecutive cycles, word ``j``
in the ``j``-th slice, and ``resp`` collects ``{o.payload, o.valid}`` the same way,
each captured at its cycle's rising edge.  The clock (10 ns, low first, rising at
``10t + 5``) runs in cocotb's C layer; Python wakes once a block, 2 ns into its
first cycle, to read the previous block's ``resp`` and write this block's
``stim``, so the Python cost is spread over the block.
"""

import os
import time
from pathlib import Path

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import Timer

__all__ = ["drive", "read_vectors", "write_vectors", "STIMULUS", "RESULTS", "SECONDS"]

STIMULUS = "stimulus.txt"
RESULTS = "results.txt"
SECONDS = "seconds.txt"
PERIOD_NS = 10
PHASE_NS = 2  # inside the low half, away from both clock edges


def read_vectors(path):
    """(valid list, payload list) from a stimulus or results file."""
    with open(path) as file:
        cycles = int(file.readline())
        valid = []
        payload = []
        for line in file:
            v, p = line.split()
            valid.append(int(v))
            payload.append(int(p, 16))
    if len(valid) != cycles:
        raise ValueError(f"{path}: header says {cycles} cycles, found {len(valid)}")
    return valid, payload


def write_vectors(path, valid, payload):
    """Write ``valid``/``payload`` lists atomically (temp file, then rename)."""
    path = Path(path)
    temp = path.with_name(path.name + ".tmp")
    with open(temp, "w") as file:
        file.write(f"{len(valid)}\n")
        file.writelines(f"{v} {p:x}\n" for v, p in zip(valid, payload))
    os.replace(temp, path)


def _blocks(valid, payload, block, word):
    """Binary strings of ``block`` input words each, cycle ``j`` of a block in slice ``j``."""
    words = [p << 1 | v for v, p in zip(valid, payload)]
    words += [0] * (-len(words) % block)  # idle padding after the last cycle
    out = []
    for start in range(0, len(words), block):
        packed = 0
        for j, w in enumerate(words[start:start + block]):
            packed |= w << (j * word)
        out.append(format(packed, f"0{block * word}b"))
    return out


@cocotb.test()
async def drive(dut):
    """Drive every stimulus cycle and record the settled outputs of each."""
    run_dir = Path(os.environ["PHONGFX_TB_DIR"])
    block = int(os.environ["PHONGFX_TB_BLOCK"])
    in_valid, in_payload = read_vectors(run_dir / STIMULUS)
    cycles = len(in_valid)
    stim, resp = dut.stim, dut.resp
    in_word, out_word = len(stim) // block, len(resp) // block
    # Strings made before the loop leave each wake a single write and read.
    stimulus = _blocks(in_valid, in_payload, block, in_word)

    start = time.perf_counter()
    Clock(dut.clk, PERIOD_NS, unit="ns").start(start_high=False)
    await Timer(PHASE_NS, unit="ns")
    period = Timer(block * PERIOD_NS, unit="ns")
    got = []
    for words in stimulus:
        stim.value = words
        await period
        got.append(resp.value)
    seconds = time.perf_counter() - start

    # to_unsigned() of a value holding X or Z raises, failing the test rather
    # than inventing bits.
    mask = (1 << out_word) - 1
    words = []
    for value in got:
        packed = value.to_unsigned()
        words.extend(packed >> (j * out_word) & mask for j in range(block))
    del words[cycles:]
    (run_dir / SECONDS).write_text(f"{seconds!r}\n")
    write_vectors(run_dir / RESULTS, [w & 1 for w in words], [w >> 1 for w in words])
