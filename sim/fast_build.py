"""The ``verilator-fast`` back end's simulator: a block's Verilog and the C++ checker
(``fast_main.cpp``) under Verilator, compiled into the build cache.

:func:`build` makes (or finds) the checker of one design: Verilator turns the block and its
top (:mod:`phongfx.sim.fast_top`) into C++, ``make`` compiles it with the run-time objects the
cache keeps per flavour (:mod:`phongfx.sim.build_cache`); :func:`warm` compiles only those
run-time objects, ahead of a build that will want them (the compile's, beside its search).
:mod:`phongfx.sim.fast_backend` runs what they make.
"""

import subprocess
import tempfile
from pathlib import Path

from phongfx.hdl.emit import payload_widths, verilog

from .build_cache import (BUILD_ARGS, TOOL_ERRORS, cache_root, cached_build, keep_runtime, log_tail, runtime_kept,
                          runtime_lock, seed_runtime)
from .fast_top import is_stream, wrapper
from .verilator_backend import tool_environment

__all__ = ["MAIN", "EXECUTABLE", "build", "warm"]

MAIN = Path(__file__).with_name("fast_main.cpp")
EXECUTABLE = "phongfx_sim"
_VERILATOR_ARGS = ["--cc", "--exe", "--prefix", "Vtop", "-O3", "--x-assign", "fast",
                   "-o", EXECUTABLE]
# The design's C++ at -O2 rather than verilated.mk's -Os: slower to build, faster to run; -O0
# for a frame's check (a shader: 7.8 s against 1.0 s to build, 11084 vectors in 0.02 s against
# 0.07 s).  Its run-time objects are -O0 too, a flavour of their own (7.2 against 9.7
# processor-seconds to compile, each cold compile's; a third slower to run, which a frame's
# check does not feel), where the optimized builds keep verilated.mk's -Os (OPT_GLOBAL).
_RUNTIME_ARGS = {True: [], False: ["OPT_GLOBAL=-O0"]}
_MAKE_ARGS = {True: ["OPT_FAST=-O2"], False: ["OPT_FAST=-O0", *_RUNTIME_ARGS[False]]}
# Unoptimized, Verilator's merge of conditionals is skipped too: on a shader inside its handshake
# it was 4.5 of 5.8 s of verilation (Lyon's halfway unit), for a run of a frame's vectors that it
# hardly speeds.
_FLAVOUR_ARGS = {True: [], False: ["-fno-merge-cond"]}


def _plan(component, trace, optimize):
    """``(module, top, wrapper, verilator_args, runtime, flavour)`` of a build of ``component``:
    the Verilog names of the block and of the simulated top around it, the top's Verilog
    (:func:`~phongfx.sim.fast_top.wrapper`), Verilator's arguments, what the run-time objects
    depend on, and what the executable does."""
    module = type(component).__name__.lower()
    verilator_args = [*_VERILATOR_ARGS, "--trace"] if trace else _VERILATOR_ARGS
    runtime = ("fast", *verilator_args, *_RUNTIME_ARGS[optimize])
    return (module, f"{module}_fast", wrapper(module, *payload_widths(component), stream=is_stream(component)),
            verilator_args, runtime, (*runtime, *_FLAVOUR_ARGS[optimize], *_MAKE_ARGS[optimize]))


def _verilate(work, source, top, verilator_args, optimize, run_):
    """Verilator on ``source`` (the block's Verilog and the top ``top``) and :data:`MAIN` in
    ``work``: the C++ and its ``Vtop.mk``."""
    (work / MAIN.name).write_text(MAIN.read_text())
    subprocess.run([str(tool_environment()), *verilator_args, *_FLAVOUR_ARGS[optimize], *BUILD_ARGS,
                    "--top-module", top, "--Mdir", str(work), str(source), str(work / MAIN.name)], **run_)


def build(component, *, build_dir=None, design=None, trace=False, optimize=True):
    """Compile ``component`` (or ``design``, Verilog of a module with its ports: a
    synthesized netlist with its cell models) with the C++ checker, or find it in the cache;
    ``trace`` compiles Verilator's VCD tracing in (``phongfx_sim`` then takes a VCD path);
    ``optimize`` False builds the design's C++ unoptimized: seconds sooner, for a run of up to
    about a million vectors.

    Returns
    -------
    phongfx.sim.build_cache.Build
        ``directory / EXECUTABLE`` is the checker.

    Raises
    ------
    RuntimeError
        If Verilator or the C++ compile fails; the message ends with the log tail.
    """
    module, top, around, verilator_args, runtime, flavour = _plan(component, trace, optimize)
    # the key covers everything the executable depends on beyond the design
    top_text = around + "/*\n" + "\n".join(flavour) + MAIN.read_text() + "*/\n"
    root = cache_root(build_dir)

    def compile_(work, source, log):
        with open(log, "w") as out:
            run_ = dict(cwd=work, stdout=out, stderr=subprocess.STDOUT, check=True)
            # before the lock: a build that waits for another's run-time objects (the compile's
            # check, for its warm-up) has its design verilated by then
            _verilate(work, source, top, verilator_args, optimize, run_)
        with runtime_lock(root, trace, runtime), open(log, "a") as out:
            seeded = seed_runtime(root, work, trace, runtime)
            run_ = dict(cwd=work, stdout=out, stderr=subprocess.STDOUT, check=True)
            # make rebuilds objects older than Vtop.mk, just written: refresh the seeded ones
            if seeded:
                subprocess.run(["touch", "-c", *map(str, seeded)], **run_)
            subprocess.run(["make", "-f", "Vtop.mk", "-j", "2", *_MAKE_ARGS[optimize]], **run_)
            keep_runtime(root, work, trace, runtime)

    return cached_build(component, module, top, top_text, compile_, root=root, waves=trace,
                        executable=EXECUTABLE, design=design)


def warm(component, *, build_dir=None, trace=False, optimize=True):
    """Compile the run-time objects of :func:`build`'s flavour into the cache, unless they are
    there, so that a later build compiles only its design: ``component`` (the smallest block
    will do) is verilated for the make file that names them, and only they are compiled (a first
    build's design, 3.5 of its 15 processor-seconds, is not).  True when this call compiled them.

    Raises
    ------
    RuntimeError
        If Verilator or the C++ compile fails; the message ends with the log tail.
    """
    module, top, around, verilator_args, runtime, _ = _plan(component, trace, optimize)
    root = cache_root(build_dir)
    if runtime_kept(root, trace, runtime):
        return False
    root.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(prefix="runtime-", dir=root) as work, runtime_lock(root, trace, runtime):
        if runtime_kept(root, trace, runtime):  # another process compiled them meanwhile
            return False
        work = Path(work)
        source, log = work / f"{top}.v", work / "build.log"
        source.write_text(verilog(component, module, emit_src=False) + around)
        try:
            with open(log, "w") as out:
                run_ = dict(cwd=work, stdout=out, stderr=subprocess.STDOUT, check=True)
                _verilate(work, source, top, verilator_args, optimize, run_)
                # the objects verilated.mk links every build with, and nothing else
                (work / "runtime.mk").write_text("include Vtop.mk\nphongfx-runtime: $(VK_GLOBAL_OBJS)\n")
                subprocess.run(["make", "-f", "runtime.mk", "-j", "2", *_MAKE_ARGS[optimize], "phongfx-runtime"],
                               **run_)
        except TOOL_ERRORS as error:
            raise RuntimeError(f"Verilator run-time build failed ({error}); log:\n{log_tail(log)}") from None
        keep_runtime(root, work, trace, runtime)
    return True
