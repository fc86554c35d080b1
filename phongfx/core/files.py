"""Output files written whole or not at all.

Every output (PNG, JSON, Markdown, CSV, Verilog) goes through :func:`atomic_write`: the
bytes go to a temporary file beside the target, which then replaces it in one step, so
a failed or interrupted run never leaves a half-written file.
"""

import os
import tempfile

__all__ = ["atomic_write"]


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
