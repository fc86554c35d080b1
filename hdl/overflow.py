"""RTL overflow assertions: the flags a block collects while it is elaborated.

A quantize with ``overflow="error"`` is the designer's claim that the value always fits
its format.  The golden model checks the claim and raises; the hardware keeps the low
bits, as ``wrap`` does, so a claim that fails in the RTL alone would pass unnoticed.
So, while a block is elaborated, each such quantize in
:meth:`~phongfx.hdl.fixed.FixedValue.quantize` (and each sub-block the block feeds)
reports a 1-bit flag "it did not fit" at its cycle (:func:`report_overflow`);
:func:`overflow_flags` collects them and
:class:`~phongfx.hdl.block.PipelinedBlock` ORs them into its ``overflow`` output, which
the harness expects to be 0 on every valid output.

Simulation checks the claim on every pixel; synthesis builds under
:func:`overflow_checks` ``(False)`` and pays nothing for it.
"""

import contextlib
import contextvars

__all__ = ["overflow_checks", "overflow_flags", "collecting_overflow", "report_overflow"]

#: The flags of the block being elaborated (None: checks off, or no block).
_FLAGS = contextvars.ContextVar("phongfx_overflow_flags", default=None)
#: Whether blocks elaborated now build overflow checks (off for synthesis).
_CHECKS = contextvars.ContextVar("phongfx_overflow_checks", default=True)


@contextlib.contextmanager
def overflow_checks(enabled):
    """Build blocks elaborated inside with (``True``, the default) or without the RTL
    overflow flags: simulation wants them, synthesis must not pay for them."""
    token = _CHECKS.set(bool(enabled))
    try:
        yield
    finally:
        _CHECKS.reset(token)


@contextlib.contextmanager
def overflow_flags():
    """Collect, while a block's datapath is built, a 1-bit
    :class:`~phongfx.hdl.fixed.FixedValue` per ``overflow="error"`` quantize that could
    overflow (and per sub-block fed): the list yielded, or None when checks are off."""
    flags = [] if _CHECKS.get() else None
    token = _FLAGS.set(flags)
    try:
        yield flags
    finally:
        _FLAGS.reset(token)


def collecting_overflow():
    """Whether a block being elaborated now collects overflow flags: when not, a
    quantize builds no comparator for its flag at all."""
    return _FLAGS.get() is not None


def report_overflow(flag):
    """Add ``flag`` (a 1-bit :class:`~phongfx.hdl.fixed.FixedValue` at its cycle) to the
    block being built."""
    flags = _FLAGS.get()
    if flags is not None:
        flags.append(flag)
