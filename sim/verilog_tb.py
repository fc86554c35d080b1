"""The text of a self-checking Verilog testbench of a block's shipped top.

:func:`verilog_testbench` writes ``tb_<name>``, the testbench that
:func:`phongfx.sim.testbench.write_testbench` puts beside the top; it is plain Verilog
(the subset Icarus Verilog ``-g2012`` and Verilator ``--binary`` both run unchanged).

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
(:func:`phongfx.sim.testbench.restart_point`): a vector from which the golden model, run from reset, gives
the same outputs as in the whole stream.  Nothing is counted as a transfer while ``rst``
is high.  The testbench ends with ``PASS <n> vectors, <cycles> cycles`` or ``FAIL``
lines (the first :data:`MAX_REPORT` errors: vector, field, got, expected) and
``$finish``; a cycle time-out prints ``FAIL`` too.
"""

from phongfx.hdl.comment import comment
from phongfx.hdl.top import port_map

from .vectors import payload_fields

__all__ = ["LINT_WAIVERS", "MAX_REPORT", "RESET_CYCLES", "MID_RESET_CYCLES", "verilog_testbench"]

#: Errors the testbench prints before its verdict.
MAX_REPORT = 5
#: Verilator ``-Wall`` classes waived in the testbench, and why each is no defect.
LINT_WAIVERS = {
    "BLKSEQ": "the checker is a program run at each clock edge (counters, generators, the "
              "verdict, in order), not logic, so it assigns with =",
    "PROCASSINIT": "its variables start at their declared values, which the clocked process then updates",
    "UNUSEDSIGNAL": "a bubble's junk payload is whole 32-bit words of the generators, of which the "
                    "payload's width is used",
}
#: Rising edges with ``rst`` high at the start, and at the mid-stream reset.
RESET_CYCLES = 4
MID_RESET_CYCLES = 2


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


def _value(word, port):
    """The port's field of ``word`` as a 65-bit signed operand, its code sign-extended if
    signed: written out at 65 bits, so that lint sees no implicit extension."""
    extra, msb = 65 - port["width"], port["offset"] + port["width"] - 1
    pad = f"{{{extra}{{{word}[{msb}]}}}}" if port["signed"] else f"{extra}'h0"
    return f"$signed({{{pad}, {word}{_slice(port)}}})"


def verilog_testbench(config, name, count, latency, *, reset_at, seed=1, stall=0.3, bubbles=0.2, vcd=False,
                      timeout=None, reset_cycles=RESET_CYCLES, interval=1):
    """The text of ``tb_<name>``, the testbench of ``<name>_top`` (see the module docstring).

    ``count`` vectors are read from ``<name>_in.memh`` and ``<name>_expected.memh``;
    ``reset_at`` is the number of results delivered when the mid-stream reset comes
    (below ``count``); ``timeout`` the cycle limit (default: generous for the stalls);
    ``reset_cycles`` the edges with ``rst`` high at the start (0: none, which checks the
    top from power-up); ``interval`` the top's clocks per vector (its in_ready says when it
    takes one; only the default time-out counts it).
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
        moves = (2 * count * interval + 2 * latency + 64) / ((1 - stall) * (1 - bubbles))
        timeout = int(4 * moves) + 1000
    width = max(len(p["name"]) for p in ports)
    connections = [".clk(clk)", ".rst(rst)", ".in_valid(in_valid)", ".in_ready(in_ready)",
                   *(f".{p['name']}(in_word{_slice(p)})" for p in inputs),
                   ".out_valid(out_valid)", ".out_ready(out_ready)",
                   *(f".{p['name']}(out_word{_slice(p)})" for p in outputs)]
    connections = ",\n    ".join(connections)
    compares = "\n".join(
        f"        if (out_word{_slice(p)} !== expected[delivered]{_slice(p)})\n"
        f"          mismatch(delivered, \"{p['name']}\", {_value('out_word', p)},\n"
        f"                   {_value('expected[delivered]', p)});"
        for p in outputs)
    dump = (f"    $dumpfile(\"tb_{name}.vcd\");\n    $dumpvars(0, tb_{name});\n") if vcd else ""
    junk_words = (in_width + 31) // 32
    start = f"applies rst for {reset_cycles} cycles" if reset_cycles else "starts without a reset (power-up)"
    about = comment(
        f"tb_{name}: self-checking testbench of {name}_top, written by phongfx (sim/testbench.py). "
        f"Runs unchanged under Icarus Verilog (iverilog -g2012) and Verilator (--binary): see README.txt. "
        f"It {start}, streams the {count} vectors of {name}_in.memh with pseudo-random in_valid bubbles "
        f"and out_ready stalls (xorshift32, seeded here: the same cycles in every simulator), resets the "
        f"top once mid-stream with results in flight (and out_ready low) and re-sends from the first "
        f"vector not yet delivered, and compares every transfer (out_valid & out_ready) in order, field "
        f"by field, with {name}_expected.memh.  It also checks that out_valid and out_* hold while "
        f"out_ready is low, and that out_valid is low while nothing is in flight.  Nothing is counted "
        f"as a transfer while rst is high.  It prints \"PASS <n> vectors, <cycles> cycles\" or FAIL "
        f"lines, then $finish.", width=94)
    waivers = "".join(comment(f"{cls}: {reason}.", width=94, indent="  ") + f"/* verilator lint_off {cls} */\n"
                      for cls, reason in LINT_WAIVERS.items())
    waivers_end = "".join(f"/* verilator lint_on {cls} */\n" for cls in LINT_WAIVERS)
    return f"""\
{about}{waivers}module tb_{name};
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
{waivers_end}"""
