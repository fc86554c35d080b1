"""Fixed-point values for Amaranth: the hardware twin of :mod:`phongfx.golden.fixed`.

:class:`FixedValue` pairs an Amaranth value with its :class:`~phongfx.format.Format`;
:class:`FixedVector` is three of them (X, Y, Z datapaths).  Operators build the
same exact expressions as the golden model, with result formats taken from the
same :class:`Format` methods, and :meth:`FixedValue.quantize` implements the same
rounding and overflow names bit for bit.  :func:`stage` and :func:`delay` add
pipeline registers, so a component reads like its golden function with the
register boundaries marked.
"""

from amaranth.hdl import Cat, Const, Mux, Signal, Value

from ..format import Format, check_overflow, check_rounding

__all__ = ["FixedValue", "FixedVector", "quantize", "stage", "delay"]


def _fit(value, fmt):
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


def quantize(value, frm, to, rounding, overflow):
    """Narrow ``value`` (raw codes of ``frm``) to ``to``; twin of ``golden.fixed.quantize_raw``.

    ``overflow="error"`` declares that overflow cannot happen: the golden model
    checks it and raises; the hardware keeps the low bits, as ``wrap`` does.
    """
    frm, to = Format.parse(frm), Format.parse(to)
    check_rounding(rounding)
    check_overflow(overflow)
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
    if overflow == "saturate":
        # clamp only on a side the value can reach: a comparison that is constant
        # (an unsigned value < 0) is dead logic, and Verilator lint flags it
        shape = value.shape()
        lowest = -(1 << (shape.width - 1)) if shape.signed else 0
        highest = (1 << (shape.width - 1 if shape.signed else shape.width)) - 1
        if lowest < to.min_raw:
            value = Mux(value < to.min_raw, to.min_raw, value)
        if highest > to.max_raw:
            value = Mux(value > to.max_raw, to.max_raw, value)
    return _fit(value, to)


class FixedValue:
    """An Amaranth value holding raw codes of ``fmt``."""

    def __init__(self, value, fmt):
        self.fmt = Format.parse(fmt)
        if isinstance(value, int):
            value = Const(value, self.fmt.shape())
        self.value = Value.cast(value)

    @classmethod
    def const(cls, value, fmt):
        """A constant that ``fmt`` holds exactly (e.g. 1.0)."""
        fmt = Format.parse(fmt)
        return cls(Const(fmt.exact_raw(value), fmt.shape()), fmt)

    def _align(self, fmt):
        return self.value << (fmt.frac_bits - self.fmt.frac_bits)

    def _result(self, expr, fmt):
        # cast to exactly the format's width (Format's result holds every exact value)
        return FixedValue(_fit(expr, fmt), fmt)

    def __add__(self, other):
        fmt = self.fmt.add(other.fmt)
        return self._result(self._align(fmt) + other._align(fmt), fmt)

    def __sub__(self, other):
        fmt = self.fmt.sub(other.fmt)
        return self._result(self._align(fmt) - other._align(fmt), fmt)

    def __mul__(self, other):
        if isinstance(other, FixedVector):
            return other * self
        return self._result(self.value * other.value, self.fmt.mul(other.fmt))

    def __neg__(self):
        fmt = self.fmt.neg()
        return self._result(-self.value, fmt)

    def shift(self, amount):
        """Exact multiply by ``2**amount``: moves the point, not the bits."""
        return self._result(self.value << self.fmt.shift_raw(amount), self.fmt.shift(amount))

    def __lshift__(self, amount):
        return self.shift(amount)

    def __rshift__(self, amount):
        return self.shift(-amount)

    def _compare_values(self, other):
        # same rule as the golden model: a number compares by its exact raw code
        if isinstance(other, FixedValue):
            f = max(self.fmt.frac_bits, other.fmt.frac_bits)
            return (self.value << (f - self.fmt.frac_bits),
                    other.value << (f - other.fmt.frac_bits))
        return self.value, self.fmt.exact_raw(other, "comparison constant")

    def __ge__(self, other):
        a, b = self._compare_values(other)
        return a >= b

    def __lt__(self, other):
        a, b = self._compare_values(other)
        return a < b

    def quantize(self, to, rounding, overflow):
        to = Format.parse(to)
        return FixedValue(quantize(self.value, self.fmt, to, rounding, overflow), to)

    def where(self, condition, other):
        """``self`` if ``condition`` else ``other`` (formats must match, as in the golden model)."""
        if other.fmt != self.fmt:
            raise ValueError(f"where: both sides must have the same format, not {self.fmt} and {other.fmt}")
        return FixedValue(Mux(condition, self.value, other.value), self.fmt)


class FixedVector:
    """Three :class:`FixedValue` of one format: the paper's triple X, Y, Z lines."""

    def __init__(self, items):
        items = list(items)
        if len(items) != 3 or len({item.fmt for item in items}) != 1:
            raise ValueError("a FixedVector needs three FixedValue of one format")
        self.items = items
        self.fmt = items[0].fmt

    @classmethod
    def from_array(cls, array, fmt):
        """Wrap the three elements of an ``ArrayLayout`` view (or any indexable of 3)."""
        return cls(FixedValue(array[i], fmt) for i in range(3))

    def __getitem__(self, index):
        return self.items[index]

    def __iter__(self):
        return iter(self.items)

    def __add__(self, other):
        return FixedVector(a + b for a, b in zip(self, other))

    def __sub__(self, other):
        return FixedVector(a - b for a, b in zip(self, other))

    def __mul__(self, other):
        if isinstance(other, FixedVector):
            return FixedVector(a * b for a, b in zip(self, other))
        return FixedVector(a * other for a in self)

    __rmul__ = __mul__

    def shift(self, amount):
        return FixedVector(a.shift(amount) for a in self)

    def sum(self):
        """Exact sum of the three elements (adder tree), format as in ``Fixed.sum``."""
        fmt = self.fmt.add(self.fmt).add(self.fmt)
        total = self.items[0].value + self.items[1].value + self.items[2].value
        return self.items[0]._result(total, fmt)

    def dot(self, other):
        return (self * other).sum()

    def quantize(self, to, rounding, overflow):
        return FixedVector(a.quantize(to, rounding, overflow) for a in self)

    def values(self):
        return [a.value for a in self]


def stage(m, x, name=None):
    """Register ``x`` (FixedValue, FixedVector, or plain Value) for one clock."""
    if isinstance(x, FixedVector):
        return FixedVector(stage(m, a, f"{name}_{axis}" if name else None)
                           for a, axis in zip(x, "xyz"))
    if isinstance(x, FixedValue):
        return FixedValue(stage(m, x.value, name), x.fmt)
    x = Value.cast(x)
    reg = Signal(x.shape(), name=name)
    m.d.sync += reg.eq(x)
    return reg


def delay(m, x, cycles, name=None):
    """``x`` delayed by ``cycles`` registers (``cycles`` may be 0)."""
    for index in range(cycles):
        x = stage(m, x, f"{name}_d{index + 1}" if name else None)
    return x
