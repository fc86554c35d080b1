"""Raw fixed-point arrays for the golden models.

A :class:`Fixed` is a numpy ``int64`` array of raw codes paired with its
:class:`~phongfx.core.format.Format`.  Arithmetic is exact and the result format grows
as the hardware's would (:meth:`Format.add`, :meth:`Format.mul`, ...); the only
narrowing operation is :meth:`Fixed.quantize`, which names its rounding and its
overflow policy (the step itself, on raw codes, is :mod:`phongfx.golden.quantize`).  :mod:`phongfx.hdl.fixed` implements the same ``quantize`` for
Amaranth, so a block's golden model and its component read alike.
"""

import math
from fractions import Fraction
from functools import lru_cache

import numpy as np

from phongfx.core.format import Format, check_overflow, check_rounding

from .chunks import CHUNK
from .quantize import FixedOverflowError, as_raw, narrow, overflow_error, quantize_raw, round_float

__all__ = ["Fixed", "FixedOverflowError", "quantize_raw", "check_range"]


@lru_cache(maxsize=4096)
def _raw_bound(bound, fmt, lower):
    """Exact raw bound for ``raw >= bound`` (``lower``) or ``raw <= bound``, as a Python int,
    or None when the format's whole range satisfies it, or "all" when none of it does."""
    if math.isinf(bound):
        return None if (bound < 0) == lower else "all"
    scaled = Fraction(bound) * fmt.one
    raw = math.ceil(scaled) if lower else math.floor(scaled)
    if lower:
        return None if raw <= fmt.min_raw else "all" if raw > fmt.max_raw else raw
    return None if raw >= fmt.max_raw else "all" if raw < fmt.min_raw else raw


