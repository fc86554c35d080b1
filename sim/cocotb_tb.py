"""cocotb test run inside the simulator by :mod:`phongfx.sim.verilator_backend`.

It is not a pytest module: ``cocotb_tools.runner`` names it as the test module and
the simulator imports it.  The run directory comes in ``$PHONGFX_TB_DIR``; it holds
``stimulus.txt`` (first line: the cycle count; then one line per cycle,
``valid hex_payload``) and receives ``results.txt`` in the same format, written
only once every cycle has run, so the caller never sees partial results.

Cycle ``t`` spans 10 ns: at ``10t`` the clock falls and the inputs of cycle ``t``
are written; at ``10t + 5`` the outputs, settled on those inputs, are read and the
clock rises.  That is the Amaranth back end's order (set, read settled, tick).
"""

import os
from pathlib import Path

import cocotb
from cocotb.triggers import Timer

__all__ = ["drive"]

STIMULUS = "stimulus.txt"
RESULTS = "results.txt"


def read_stimulus(path):
    """(valid list, payload list) from a stimulus file."""
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


@cocotb.test()
async def drive(dut):
    """Drive every stimulus cycle and record the settled outputs of each."""
    run_dir = Path(os.environ["PHONGFX_TB_DIR"])
    in_valid, in_payload = read_stimulus(run_dir / STIMULUS)
    cycles = len(in_valid)
    clk, rst = dut.clk, dut.rst
    i_valid, i_payload = dut.i__valid, dut.i__payload
    o_valid, o_payload = dut.o__valid, dut.o__payload
    # Convert before the loop: a binary string is what the VPI write takes for
    # signals over 32 bits anyway, and it keeps the per-cycle work to the writes.
    width = len(i_payload)
    if width > 32:
        in_payload = [format(p, f"0{width}b") for p in in_payload]
    half = Timer(5, unit="ns")

    rst.value = 0
    got_valid = [None] * cycles
    got_payload = [None] * cycles
    for cycle in range(cycles):
        clk.value = 0
        i_valid.value = in_valid[cycle]
        i_payload.value = in_payload[cycle]
        await half
        got_valid[cycle] = o_valid.value
        got_payload[cycle] = o_payload.value
        clk.value = 1
        await half

    # int() of a value holding X or Z raises, failing the test rather than
    # inventing bits.
    write_vectors(run_dir / RESULTS, [int(v) for v in got_valid],
                  [p.to_unsigned() for p in got_payload])
