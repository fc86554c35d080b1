"""Fixed-point values for Amaranth: the hardware twin of :mod:`phongfx.golden.fixed`.

:class:`FixedValue` pairs an Amaranth value with its :class:`~phongfx.core.format.Format`;
:class:`FixedVector` is three of them (X, Y, Z datapaths).  Operators build the
same exact expressions as the golden model, with result formats taken from the
same :class:`Format` methods, and :meth:`FixedValue.quantize` implements the same
rounding and overflow names bit for bit (on raw values: :mod:`phongfx.hdl.quantize`).  :func:`stage` and :func:`delay` add
pipeline registers, so a component reads like its golden function with the
register boundaries marked.

Pipelining by cycle tags: a :class:`FixedValue` may carry the ``cycle`` at which it
is valid (clocks after the block's input, 0 for an input port) and the module its
registers go in; an untagged one (``cycle=None``: constants, and every value of a
block that does not use tags) is taken as valid at any cycle.  :func:`stage` adds
one; an operator whose operands sit at different cycles first delays the earlier
one to the later (:meth:`FixedValue.at`; registers are shared between uses of the
same value).  So a block only marks where its registers go (:func:`cut` for the
optional ones of a pipeline depth, :func:`quantize_cut` and
:func:`~phongfx.hdl.dsp.split_product` for the deepest cuts) and every parallel path is
padded to match by construction;
:class:`~phongfx.hdl.block.PipelinedBlock` records the cycle each output leaves at,
for tests to hold against the block's ``latency`` formula.  Comparisons give plain
1-bit values (no tag): a flag that must wait alongside the data is made with
:meth:`FixedValue.flag`.

Overflow assertions: a :meth:`FixedValue.quantize` with ``overflow="error"`` (the
designer's claim that the value always fits) also builds, while a block is being
elaborated, a 1-bit flag "it did not fit" at the value's cycle (:func:`overflowed`),
collected by :mod:`phongfx.hdl.overflow`.
"""

from amaranth.hdl import Const, Mux, Signal, Value

from phongfx.core.format import Format

from .overflow import caller, collecting_overflow, probing, report_overflow, report_static
from .quantize import fit, overflowed, quantize

__all__ = ["FixedValue", "FixedVector", "fit", "quantize", "overflowed", "stage", "delay", "cut", "align",
           "quantize_cut"]


class FixedValue:
    """An Amaranth value holding raw codes of ``fmt``, valid at clock ``cycle`` (None: any).

    ``module`` is where delay registers for this value go (set by :func:`stage`;
    any value at a cycle above 0 has one); ``name`` names those registers.

    ``pre``: for a register's output (:func:`stage`), the value it holds one clock later,
    i.e. its input (a function of a register's output, such as a :meth:`shift`, has the
    same function of that input).  A DSP takes an operand from there into its own input
    register (:mod:`phongfx.hdl.dsp`); None for anything else.
    """

    def __init__(self, value, fmt, cycle=None, module=None, name=None):
        self.fmt = Format.parse(fmt)
        if isinstance(value, int):
            value = Const(value, self.fmt.shape())
        self.value = Value.cast(value)
        self.cycle = cycle
        self.module = module
        self.name = name
        self.pre = None
        self._delayed = [self]  # self delayed by 0, 1, 2 ... cycles, built on demand

    def at(self, cycle):
        """This value delayed to ``cycle`` (earlier than its own is an error; untagged: itself)."""
        if self.cycle is None or cycle is None:
            return self
        if cycle < self.cycle:
            raise ValueError(f"{self.name or 'value'} is valid at cycle {self.cycle}, "
                             f"it cannot be used at {cycle}")
        while len(self._delayed) <= cycle - self.cycle:
            last = self._delayed[-1]
            index = len(self._delayed)
            self._delayed.append(stage(self.module, last, f"{self.name or 'delay'}_d{index}"))
        return self._delayed[cycle - self.cycle]

    def tagged(self, cycle, module):
        """This value declared valid at ``cycle`` in ``module``: how a block with
        hand-aligned registers (no cycle tags) marks what its overflow flags must wait for."""
        return FixedValue(self.value, self.fmt, cycle, module, self.name)

    def flag(self, condition, name=None):
        """A 1-bit :class:`FixedValue` (format ``1.0``) ``condition`` at this value's cycle."""
        return FixedValue(condition, "1.0", self.cycle, self.module, name)

    @classmethod
    def const(cls, value, fmt):
        """A constant that ``fmt`` holds exactly (e.g. 1.0)."""
        fmt = Format.parse(fmt)
        return cls(Const(fmt.exact_raw(value), fmt.shape()), fmt)

    def _align(self, fmt):
        return self.value << (fmt.frac_bits - self.fmt.frac_bits)

    def _result(self, expr, fmt, *others):
        # cast to exactly the format's width (Format's result holds every exact value)
        module = next((v.module for v in (self, *others) if v.module is not None), None)
        return FixedValue(fit(expr, fmt), fmt, _latest(self, *others), module)

    def __add__(self, other):
        a, b = align(self, other)
        fmt = a.fmt.add(b.fmt)
        return a._result(a._align(fmt) + b._align(fmt), fmt, b)

    def __sub__(self, other):
        a, b = align(self, other)
        fmt = a.fmt.sub(b.fmt)
        return a._result(a._align(fmt) - b._align(fmt), fmt, b)

    def __mul__(self, other):
        if isinstance(other, FixedVector):
            return other * self
        a, b = align(self, other)
        return a._result(a.value * b.value, a.fmt.mul(b.fmt), b)

    def __neg__(self):
        fmt = self.fmt.neg()
        return self._result(-self.value, fmt)

    def shift(self, amount):
        """Exact multiply by ``2**amount``: moves the point, not the bits."""
        result = self._result(self.value << self.fmt.shift_raw(amount), self.fmt.shift(amount))
        result.pre = None if self.pre is None else self.pre.shift(amount)
        return result

    def __lshift__(self, amount):
        return self.shift(amount)

    def __rshift__(self, amount):
        return self.shift(-amount)

    def _compare_values(self, other):
        # same rule as the golden model: a number compares by its exact raw code
        if isinstance(other, FixedValue):
            self, other = align(self, other)
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

    def quantize(self, to, rounding, overflow, parallel_clamp=False):
        to = Format.parse(to)
        if overflow == "error" and collecting_overflow():
            bad = overflowed(self.value, self.fmt, to, rounding)
            # the claim's words and source line matter to a proof only: no frame walk otherwise
            claim = f"{self.fmt} -> {to} ({rounding}) at {caller(('fixed.py', 'dsp.py'))}" if probing() else ""
            if bad is not None:
                report_overflow(self.flag(bad, "overflow"), claim)
            else:
                report_static(claim)
        return FixedValue(quantize(self.value, self.fmt, to, rounding, overflow, parallel_clamp), to,
                          self.cycle, self.module)

    def where(self, condition, other):
        """``self`` if ``condition`` else ``other`` (formats must match, as in the golden model).

        ``condition`` is a plain 1-bit value of the operands' cycle or a
        :meth:`flag`, aligned with them like any operand."""
        if other.fmt != self.fmt:
            raise ValueError(f"where: both sides must have the same format, not {self.fmt} and {other.fmt}")
        if isinstance(condition, FixedValue):
            condition, a, b = align(condition, self, other)
            condition = condition.value
        else:
            a, b = align(self, other)
        return a._result(Mux(condition, a.value, b.value), a.fmt, b)


