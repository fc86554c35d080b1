"""Raw fixed-point arrays for the golden models.

A :class:`Fixed` is a numpy ``int64`` array of raw codes paired with its
:class:`~phongfx.format.Format`.  Arithmetic is exact and the result format grows
as the hardware's would (:meth:`Format.add`, :meth:`Format.mul`, ...); the only
narrowing operation is :meth:`Fixed.quantize`, which names its rounding and its
overflow policy.  :mod:`phongfx.hdl.fixed` implements the same ``quantize`` for
Amaranth, so a block's golden model and its component read alike.
"""

import numpy as np

from ..format import Format, check_overflow, check_rounding

__all__ = ["Fixed", "FixedOverflowError", "quantize_raw", "check_range"]


class FixedOverflowError(OverflowError):
    """A ``quantize`` with ``overflow="error"`` met a value outside its format."""


def _as_raw(raw):
    array = np.asarray(raw)
    if array.dtype.kind not in "iub":
        raise TypeError(f"raw codes must be integers, not {array.dtype}")
    return array.astype(np.int64)


def quantize_raw(raw, frm, to, rounding, overflow, op="quantize"):
    """Narrow raw codes of format ``frm`` to format ``to``.

    Parameters
    ----------
    raw : array of int64
    frm, to : Format
    rounding : {"truncate", "round_half_up", "round_half_even"}
        Applied when ``to`` has fewer fraction bits.
    overflow : {"saturate", "wrap", "error"}
        Applied when the rounded value falls outside ``to``.
    op : str
        Name of the operation, for the error message.
    """
    frm, to = Format.parse(frm), Format.parse(to)
    check_rounding(rounding)
    check_overflow(overflow)
    raw = _as_raw(raw)
    drop = frm.frac_bits - to.frac_bits
    if drop > 0:
        if rounding == "round_half_up":
            raw = raw + (1 << (drop - 1))
        elif rounding == "round_half_even":
            # adding half minus one plus the kept LSB makes exact ties go to even
            raw = raw + ((1 << (drop - 1)) - 1) + ((raw >> drop) & 1)
        raw = raw >> drop
    elif drop < 0:
        if frm.width - drop > 64:
            raise ValueError(f"{op}: {frm} moved to {-drop} more fraction bits does not fit in int64")
        raw = raw << -drop
    bad = (raw < to.min_raw) | (raw > to.max_raw)
    if np.any(bad):
        if overflow == "error":
            first = raw[bad].flat[0] if raw.ndim else raw
            raise FixedOverflowError(
                f"{op}: {int(np.count_nonzero(bad))} value(s) overflow format {to} "
                f"(range {to.min_raw * to.lsb}..{to.max_raw * to.lsb}); "
                f"first offending value {int(first) * to.lsb} (raw {int(first)})")
        if overflow == "saturate":
            raw = np.clip(raw, to.min_raw, to.max_raw)
        else:
            raw = raw & ((1 << to.width) - 1) if to.width < 64 else raw
            if to.signed and to.width < 64:
                raw = np.where(raw >= (1 << (to.width - 1)), raw - (1 << to.width), raw)
    return raw


def check_range(name, value, lo, hi):
    """Refuse input values outside ``lo..hi`` (floats) with a message naming ``name``."""
    lo_raw, hi_raw = lo * value.fmt.one, hi * value.fmt.one
    bad = (value.raw < lo_raw) | (value.raw > hi_raw)
    if np.any(bad):
        first = value.raw[bad].flat[0]
        raise ValueError(f"{name} must be in {lo:g}..{hi:g}; {int(np.count_nonzero(bad))} value(s) "
                         f"are not, first {int(first) * value.fmt.lsb:g} (raw {int(first)})")
    return value