def check_range(name, value, lo, hi):
    """Refuse input values outside ``lo..hi`` (floats) with a message naming ``name``."""
    # exact raw bounds: int64 codes compared with float bounds round past 53 bits
    low, high = _raw_bound(lo, value.fmt, True), _raw_bound(hi, value.fmt, False)
    raw = value.raw
    if not raw.size or (low is None and high is None):
        return value
    if "all" not in (low, high) and (low is None or raw.min() >= low) and (high is None or raw.max() <= high):
        return value  # one min/max pair: the mask below only to say what is wrong
    bad = np.zeros(raw.shape, dtype=bool)
    for raw_bound, lower in ((low, True), (high, False)):
        if raw_bound == "all":
            bad[...] = True
        elif raw_bound is not None:
            bad |= (raw < raw_bound) if lower else (raw > raw_bound)
    first = raw[bad].flat[0]
    raise ValueError(f"{name} must be in {lo:g}..{hi:g}; {int(np.count_nonzero(bad))} value(s) "
                     f"are not, first {int(first) * value.fmt.lsb:g} (raw {int(first)})")


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
        self.raw = as_raw(raw)
        if self.raw.size and (self.raw.min() < self.fmt.min_raw or self.raw.max() > self.fmt.max_raw):
            bad = (self.raw < self.fmt.min_raw) | (self.raw > self.fmt.max_raw)
            raise ValueError(
                f"raw codes must lie in {self.fmt.min_raw}..{self.fmt.max_raw} for format "
                f"{self.fmt}; {int(np.count_nonzero(bad))} do not, first {int(self.raw[bad].flat[0])}")

    @classmethod
    def _of(cls, raw, fmt):
        """``raw`` in ``fmt`` unchecked: the results of this class's operations lie in ``fmt`` by
        construction (an exact operation's format covers its operands' whole ranges; a quantize
        saturates, wraps or raises), and the check was a fifth of the golden models' time."""
        if type(raw) is not np.ndarray:  # an operation on two 0-d arrays gives a numpy scalar
            raw = as_raw(raw)
        # left writeable: a fresh result is nobody else's; a view of an operand is read-only
        value = cls.__new__(cls)
        value.fmt, value.raw = fmt, raw
        return value

    @classmethod
    def from_float(cls, value, fmt, rounding="round_half_up", overflow="error"):
        """Quantize float values to ``fmt`` with a named rounding and overflow policy."""
        fmt = Format.parse(fmt)
        check_rounding(rounding)
        check_overflow(overflow)
        value = np.asarray(value, dtype=np.float64)
        # one min/max pair: whether every value is finite, and (value·2^frac and each
        # rounding being monotone) the range of the codes, before any array pass
        ends = np.array([value.min(), value.max()]) if value.size else np.zeros(2)
        if not np.all(np.isfinite(ends)):
            raise ValueError(f"from_float: values must be finite to convert to {fmt}")
        with np.errstate(over="ignore", invalid="ignore"):
            lo, hi = round_float(ends * float(fmt.one), rounding)
        inside = lo >= fmt.min_raw and hi <= fmt.max_raw
        if fmt.width <= 53 and (inside or overflow == "saturate"):
            # the bounds are floats exactly: clip (saturating as below) and convert, a chunk
            # at a time so that the float temporaries stay in the CPU's cache
            flat, out = value.reshape(-1), np.empty(value.size, np.int64)
            for start in range(0, flat.size, CHUNK):
                with np.errstate(over="ignore", invalid="ignore"):
                    raw = round_float(flat[start:start + CHUNK] * float(fmt.one), rounding)
                if not inside:
                    np.clip(raw, float(fmt.min_raw), float(fmt.max_raw), out=raw)
                out[start:start + CHUNK] = raw
            return cls._of(out.reshape(value.shape), fmt)
        with np.errstate(over="ignore", invalid="ignore"):
            # exact (a power of two) unless it overflows to inf, which is out of range anyway
            raw = round_float(value * float(fmt.one), rounding)
        # the range checks in floats are exact: min_raw and max_raw + 1 are 0 or powers of two
        low, high = raw < float(fmt.min_raw), raw >= float(fmt.max_raw + 1)
        bad = low | high
        codes = np.where(bad, 0.0, raw).astype(np.int64)
        if np.any(bad):
            if overflow == "error":
                index = np.flatnonzero(bad)[0]
                first = raw.flat[index]
                # past the float range a finite value is an integer: its code is exact
                first = int(first) if np.isfinite(first) else int(value.flat[index]) * fmt.one
                raise overflow_error("from_float", fmt, int(np.count_nonzero(bad)), first)
            if overflow == "saturate":
                codes = np.where(high, fmt.max_raw, np.where(low, fmt.min_raw, codes))
            else:
                # the code modulo 2**width, brought into int64 range: fmod is exact, and
                # so (Sterbenz) is moving its result by one modulus into [-half, half);
                # a scaled value too large for a float is a multiple of any 2**width
                modulus, half = 2.0 ** fmt.width, 2.0 ** (fmt.width - 1)
                with np.errstate(invalid="ignore"):
                    wrapped = np.where(np.isinf(raw), 0.0, np.fmod(raw, modulus))
                wrapped = np.where(wrapped >= half, wrapped - modulus, wrapped)
                wrapped = np.where(wrapped < -half, wrapped + modulus, wrapped)
                codes = np.where(bad, wrapped.astype(np.int64), codes)
                codes = quantize_raw(codes, fmt, fmt, rounding, "wrap", op="from_float")
        return cls(codes, fmt)

    @classmethod
    def const(cls, value, fmt):
        """A scalar constant that ``fmt`` holds exactly (e.g. 1.0)."""
        return _const(value, Format.parse(fmt))

    def to_float(self):
        return self.raw.astype(np.float64) * self.fmt.lsb

    def __repr__(self):
        return f"Fixed({self.fmt}, {self.to_float()!r})"

    def __len__(self):
        return len(self.raw)

    def __getitem__(self, index):
        return Fixed._of(self.raw[index], self.fmt)

    @property
    def shape(self):
        return self.raw.shape

    # -- exact arithmetic -------------------------------------------------------------------

    def _align(self, fmt):
        shift = fmt.frac_bits - self.fmt.frac_bits
        return self.raw << shift if shift else self.raw  # ``<< 0`` would copy the array

    def __add__(self, other):
        other = _coerce(other)
        fmt = self.fmt.add(other.fmt)
        return Fixed._of(self._align(fmt) + other._align(fmt), fmt)

    def __sub__(self, other):
        other = _coerce(other)
        fmt = self.fmt.sub(other.fmt)
        return Fixed._of(self._align(fmt) - other._align(fmt), fmt)

    def __mul__(self, other):
        other = _coerce(other)
        return Fixed._of(_product(self.raw, other.raw), self.fmt.mul(other.fmt))

    def __neg__(self):
        return Fixed._of(-self.raw, self.fmt.neg())

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
        move = self.fmt.shift_raw(amount)
        return Fixed._of(self.raw << move if move else self.raw, self.fmt.shift(amount))

    def sum(self, axis=-1):
        """Exact sum along ``axis`` (an adder tree: the format grows as for repeated adds)."""
        count, fmt = self.raw.shape[axis], _sum_format(self.fmt, self.raw.shape[axis])
        if 1 <= count <= 4:  # the X, Y, Z lanes: explicit adds beat numpy's reduction machinery
            lanes = np.moveaxis(self.raw, axis, 0)
            total = lanes[0].copy() if count == 1 else lanes[0] + lanes[1]
            for lane in lanes[2:]:
                total += lane
            return Fixed._of(total, fmt)
        return Fixed._of(self.raw.sum(axis=axis), fmt)

    def dot(self, other):
        """Exact dot product over the last axis (three multipliers and an adder tree)."""
        other = _coerce(other)
        a, b, product = self.raw, other.raw, self.fmt.mul(other.fmt)
        count = a.shape[-1] if a.ndim else 0
        if not 1 <= count <= 4 or b.ndim == 0 or b.shape[-1] != count:
            return (self * other).sum(axis=-1)
        total = a[..., 0] * b[..., 0]  # lane by lane: no (count, 3) temporary of products
        for lane in range(1, count):
            total += a[..., lane] * b[..., lane]
        return Fixed._of(total, _sum_format(product, count))

    def _compare_raw(self, other):
        # comparisons against a number use its exact raw code in this format.
        # Two Fixed: rather than align the coarser code up (which can pass int64), bring
        # the finer one down, rounded so >= and < stay exact: for integers a, b and
        # d > 0, a*2**d >= b  <=>  a >= ceil(b/2**d), and a >= b*2**d  <=>  floor(a/2**d) >= b
        if isinstance(other, Fixed):
            d = other.fmt.frac_bits - self.fmt.frac_bits
            if d > 0:
                mask = (1 << d) - 1
                return self.raw, (other.raw >> d) + ((other.raw & mask) != 0)
            return self.raw >> -d, other.raw
        return self.raw, self.fmt.exact_raw(other, "comparison constant")

    def __ge__(self, other):
        a, b = self._compare_raw(other)
        return a >= b

    def __lt__(self, other):
        a, b = self._compare_raw(other)
        return a < b

    def quantize(self, to, rounding, overflow, op="quantize"):
        """The one narrowing step: to format ``to`` with named rounding and overflow."""
        to = Format.parse(to)
        check_rounding(rounding)
        check_overflow(overflow)
        return Fixed._of(narrow(self.raw, self.fmt, to, rounding, overflow, op, inside=True), to)

    def where(self, condition, other):
        """``self`` where ``condition`` else ``other``: a multiplexer; formats must match."""
        other = _coerce(other)
        if other.fmt != self.fmt:
            raise ValueError(f"where: both sides must have the same format, not {self.fmt} and {other.fmt}")
        if isinstance(condition, np.ndarray) and condition.dtype == bool:
            # a mux to 0 is a multiply by the condition: np.where branches on every element,
            # 5-8× slower where the condition is as random as a backside test
            if other.raw.ndim == 0 and other.raw == 0:
                return Fixed._of(self.raw * condition, self.fmt)
            if self.raw.ndim == 0 and self.raw == 0:
                return Fixed._of(other.raw * ~condition, self.fmt)
        return Fixed._of(np.where(condition, self.raw, other.raw), self.fmt)


