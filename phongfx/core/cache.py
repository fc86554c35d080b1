"""The per-user cache: one folder, a subfolder per tool, entries made whole or not at all.

Every tool result that can be made again is kept here rather than in the current folder:
Verilator builds (``verilator/``), FPGA synthesis and netlists (``synth/``), the
standard-cell flow with its OpenSTA timing (``sta/``), proofs (``prove/``) and the scene
compiler's journal (``compile/``).  The folder is ``$PHONGFX_CACHE`` when set, else the
platform's per-user cache directory (``platformdirs.user_cache_dir("phongfx")``:
``~/.cache/phongfx`` on Linux); ``phongfx cache --info`` shows it, ``--clear`` empties it.

:func:`make_entry` is the one way an entry is made: the tool runs in a private folder
beside the entry (``<key>.part-XXXX``), which is renamed to ``<key>`` only once the
result is complete, so a reader never sees half a result and two processes making the
same entry both end up with one whole copy.  A run that fails or is interrupted leaves
no partial folder: one that raised is kept, visibly, as ``failed/<key>`` (its logs, the
paths in the error already pointing there), one that was interrupted is removed.

A key hashes the elaborated design (its RTLIL), which takes seconds to make for a datapath:
:func:`remembered_key` keeps, in ``keys/``, the key each design identity (its
classes, config and the digest of the sources that make hardware) was found to have, so a
known design is keyed without being elaborated.
"""

import functools
import hashlib
import os
import shutil
import tempfile
from pathlib import Path

from phongfx.core.files import atomic_write

__all__ = ["ENVIRONMENT", "TOOLS", "root", "folder", "versions", "make_entry", "remembered_key", "usage", "clear"]

#: The environment variable that moves the cache.
ENVIRONMENT = "PHONGFX_CACHE"
#: The subfolders, one per tool (:func:`folder` takes these names); ``proxy/`` holds the
#: tool-free estimates (:mod:`phongfx.explore.synth.estimates`), ``keys/`` the keys
#: :func:`remembered_key` learnt.
TOOLS = ("verilator", "synth", "sta", "prove", "compile", "proxy", "keys")
#: Where the run folders of failed entries are kept for their logs.
FAILED = "failed"


def root():
    """The cache folder: ``$PHONGFX_CACHE``, else the platform's per-user cache directory."""
    configured = os.environ.get(ENVIRONMENT)
    if configured:
        return Path(configured).expanduser().resolve()
    import platformdirs

    return Path(platformdirs.user_cache_dir("phongfx", appauthor=False))


def folder(tool):
    """The subfolder of ``tool`` (one of :data:`TOOLS`), not created."""
    if tool not in TOOLS:
        raise ValueError(f"tool must be one of {', '.join(TOOLS)}, not {tool!r}")
    return root() / tool


@functools.cache
def versions(*packages):
    """``("name=version", ...)`` of the installed ``packages``: the part of an entry's key
    that makes a new tool release miss the entries its predecessor made."""
    from importlib.metadata import version

    return tuple(f"{name}={version(name)}" for name in packages)


def _retarget(error, old, new):
    """``error`` with every mention of folder ``old`` in its message pointing at ``new``."""
    error.args = tuple(a.replace(str(old), str(new)) if isinstance(a, str) else a for a in error.args)
    return error


