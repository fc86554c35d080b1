"""Output files written whole or not at all.

Every output (PNG, JSON, Markdown, CSV, Verilog) goes through :func:`atomic_write`: the
bytes go to a temporary file beside the target, which then replaces it in one step, so
a failed or interrupted run never leaves a half-written file.
"""

import os
import tempfile

__all__ = ["atomic_write", "check_folder"]


def check_folder(path, what="output folder"):
    """``path`` if it is, or could be made, a folder: else ``NotADirectoryError`` naming it and
    the regular file in its way.  Called before long work, so that a bad ``-o`` fails at once,
    not after the work is done."""
    path = os.path.abspath(os.fspath(path))
    probe = path
    while not os.path.exists(probe):
        parent = os.path.dirname(probe)
        if parent == probe:
            break
        probe = parent
    if os.path.exists(probe) and not os.path.isdir(probe):
        where = "is a regular file" if probe == path else f"is under {probe}, a regular file"
        raise NotADirectoryError(20, f"the {what} {where}: Not a directory", path)
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
    umask = os.umask(0)
    os.umask(umask)
    try:
        os.chmod(tmp, 0o666 & ~umask)  # mkstemp makes it private; outputs are for reading
        write(tmp)
        os.replace(tmp, path)
    except BaseException:
        os.unlink(tmp)
        raise