def _product(a, b):
    """``a * b``; a vector (count, 3) by a column (count, 1) lane by lane, as numpy's broadcast
    of the length-1 axis runs its inner loop three values at a time (2-3× slower)."""
    if a.ndim != 2 or b.ndim != 2 or len(a) != len(b) or (a.shape[1] == 1) == (b.shape[1] == 1):
        return a * b
    vector, column = (a, b[:, 0]) if b.shape[1] == 1 else (b, a[:, 0])
    if vector.shape[1] > 4:
        return a * b
    out = np.empty(vector.shape, np.int64)
    for lane in range(vector.shape[1]):
        np.multiply(vector[:, lane], column, out=out[:, lane])
    return out


@lru_cache(maxsize=1024)
def _const(value, fmt):
    """:meth:`Fixed.const`, made once per value and format: the golden models ask for the same
    few constants (1, 0) on every call, and a Fixed is read-only."""
    return Fixed(fmt.exact_raw(value), fmt)


@lru_cache(maxsize=1024)
def _sum_format(fmt, count):
    """Format of the exact sum of ``count`` values of ``fmt`` (an adder tree)."""
    total = fmt
    for _ in range(count - 1):
        total = total.add(fmt)
    return total


def _coerce(value):
    if isinstance(value, Fixed):
        return value
    raise TypeError(f"fixed-point operands must be Fixed, not {type(value).__name__}; "
                    f"use Fixed.const(value, fmt) for constants")