class FixedVector:
    """Three :class:`FixedValue` of one format: the paper's triple X, Y, Z lines."""

    def __init__(self, items):
        items = list(items)
        if len(items) != 3 or len({item.fmt for item in items}) != 1:
            raise ValueError("a FixedVector needs three FixedValue of one format")
        self.items = items
        self.fmt = items[0].fmt

    @classmethod
    def from_array(cls, array, fmt, cycle=None, module=None, name=None):
        """Wrap the three elements of an ``ArrayLayout`` view (or any indexable of 3)."""
        return cls(FixedValue(array[i], fmt, cycle, module, f"{name}_{axis}" if name else None)
                   for i, axis in zip(range(3), "xyz"))

    @property
    def cycle(self):
        return _latest(*self.items)

    def at(self, cycle):
        return FixedVector(item.at(cycle) for item in self.items)

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
        items = align(*self.items)
        total = items[0].value + items[1].value + items[2].value
        return items[0]._result(total, fmt, *items[1:])

    def dot(self, other):
        return (self * other).sum()

    def quantize(self, to, rounding, overflow, parallel_clamp=False):
        return FixedVector(a.quantize(to, rounding, overflow, parallel_clamp) for a in self)

    def values(self):
        return [a.value for a in self]


def stage(m, x, name=None):
    """Register ``x`` (FixedValue, FixedVector, or plain Value) for one clock."""
    if isinstance(x, FixedVector):
        return FixedVector(stage(m, a, f"{name}_{axis}" if name else None)
                           for a, axis in zip(x, "xyz"))
    if isinstance(x, FixedValue):
        cycle = None if x.cycle is None else x.cycle + 1
        out = FixedValue(stage(m, x.value, name), x.fmt, cycle, m, name)
        out.pre = x
        return out
    x = Value.cast(x)
    reg = Signal(x.shape(), name=name)
    m.d.sync += reg.eq(x)
    return reg


def delay(m, x, cycles, name=None):
    """``x`` delayed by ``cycles`` registers (``cycles`` may be 0)."""
    for index in range(cycles):
        x = stage(m, x, f"{name}_d{index + 1}" if name else None)
    return x


def cut(m, x, on, name=None):
    """:func:`stage` ``x`` if ``on`` (a pipeline depth's optional register), else ``x``."""
    return stage(m, x, name) if on else x


def quantize_cut(m, x, to, rounding, overflow, on, name=None, bits=False):
    """``x.quantize(to, rounding, overflow)``, with a register between its rounding adder and
    its clamp (comparators) if ``on``: the same codes, one clock later.

    The rounded value is held exactly in ``to``'s fraction bits and one integer bit more
    than ``x`` has (rounding up can carry that far), so the clamp behind the register sees
    what the one-step quantize would have clamped; it compares with both limits in parallel,
    by bit tests rather than comparators if ``bits`` (no carry chain before the multiplexer).
    """
    if not on:
        return x.quantize(to, rounding, overflow)
    to = Format.parse(to)
    mid = Format(x.fmt.int_bits + 1, to.frac_bits, x.fmt.signed)
    return stage(m, x.quantize(mid, rounding, "wrap"), name).quantize(to, rounding, overflow,
                                                                      "bits" if bits else True)


def align(*values):
    """``values`` (:class:`FixedValue` / :class:`FixedVector`) each delayed to the latest one's cycle."""
    cycle = _latest(*values)
    return [value.at(cycle) for value in values]


def _latest(*values):
    """The latest cycle tag of ``values``, None if none is tagged."""
    cycles = [value.cycle for value in values if value.cycle is not None]
    return max(cycles) if cycles else None
