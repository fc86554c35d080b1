"""A design's identity, known without elaborating it: what a cache key of its builds hashes.

A block's hardware is a function of its component class, its (frozen) config, the
elaboration settings in force (:func:`~phongfx.hdl.overflow.overflow_checks`,
:func:`~phongfx.hdl.dsp.dsp_mapping`, :func:`~phongfx.hdl.overflow.overflow_probes`) and the
source that builds it: the packages :data:`HARDWARE_PACKAGES` (formats, configs, the golden
tables some ROMs are filled from, the Amaranth components) and the versions of Amaranth and
NumPy.  Converting a Figure 7 datapath to RTLIL to hash it takes 1.5 s; hashing this takes
microseconds once the sources' digest (:func:`source_digest`, a few milliseconds) is known.
So the flows key their caches by :func:`design_identity` (the Verilator builds of
:mod:`phongfx.sim.build_cache`, synthesis, the cost proxies) and elaborate only to build.

Correctness rests on the digest covering every line that can change the hardware: any edit
of a file of those packages changes every identity.  A class or a module of those packages
that does not come from their files (a test's block made from source text, a class swapped
in from elsewhere) has no identity: :func:`design_identity` returns None and the caller
hashes the elaborated design as before.
"""

import functools
import hashlib
import sys
from importlib import import_module
from importlib.metadata import version
from pathlib import Path

from .dsp import dsp_target
from .overflow import overflow_checking, probing

__all__ = ["HARDWARE_PACKAGES", "folder_digest", "source_digest", "design_identity"]

#: The packages whose files make hardware: a block's config, its components, and the golden
#: code and format arithmetic they call to fill tables and size values.
HARDWARE_PACKAGES = ("phongfx.core", "phongfx.config", "phongfx.golden", "phongfx.hdl")
#: The files of a package that count: its Python source and the Verilog models it ships.
_SUFFIXES = (".py", ".v")


def folder_digest(folder):
    """SHA-256 (hex) of every source file under ``folder``: each one's path relative to it
    and its bytes, in path order, so an edit, a new file or a renamed one changes it."""
    folder = Path(folder)
    digest = hashlib.sha256()
    for path in sorted(p for p in folder.rglob("*") if p.suffix in _SUFFIXES and p.is_file()
                       and "__pycache__" not in p.parts):
        digest.update(path.relative_to(folder).as_posix().encode() + b"\0")
        digest.update(path.read_bytes() + b"\0")
    return digest.hexdigest()


@functools.cache
def _folders():
    return tuple(Path(folder).resolve() for name in HARDWARE_PACKAGES for folder in import_module(name).__path__)


@functools.cache
def source_digest():
    """The digest of the hardware's sources: :func:`folder_digest` of every package of
    :data:`HARDWARE_PACKAGES` with the Amaranth and NumPy versions (computed once per process:
    the modules a process has imported do not change under it)."""
    parts = [f"{folder.name}:{folder_digest(folder)}" for folder in _folders()]
    parts += [f"{name}={version(name)}" for name in ("amaranth", "numpy")]
    return hashlib.sha256("\n".join(parts).encode()).hexdigest()


def _from_files(module_name):
    """Whether module ``module_name`` was loaded from a file of the hashed folders."""
    return _is_hashed(getattr(sys.modules.get(module_name), "__file__", None))


@functools.lru_cache(maxsize=None)
def _is_hashed(file):
    if not file:
        return False
    path = Path(file).resolve()
    return any(path.is_relative_to(folder) for folder in _folders())


def _all_from_files():
    """Whether every loaded module of :data:`HARDWARE_PACKAGES` came from their files."""
    prefixes = tuple(f"{name}." for name in HARDWARE_PACKAGES)
    return all(_from_files(name) for name in list(sys.modules)
               if name in HARDWARE_PACKAGES or name.startswith(prefixes))


def design_identity(classes, config, *extra):
    """The identity (a hex digest) of the design ``classes[0](config)`` elaborates to under
    the settings in force, or None when it has none (module docstring).

    ``classes`` is the component's class, then any class it builds that does not follow
    from ``config`` (a :class:`~phongfx.hdl.handshake.Handshake`'s block class); ``extra``
    strings are hashed beside (the module name the design is emitted as)."""
    if isinstance(classes, type):
        classes = (classes,)
    types = (*classes, type(config))
    if not all(_from_files(t.__module__) for t in types) or not _all_from_files():
        return None
    settings = (f"overflow_checks={overflow_checking()}", f"dsp={dsp_target()}", f"probes={probing()}")
    parts = [*(f"{t.__module__}.{t.__qualname__}" for t in types), repr(config), *settings,
             source_digest(), *extra]
    return hashlib.sha256("\0".join(parts).encode()).hexdigest()