class Fixed:
    """Raw ``int64`` codes with their format.

    Parameters
    ----------
    raw : array_like of int
        Raw codes; they must lie inside ``fmt`` (use :meth:`quantize` to narrow).
    fmt : Format or str
    """

    __array_priority__ = 100  # so ``ndarray op Fixed`` defers to Fixed

    def __init__(self, raw, fmt):
        self.fmt = Format.parse(fmt)
        self.raw = _as_raw(raw)
        if self.raw.size and (self.raw.min() < self.fmt.min_raw or self.raw.max() > self.fmt.max_raw):
            bad = (self.raw < self.fmt.min_raw) | (self.raw > self.fmt.max_raw)
            raise ValueError(
                f"raw codes must lie in {self.fmt.min_raw}..{self.fmt.max_raw} for format "
                f"{self.fmt}; {int(np.count_nonzero(bad))} do not, first {int(self.raw[bad].flat[0])}")

    @classmethod
    def from_float(cls, value, fmt, rounding="round_half_up", overflow="error"):
        """Quantize float values to ``fmt`` with a named rounding and overflow policy."""
        fmt = Format.parse(fmt)
        check_rounding(rounding)
        scaled = np.asarray(value, dtype=np.float64) * float(fmt.one)
        if not np.all(np.isfinite(scaled)):
            raise ValueError(f"from_float: values must be finite to convert to {fmt}")
        if rounding == "truncate":
            raw = np.floor(scaled)
        elif rounding == "round_half_up":
            raw = np.floor(scaled + 0.5)
        else:
            raw = np.round(scaled)  # numpy rounds ties to even
        limit = 2.0 ** 62
        raw = np.clip(raw, -limit, limit).astype(np.int64)
        return cls(quantize_raw(raw, fmt, fmt, rounding, overflow, op="from_float"), fmt)

    @classmethod
    def const(cls, value, fmt):
        """A scalar constant that ``fmt`` holds exactly (e.g. 1.0)."""
        fmt = Format.parse(fmt)
        raw = value * fmt.one
        if raw != int(raw):
            raise ValueError(f"constant {value} is not exactly representable in {fmt}")
        return cls(int(raw), fmt)

    def to_float(self):
        return self.raw.astype(np.float64) * self.fmt.lsb

    def __repr__(self):
        return f"Fixed({self.fmt}, {self.to_float()!r})"

    def __len__(self):
        return len(self.raw)

    def __getitem__(self, index):
        return Fixed(self.raw[index], self.fmt)

    @property
    def shape(self):
        return self.raw.shape

    # -- exact arithmetic -------------------------------------------------------------------

    def _align(self, fmt):
        return self.raw << (fmt.frac_bits - self.fmt.frac_bits)

    def __add__(self, other):
        other = _coerce(other)
        fmt = self.fmt.add(other.fmt)
        return Fixed(self._align(fmt) + other._align(fmt), fmt)

    def __sub__(self, other):
        other = _coerce(other)
        fmt = self.fmt.sub(other.fmt)
        return Fixed(self._align(fmt) - other._align(fmt), fmt)

    def __mul__(self, other):
        other = _coerce(other)
        return Fixed(self.raw * other.raw, self.fmt.mul(other.fmt))

    def __neg__(self):
        return Fixed(-self.raw, self.fmt.neg())

    __radd__ = __add__
    __rmul__ = __mul__

    def __rsub__(self, other):
        return _coerce(other) - self

    def __lshift__(self, amount):
        return self.shift(amount)

    def __rshift__(self, amount):
        return self.shift(-amount)

    def shift(self, amount):
        """Exact multiply by ``2**amount``: moves the point, not the bits."""
        return Fixed(self.raw << self.fmt.shift_raw(amount), self.fmt.shift(amount))

    def sum(self, axis=-1):
        """Exact sum along ``axis`` (an adder tree: the format grows as for repeated adds)."""
        count = self.raw.shape[axis]
        fmt = self.fmt
        for _ in range(count - 1):
            fmt = fmt.add(self.fmt)
        return Fixed(self.raw.sum(axis=axis), fmt)

    def dot(self, other):
        """Exact dot product over the last axis (three multipliers and an adder tree)."""
        return (self * _coerce(other)).sum(axis=-1)

    def _compare_raw(self, other):
        # comparisons against a number use its exact raw code in this format
        if isinstance(other, Fixed):
            f = max(self.fmt.frac_bits, other.fmt.frac_bits)
            return self.raw << (f - self.fmt.frac_bits), other.raw << (f - other.fmt.frac_bits)
        raw = other * self.fmt.one
        if raw != int(raw):
            raise ValueError(f"comparison constant {other} is not exactly representable in {self.fmt}")
        return self.raw, int(raw)

    def __ge__(self, other):
        a, b = self._compare_raw(other)
        return a >= b

    def __lt__(self, other):
        a, b = self._compare_raw(other)
        return a < b

    def quantize(self, to, rounding, overflow, op="quantize"):
        """The one narrowing step: to format ``to`` with named rounding and overflow."""
        to = Format.parse(to)
        return Fixed(quantize_raw(self.raw, self.fmt, to, rounding, overflow, op=op), to)

    def where(self, condition, other):
        """``self`` where ``condition`` else ``other``: a multiplexer; formats must match."""
        other = _coerce(other)
        if other.fmt != self.fmt:
            raise ValueError(f"where: both sides must have the same format, not {self.fmt} and {other.fmt}")
        return Fixed(np.where(condition, self.raw, other.raw), self.fmt)


def _coerce(value):
    if isinstance(value, Fixed):
        return value
    raise TypeError(f"fixed-point operands must be Fixed, not {type(value).__name__}; "
                    f"use Fixed.const(value, fmt) for constants")
