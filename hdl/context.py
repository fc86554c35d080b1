"""Settings that hold while blocks are elaborated inside a ``with`` block.

Whether overflow checks are built, which DSP products map onto, what is being collected:
each is a :class:`contextvars.ContextVar` set for the extent of a ``with`` and restored after,
even on an exception, so that one elaboration's setting never leaks into the next.
"""

import contextlib

__all__ = ["scoped"]


@contextlib.contextmanager
def scoped(variable, value):
    """``variable`` (a ``ContextVar``) set to ``value`` inside; yields ``value``."""
    token = variable.set(value)
    try:
        yield value
    finally:
        variable.reset(token)
