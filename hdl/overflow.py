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
:func:`overflow_checks` ``(False)`` and pays nothing for it (:class:`Checked` wraps a
component so that its whole subtree is elaborated so, as the shipped top is).  A formal proof
(:mod:`phongfx.sim.prove`) needs each claim on its own: under :func:`overflow_probes`
every block also gives each of its own flags a signal of its own, valid-gated at the
output cycle, with what it claims (formats, rounding) and where it was made.
"""

import contextlib
import contextvars
import os
import sys

from amaranth.hdl import Elaboratable, Fragment

from .context import scoped

__all__ = ["Checked", "overflow_checks", "overflow_checking",
           "overflow_flags", "collecting_overflow", "report_overflow", "report_static",
           "overflow_probes", "add_probe", "probing", "caller"]

#: The flags of the block being elaborated (None: checks off, or no block).
_FLAGS = contextvars.ContextVar("phongfx_overflow_flags", default=None)
#: Whether blocks elaborated now build overflow checks (off for synthesis).
_CHECKS = contextvars.ContextVar("phongfx_overflow_checks", default=True)
#: The probes of :func:`overflow_probes` (None: not probing).
_PROBES = contextvars.ContextVar("phongfx_overflow_probes", default=None)


@contextlib.contextmanager
def overflow_checks(enabled):
    """Build blocks elaborated inside with (``True``, the default) or without the RTL
    overflow flags: simulation wants them, synthesis must not pay for them."""
    with scoped(_CHECKS, bool(enabled)):
        yield


class Checked(Elaboratable):
    """``inner`` elaborated with overflow checks on or off (:func:`overflow_checks`).
    Amaranth elaborates submodules only after the parent's ``elaborate`` has returned, so a
    context manager there would not reach the block; here ``Fragment.get`` builds the whole
    subtree inside it."""

    def __init__(self, inner, enabled):
        self.inner = inner
        self.enabled = enabled

    def elaborate(self, platform):
        with overflow_checks(self.enabled):
            return Fragment.get(self.inner, platform)


def overflow_checking():
    """Whether blocks elaborated now build overflow checks (:func:`overflow_checks`)."""
    return _CHECKS.get()


@contextlib.contextmanager
def overflow_flags():
    """Collect, while a block's datapath is built, a 1-bit
    :class:`~phongfx.hdl.fixed.FixedValue` per ``overflow="error"`` quantize that could
    overflow (and per sub-block fed): the list yielded, or None when checks are off."""
    with scoped(_FLAGS, _Flags() if _CHECKS.get() else None) as flags:
        yield flags


class _Flags(list):
    """The flags of one block, and (``static``) the claims of its quantizes whose widths
    alone keep them in range (no flag: nothing can overflow)."""

    def __init__(self):
        super().__init__()
        self.static = []


def report_static(what):
    """Record the claim ``what`` of a quantize that cannot overflow by its widths alone."""
    flags = _FLAGS.get()
    if flags is not None:
        flags.static.append(what)


def collecting_overflow():
    """Whether a block being elaborated now collects overflow flags: when not, a
    quantize builds no comparator for its flag at all."""
    return _FLAGS.get() is not None


def report_overflow(flag, what=None):
    """Add ``flag`` (a 1-bit :class:`~phongfx.hdl.fixed.FixedValue` at its cycle) to the
    block being built; ``what`` says what it claims (None: a sub-block's own overflow
    output, whose claims that block probes itself)."""
    flags = _FLAGS.get()
    if flags is not None:
        flag.claim = what
        flags.append(flag)


@contextlib.contextmanager
def overflow_probes():
    """Collect, while blocks are elaborated inside, ``{"block", "claim", "signal"}`` per
    ``overflow="error"`` quantize of each: ``signal`` is 1 on a valid output whose value
    did not fit (:func:`add_probe`)."""
    with scoped(_PROBES, []) as probes:
        yield probes


def probing():
    """Whether :func:`overflow_probes` is collecting."""
    return _PROBES.get() is not None


def add_probe(block, claim, signal):
    probes = _PROBES.get()
    if probes is not None:
        probes.append({"block": block, "claim": claim, "signal": signal})


def caller(skip):
    """``file:line`` of the nearest caller outside the files ``skip`` (base names)."""
    frame = sys._getframe(1)
    while frame is not None and os.path.basename(frame.f_code.co_filename) in skip:
        frame = frame.f_back
    if frame is None:
        return "?"
    return f"{os.path.basename(frame.f_code.co_filename)}:{frame.f_lineno}"
