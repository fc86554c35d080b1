"""Narrowing a raw Amaranth value from one fixed-point format to another, in hardware.

:func:`quantize` is the twin of :func:`phongfx.golden.fixed.quantize_raw`: the same
rounding and overflow names (:mod:`phongfx.core.format`), bit for bit; the rounding adder
first, then the clamp's comparators (or bit tests) and multiplexers.  :func:`overflowed`
is the 1-bit "it did not fit" of an ``overflow="error"`` quantize, and :func:`fit` the
sign-correct widening or truncation every result goes through.  :class:`~phongfx.hdl.fixed.FixedValue`
calls them with its own format.
"""

from amaranth.hdl import Cat, Const, Mux, Value

from phongfx.core.format import Format, check_overflow, check_rounding

__all__ = ["fit", "quantize", "overflowed"]


def fit(value, fmt):
    """``value`` extended by its own signedness (or truncated) to exactly ``fmt``'s shape.

    Slicing alone cannot widen: ``value[:n]`` of a narrower value keeps its width, so an
    unsigned value recast as signed (or the reverse) would change its meaning.
    """
    value = Value.cast(value)
    if len(value) < fmt.width:
        if len(value) == 0:
            value = Const(0, fmt.width)
        elif value.shape().signed:
            value = Cat(value, value[-1].replicate(fmt.width - len(value)))
        else:
            value = Cat(value, Const(0, fmt.width - len(value)))
    value = value[:fmt.width]
    return value.as_signed() if fmt.signed else value.as_unsigned()


def _rounded(value, frm, to, rounding):
    """``value`` (raw codes of ``frm``) rounded to ``to``'s fraction bits, not yet narrowed."""
    value = Value.cast(value)
    value = value.as_signed() if frm.signed else value.as_unsigned()
    drop = frm.frac_bits - to.frac_bits
    if drop > 0:
        if rounding == "round_half_up":
            value = value + (1 << (drop - 1))
        elif rounding == "round_half_even":
            # the LSB kept, bit ``drop``: past the top of the value it is the sign (or 0)
            if drop < len(value):
                kept_lsb = value[drop]
            else:
                kept_lsb = value[-1] if frm.signed else Const(0, 1)
            value = value + ((1 << (drop - 1)) - 1) + kept_lsb
        value = value >> drop
    elif drop < 0:
        value = value << -drop
    return value


def _out_of_range(value, to):
    """(below, above): 1-bit values, or None on a side ``value``'s shape cannot reach.

    A comparison that is constant (an unsigned value < 0) is dead logic, and Verilator
    lint flags it, so it is not built.
    """
    shape = value.shape()
    lowest = -(1 << (shape.width - 1)) if shape.signed else 0
    highest = (1 << (shape.width - 1 if shape.signed else shape.width)) - 1
    return (value < to.min_raw if lowest < to.min_raw else None,
            value > to.max_raw if highest > to.max_raw else None)


def _out_of_range_bits(value, to):
    """:func:`_out_of_range` as bit tests: every limit of a format is a power of two (less one
    above), so ``value`` is out of range exactly when its bits from ``to``'s top bit up are
    not all copies of its sign (signed ``to``) or not all 0 (unsigned): LUTs, no carry chain."""
    low, high = _out_of_range(value, to)
    if low is None and high is None:
        return low, high
    signed = value.shape().signed
    top = to.width - 1 if to.signed else to.width  # the first bit ``to`` cannot hold freely
    sign = value[-1] if signed else Const(0, 1)
    if to.signed:
        rest = value[top:]  # sign bit of ``to`` and above: all equal when in range
        low = None if low is None else sign & ~rest.all()
        high = None if high is None else ~sign & rest.any()
    else:
        low = None if low is None else sign
        high = None if high is None else ~sign & value[top:len(value) - signed].any()
    return low, high


def quantize(value, frm, to, rounding, overflow, parallel_clamp=False):
    """Narrow ``value`` (raw codes of ``frm``) to ``to``; twin of ``golden.fixed.quantize_raw``.

    ``overflow="error"`` declares that overflow cannot happen: the golden model
    checks it and raises; the hardware keeps the low bits, as ``wrap`` does, and
    :meth:`FixedValue.quantize` raises a simulation-only flag (see
    :func:`~phongfx.hdl.overflow.overflow_flags`).
    ``parallel_clamp`` compares with both limits side by side rather than the upper
    one behind the lower one's multiplexer: the same codes, one comparator deep;
    ``"bits"`` does so with bit tests instead of comparators (:func:`_out_of_range_bits`).
    """
    frm, to = Format.parse(frm), Format.parse(to)
    check_rounding(rounding)
    check_overflow(overflow)
    value = _rounded(value, frm, to, rounding)
    if overflow == "saturate":
        low, high = (_out_of_range_bits if parallel_clamp == "bits" else _out_of_range)(value, to)
        if parallel_clamp == "bits":
            value = Mux(high, to.max_raw, value) if high is not None else value
            value = Mux(low, to.min_raw, value) if low is not None else value
        elif parallel_clamp and low is not None and high is not None:
            value = Mux(low, to.min_raw, Mux(high, to.max_raw, value))
        else:
            if low is not None:
                value = Mux(low, to.min_raw, value)
            if high is not None:
                # compared behind the first multiplexer (the depth-0..2 designs keep this form)
                value = Mux(value > to.max_raw, to.max_raw, value)
    return fit(value, to)


def overflowed(value, frm, to, rounding):
    """1-bit: ``value`` rounded to ``to`` lies outside it (None where it cannot)."""
    frm, to = Format.parse(frm), Format.parse(to)
    flags = [flag for flag in _out_of_range(_rounded(value, frm, to, rounding), to) if flag is not None]
    return None if not flags else flags[0] if len(flags) == 1 else flags[0] | flags[1]
