"""Output files written whole or not at all.

Every output (PNG, JSON, Markdown, CSV, Verilog) goes through :func:`atomic_write`: the
bytes go to a temporary file beside the target, which then replaces it in one step, so
a failed or interrupted run never leaves a half-written file.  A folder of outputs that
belong together (the scene compiler's Verilog, frames and manifest) goes through
:func:`staged_folder`: it is built beside its place and renamed into it when complete, so
the folder is a complete result of one run, or the previous one, never a mix.
"""

import contextlib
import os
import shutil
import tempfile

__all__ = ["atomic_write", "check_folder", "staged_folder"]


def _existing(path):
    """``path`` or its nearest ancestor that exists."""
    while not os.path.exists(path):
        parent = os.path.dirname(path)
        if parent == path:
            break
        path = parent
    return path


def check_folder(path, what="output folder"):
    """``path`` if it is, or could be made, a folder: else ``NotADirectoryError`` naming it and
    the regular file in its way, or ``PermissionError`` naming the folder that cannot be
    written (the output is built beside ``path``, in its parent; tried by making and removing
    a folder there, so that it holds for root and read-only file systems too).  Called before
    long work, so that a bad ``-o`` fails at once, not after the work is done."""
    path = os.path.abspath(os.fspath(path))
    probe = _existing(path)
    if os.path.exists(probe) and not os.path.isdir(probe):
        where = "is a regular file" if probe == path else f"is under {probe}, a regular file"
        raise NotADirectoryError(20, f"the {what} {where}: Not a directory", path)
    parent = _existing(os.path.dirname(path))
    try:
        os.rmdir(tempfile.mkdtemp(prefix=".phongfx-probe-", dir=parent))
    except OSError as error:
        raise PermissionError(error.errno, f"the {what} cannot be written: {parent} is not writable "
                                           f"({error.strerror})", path) from None
    return path


def atomic_write(path, write):
    """Call ``write(tmp)`` on a temporary file beside ``path``, then move it into place:
    a failed write leaves no half-written ``path``.  An ``OSError`` names ``path``, not
    the temporary file."""
    path = os.fspath(path)
    directory = os.path.dirname(path) or "."
    name = os.path.basename(path)
    try:
        os.makedirs(directory, exist_ok=True)
        fd, tmp = tempfile.mkstemp(prefix=f".{name}.", suffix=".tmp", dir=directory)
    except OSError as error:
        raise OSError(error.errno, error.strerror, path) from None
    os.close(fd)
    try:
        os.chmod(tmp, 0o666 & ~_umask())  # mkstemp makes it private; outputs are for reading
        write(tmp)
        os.replace(tmp, path)
    except BaseException:
        os.unlink(tmp)
        raise


@contextlib.contextmanager
def staged_folder(path):
    """A context whose value is a fresh hidden folder beside ``path``; on a normal exit it
    replaces ``path`` (an existing folder there is removed only after the new one is in
    place), on an exception or an interrupt it is removed and ``path`` is left as it was."""
    path = os.path.abspath(check_folder(path))
    parent, name = os.path.split(path)
    os.makedirs(parent, exist_ok=True)
    work = tempfile.mkdtemp(prefix=f".{name}.", suffix=".partial", dir=parent)
    old = None
    try:
        os.chmod(work, 0o777 & ~_umask())  # mkdtemp makes it private; outputs are for reading
        yield work
        if os.path.lexists(path):
            old = tempfile.mkdtemp(prefix=f".{name}.", suffix=".old", dir=parent)
            os.rmdir(old)
            os.rename(path, old)
        os.rename(work, path)
    except BaseException:
        if old is not None and not os.path.lexists(path):
            os.rename(old, path)  # interrupted between the two renames: the previous result back
            old = None
        shutil.rmtree(work, ignore_errors=True)
        raise
    if old is not None:
        shutil.rmtree(old, ignore_errors=True)


def _umask():
    umask = os.umask(0)
    os.umask(umask)
    return umask