def make_entry(directory, key, complete, make):
    """The entry ``<directory>/<key>``, made by ``make(work)`` if it is not complete yet.

    Parameters
    ----------
    directory : path
        The folder of entries (a :func:`folder`, or any folder the caller chose).
    key : str
        The entry's name: a hash of everything its content depends on.
    complete : str
        The file whose presence marks a complete entry; ``make`` writes it last.  A result
        not worth keeping (a time-out, which a rerun may well beat) is one ``make``
        returns without writing it: its folder is removed.
    make : callable
        ``make(work)`` fills the private folder ``work`` and returns a value.

    Returns
    -------
    (pathlib.Path or None, object)
        The entry and ``make``'s value; None for the value when the entry was already
        complete (nothing was run), None for the entry when the result was not kept.
    """
    directory = Path(directory).resolve()
    final = directory / key
    if (final / complete).is_file():
        return final, None
    directory.mkdir(parents=True, exist_ok=True)
    work = Path(tempfile.mkdtemp(prefix=f"{key}.part-", dir=directory))
    os.chmod(work, 0o755)  # mkdtemp makes it private; the entries are for reading
    try:
        value = make(work)
    except KeyboardInterrupt:  # half a run is no entry
        shutil.rmtree(work, ignore_errors=True)
        raise
    except BaseException as error:  # noqa: BLE001 - the logs of any failure are worth keeping
        failed = directory / FAILED / key
        shutil.rmtree(failed, ignore_errors=True)
        failed.parent.mkdir(exist_ok=True)
        try:
            work.rename(failed)
        except OSError:
            shutil.rmtree(work, ignore_errors=True)
            raise
        raise _retarget(error, work, failed)
    # the logs of an earlier failure of this entry are out of date now
    shutil.rmtree(directory / FAILED / key, ignore_errors=True)
    if not (work / complete).is_file():  # not worth keeping
        shutil.rmtree(work, ignore_errors=True)
        return None, value
    try:
        work.rename(final)
    except OSError:  # another process finished the same entry first, or a stale folder
        if (final / complete).is_file():
            shutil.rmtree(work, ignore_errors=True)
        else:
            shutil.rmtree(final, ignore_errors=True)
            work.rename(final)
    return final, value


#: Keys :func:`remembered_key` found in this process, by the hash of their identity.
_KNOWN = {}


def remembered_key(identity, make_key):
    """The key of a cache entry whose design is named by ``identity`` (strings: everything
    ``make_key`` depends on, the design by its identity rather than its text; None when it
    has none): ``make_key()`` the first time, then read back from the cache's
    ``keys/<hash of identity>`` (and this process' memory) without calling it.

    ``make_key`` hashes the design's elaborated text (seconds for a datapath), so entries
    keep their keys across edits that do not change the design; ``identity`` changes on any
    edit of the sources (:func:`phongfx.hdl.identity.design_identity`), so an edited design
    is keyed afresh, never by what its predecessor was keyed by.  The key does not depend on
    the folder of entries, so one record serves every folder."""
    if identity is None:
        return make_key()
    name = hashlib.sha256("\0".join(identity).encode()).hexdigest()[:32]
    if name not in _KNOWN:
        path = folder("keys") / name
        try:
            key = path.read_text().strip()
        except OSError:
            key = ""
        if not key:
            key = make_key()
            atomic_write(path, lambda tmp: Path(tmp).write_text(key + "\n"))
        _KNOWN[name] = key
    return _KNOWN[name]


def _size(path):
    total = 0
    for base, _, files in os.walk(path):
        for name in files:
            try:
                total += os.lstat(os.path.join(base, name)).st_size
            except OSError:  # removed meanwhile
                pass
    return total


def usage():
    """``[(subfolder, entries, bytes)]`` of every subfolder present, in :data:`TOOLS` order
    first; an entry is a direct child (a build, a result, a run folder)."""
    base = root()
    if not base.is_dir():
        return []
    present = sorted(p.name for p in base.iterdir() if p.is_dir())
    names = [t for t in TOOLS if t in present] + [n for n in present if n not in TOOLS]
    return [(name, sum(1 for _ in (base / name).iterdir()), _size(base / name)) for name in names]


def clear():
    """Remove the cache folder's content; returns the bytes freed."""
    base = root()
    if not base.is_dir():
        return 0
    freed = _size(base)
    for child in base.iterdir():
        if child.is_dir() and not child.is_symlink():
            shutil.rmtree(child, ignore_errors=True)
        else:
            child.unlink(missing_ok=True)
    return freed
