"""Interval values that run the golden models unchanged: per element, where the hardware's value
can be and how far it can be from the ideal one.

An :class:`Interval` stands in for a :class:`~phongfx.golden.fixed.Fixed` (it is a subclass,
so that ``Fixed.const(1, fmt) - z`` reaches :meth:`Interval.__rsub__` before ``Fixed``'s own
operator refuses it) and carries, for every element (one element per box of the input domain):

* ``lo``, ``hi``: bounds on the hardware's value (real numbers, not raw codes);
* the deviation ``δ = hardware - ideal``, where *ideal* is the same computation with every
  ``quantize`` removed, fed the exact float inputs, as an affine form
  ``δ = Σ_k terms_k·ε_k + r`` over shared noise symbols ``|ε_k| <= 1`` (the input's own
  errors) and an independent remainder ``|r| <= err``; :attr:`dev` ``= Σ|terms_k| + err``
  bounds ``|δ|``.  The shared symbols let errors cancel where the datapath cancels them:
  Lyon's normalizer (Figure 7a) takes out the part of an error in ``N'`` along ``N'``, which
  per-component bounds would count three times over;
* ``fmt``: the format the golden model gives the value (the same :class:`Format` arithmetic as
  :class:`Fixed`, so the blocks' ``quantize`` calls and shifts read alike).

The rules, for ``a'``, ``b'`` the ideal values, ``m`` and ``ρ`` the midpoint and radius of a
hardware range:

* ``a ± b``: forms add; ``a·b - a'b' = a·δb + b'·δa``, so its terms are ``m_a·terms_b +
  m_b·terms_a`` and its remainder ``|m_a|·err_b + ρ_a·dev_b + |m_b|·err_a + (ρ_b + dev_b)·dev_a``
  (``a·a``: ``2m_a·terms_a`` and ``2|m_a|·err_a + 2ρ_a·dev_a + dev_a²``);
* ``quantize``: the rounding's own error is added (``2^-(f+1)`` to nearest, ``2^-f - 2^-g``
  truncating ``g`` fraction bits to ``f``); its overflow policy is taken only where the range
  proves it sound: ``"saturate"`` is a clamp, which moves no value that is inside the format
  and any other by at most its distance to the format, so ``err`` grows by
  ``max(0, hi + dev - max, min - lo + dev)``; ``"wrap"`` and ``"error"`` where the range may
  leave the format give ``err = inf`` (no bound) and name the quantize in :attr:`faults`;
* a comparison gives a :class:`Condition`; ``where`` picks per element when hardware and ideal
  both decide the same way, takes ``e_v`` when it is a clamp ``max(v, c)``/``min(v, c)`` (a
  1-Lipschitz function of ``v``, as the diffuse unit's backside clamp), and otherwise the largest
  difference between one branch's hardware value and the other's ideal one (a clamp or a mixed
  choice keeps no terms: its ``dev`` becomes the remainder).

Floating point: each result is widened outward by one unit in the last place and every ``err``
by a relative ``2^-50``, which covers float64's own rounding of these few operations; before
rounding, the bounds snap to the source format's grid, on which every hardware value lies.
"""

import functools

import numpy as np

from phongfx.core.format import Format
from phongfx.golden.fixed import Fixed

__all__ = ["Interval", "Condition", "rounding_error", "least", "most"]

_GROW = 1.0 + 2.0 ** -50


def rounding_error(frm, to, rounding):
    """The largest ``|rounded - value|`` of one quantize from format ``frm`` to ``to``."""
    drop = frm.frac_bits - to.frac_bits
    if drop <= 0:
        return 0.0
    return to.lsb - frm.lsb if rounding == "truncate" else to.lsb / 2


def _round(value, frac, rounding):
    """``value`` (on a finer grid) rounded to ``frac`` fraction bits: a monotone map."""
    scaled = value * 2.0 ** frac
    if rounding == "truncate":
        out = np.floor(scaled)
    elif rounding == "round_half_up":
        out = np.floor(scaled + 0.5)
    else:
        out = np.rint(scaled)
    return out * 2.0 ** -frac


def least(values):
    """The elementwise minimum of four arrays (an interval product's corners), without stacking
    them (``np.minimum.reduce`` of a list copies it into one array first): the same floats, sooner
    (a twelfth of the certificates' time went to stacking)."""
    return np.minimum(np.minimum(values[0], values[1]), np.minimum(values[2], values[3]))


def most(values):
    """The elementwise maximum of four arrays, as :func:`least`."""
    return np.maximum(np.maximum(values[0], values[1]), np.maximum(values[2], values[3]))


def _widen(lo, hi):
    # at least one unit in the last place outward (cheaper than nextafter, and as sound)
    return lo - (np.abs(lo) * 2.0 ** -51 + 1e-300), hi + (np.abs(hi) * 2.0 ** -51 + 1e-300)


class Condition:
    """``value >= threshold`` (``ge``) or ``value < threshold`` per element, seen from both
    sides: :attr:`hw_true` / :attr:`hw_false` where the hardware may decide so, and
    :attr:`ideal_true` / :attr:`ideal_false` where the ideal computation may."""

    def __init__(self, value, threshold, ge):
        self.value, self.threshold, self.ge = value, threshold, ge
        lo, hi, e = value.lo, value.hi, value.dev
        above_hw, below_hw = hi >= threshold, lo < threshold
        above_id, below_id = hi + e >= threshold, lo - e < threshold
        self.hw_true, self.hw_false = (above_hw, below_hw) if ge else (below_hw, above_hw)
        self.ideal_true, self.ideal_false = (above_id, below_id) if ge else (below_id, above_id)


class Interval(Fixed):
    """Hardware range ``[lo, hi]`` and deviation form (``terms``, ``err``) per element (module
    docstring); ``terms`` is None (no shared symbol) or of shape ``shape + (K,)``."""

    def __init__(self, lo, hi, err, fmt, faults=frozenset(), terms=None):  # no Fixed.__init__: no raw codes
        self.fmt = Format.parse(fmt)
        self.lo, self.hi = np.asarray(lo, dtype=np.float64), np.asarray(hi, dtype=np.float64)
        self.err = np.broadcast_to(np.asarray(err, dtype=np.float64), np.broadcast(self.lo, self.hi).shape)
        if terms is not None:
            terms = np.asarray(terms, dtype=np.float64)
            shape = np.broadcast_shapes(self.err.shape, terms.shape[:-1])
            self.err = np.broadcast_to(self.err, shape)
            terms = np.broadcast_to(terms, shape + terms.shape[-1:])
        self.terms = terms
        self.faults = frozenset(faults)

    @classmethod
    def exact(cls, values, fmt, err=0.0):
        """Known hardware values (``err`` their distance to the ideal ones, 0 by default)."""
        values = np.asarray(values, dtype=np.float64)
        return cls(values, values, err, fmt)

    @classmethod
    def of(cls, value):
        """``value`` as an Interval: a :class:`Fixed` is exact (its codes are the ideal too)."""
        if isinstance(value, Interval):
            return value
        if isinstance(value, Fixed):
            return cls.exact(value.to_float(), value.fmt)
        raise TypeError(f"operands must be Fixed or Interval, not {type(value).__name__}")

    @property
    def raw(self):
        raise TypeError("an Interval has ranges, not raw codes")

    @property
    def shape(self):
        return self.err.shape

    def __len__(self):
        return len(self.err)

    def __repr__(self):
        return f"Interval({self.fmt}, lo={self.lo!r}, hi={self.hi!r}, dev={self.dev!r})"

    def __getitem__(self, index):
        terms = None if self.terms is None else self.terms[index]
        return Interval(np.broadcast_to(self.lo, self.shape)[index], np.broadcast_to(self.hi, self.shape)[index],
                        self.err[index], self.fmt, self.faults, terms)

    @functools.cached_property
    def dev(self):
        """A bound on ``|hardware - ideal|`` per element (an Interval is not changed once made)."""
        if self.terms is None:
            return self.err
        # the symbols added one by one: the same sum as np.sum's over so few, several times faster
        total = np.abs(self.terms[..., 0])
        for k in range(1, self.terms.shape[-1]):
            total = total + np.abs(self.terms[..., k])
        return self.err + total

    @property
    def magnitude(self):
        """``max |hardware value|`` per element."""
        return np.maximum(np.abs(self.lo), np.abs(self.hi))

    @functools.cached_property
    def mid(self):
        """The middle of the hardware range (kept: a product asks for it twice per operand)."""
        return 0.5 * (self.lo + self.hi)

    @functools.cached_property
    def radius(self):
        """Half the hardware range (kept, as :attr:`mid`)."""
        return 0.5 * (self.hi - self.lo)

    def _make(self, lo, hi, err, fmt, other=None, terms=None):
        lo, hi = _widen(lo, hi)
        faults = self.faults | (other.faults if other is not None else frozenset())
        return Interval(lo, hi, err * _GROW, fmt, faults, terms)

    # -- exact arithmetic (the hardware's is exact between quantizes) -----------------------

    def _terms(self, scale=1.0):
        return None if self.terms is None else self.terms * np.asarray(scale)[..., None]

    def __add__(self, other):
        other = Interval.of(other)
        return self._make(self.lo + other.lo, self.hi + other.hi, self.err + other.err,
                          self.fmt.add(other.fmt), other, _sum(self.terms, other.terms))

    def __sub__(self, other):
        other = Interval.of(other)
        return self._make(self.lo - other.hi, self.hi - other.lo, self.err + other.err,
                          self.fmt.sub(other.fmt), other, _sum(self.terms, other._terms(-1.0)))

    def __radd__(self, other):
        return Interval.of(other) + self

    def __rsub__(self, other):
        return Interval.of(other) - self

    def __neg__(self):
        return self._make(-self.hi, -self.lo, self.err, self.fmt.neg(), terms=self._terms(-1.0))

    def __mul__(self, other):
        other = Interval.of(other)
        fmt = self.fmt.mul(other.fmt)
        if other is self:  # a squarer: its range is one-signed and tighter than a product's
            low = np.where((self.lo <= 0) & (self.hi >= 0), 0.0, np.minimum(self.lo ** 2, self.hi ** 2))
            m, dev = self.magnitude, self.dev
            err = 2 * np.abs(self.mid) * self.err + 2 * self.radius * dev + dev * dev
            return self._make(low, m * m, err, fmt, terms=self._terms(2 * self.mid))
        corners = [self.lo * other.lo, self.lo * other.hi, self.hi * other.lo, self.hi * other.hi]
        lo, hi = least(corners), most(corners)
        da, db = self.dev, other.dev
        err = (np.abs(self.mid) * other.err + self.radius * db
               + np.abs(other.mid) * self.err + (other.radius + db) * da)
        terms = _sum(other._terms(self.mid), self._terms(other.mid))
        return self._make(lo, hi, err, fmt, other, terms)

    def __rmul__(self, other):
        return Interval.of(other) * self

    def shift(self, amount):
        scale = 2.0 ** amount
        return Interval(self.lo * scale, self.hi * scale, self.err * scale, self.fmt.shift(amount), self.faults,
                        self._terms(scale))

    def sum(self, axis=-1):
        """The lanes along ``axis`` added in order, as ``+`` adds them one by one (the same float
        operations, on the arrays rather than an Interval per lane)."""
        axis = self.err.ndim + axis if axis < 0 else axis
        shape = self.shape
        lo, hi = (np.moveaxis(np.broadcast_to(v, shape), axis, 0) for v in (self.lo, self.hi))
        err = np.moveaxis(self.err, axis, 0)
        terms = None if self.terms is None else np.moveaxis(self.terms, axis, 0)
        total_lo, total_hi, total_err, fmt = lo[0], hi[0], err[0], self.fmt
        total_terms = None if terms is None else terms[0]
        for i in range(1, shape[axis]):
            total_lo, total_hi = _widen(total_lo + lo[i], total_hi + hi[i])
            total_err = (total_err + err[i]) * _GROW
            total_terms = None if terms is None else total_terms + terms[i]
            fmt = fmt.add(self.fmt)
        return Interval(total_lo, total_hi, total_err, fmt, self.faults, total_terms)

    def dot(self, other):
        other = Interval.of(other)
        return (self * self if other is self else self * other).sum(axis=-1)

    def within(self, lo, hi):
        """This value with its hardware range cut to ``[lo - dev, hi + dev]``: where the hardware
        can be when the ideal value is known to lie in ``[lo, hi]`` (a bound from the geometry,
        tighter than interval arithmetic's where L and V range over cones, :mod:`.cones`)."""
        dev = self.dev
        low = np.minimum(np.maximum(self.lo, lo - dev), self.hi)
        return Interval(low, np.maximum(np.minimum(self.hi, hi + dev), low), self.err, self.fmt, self.faults, self.terms)

    # -- the one narrowing step -------------------------------------------------------------

    def quantize(self, to, rounding, overflow, op="quantize"):
        to, frm = Format.parse(to), self.fmt
        lo, hi = _widen(self.lo, self.hi)
        grid = 2.0 ** frm.frac_bits
        lo, hi = np.ceil(lo * grid) / grid, np.floor(hi * grid) / grid
        lo, hi = _round(lo, to.frac_bits, rounding), _round(hi, to.frac_bits, rounding)
        err = (self.err + rounding_error(frm, to, rounding)) * _GROW
        low, top = to.min_raw * to.lsb, to.max_raw * to.lsb
        outside = (lo < low) | (hi > top)
        faults = self.faults
        if np.any(outside):
            if overflow == "saturate":
                dev = self.dev
                err = err + np.maximum(0.0, np.maximum(self.hi + dev - top, low - self.lo + dev))
                lo, hi = np.clip(lo, low, top), np.clip(hi, low, top)
            else:
                err = np.where(outside, np.inf, err)
                faults = faults | {op}
        return Interval(lo, hi, err, to, faults, self.terms)

    # -- comparators and multiplexers -------------------------------------------------------

    def _threshold(self, other):
        if isinstance(other, Fixed) and not isinstance(other, Interval):
            values = other.to_float()
            if values.size and np.all(values == values.flat[0]):
                return float(values.flat[0])
        if isinstance(other, (int, float)):
            return float(other)
        raise TypeError("an Interval compares with a number or a constant Fixed only")

    def __ge__(self, other):
        return Condition(self, self._threshold(other), ge=True)

    def __lt__(self, other):
        return Condition(self, self._threshold(other), ge=False)

    def where(self, condition, other):
        """``self`` where ``condition`` else ``other`` (module docstring)."""
        if not isinstance(condition, Condition):
            raise TypeError("Interval.where takes the Condition of an Interval comparison")
        other = Interval.of(other)
        if other.fmt != self.fmt:
            raise ValueError(f"where: both sides must have the same format, not {self.fmt} and {other.fmt}")
        c = condition
        pick_self, pick_other = c.hw_true, c.hw_false
        (s_lo, s_hi), (o_lo, o_hi) = self._taken(c, True), other._taken(c, False)
        lo = np.where(pick_self & pick_other, np.minimum(s_lo, o_lo), np.where(pick_self, s_lo, o_lo))
        hi = np.where(pick_self & pick_other, np.maximum(s_hi, o_hi), np.where(pick_self, s_hi, o_hi))
        only_self = c.hw_true & c.ideal_true & ~c.hw_false & ~c.ideal_false
        only_other = c.hw_false & c.ideal_false & ~c.hw_true & ~c.ideal_true
        ds, do = self.dev, other.dev
        if self._is_clamp(c, other):
            mixed = c.value.dev
        else:
            cross_a = np.maximum(self.hi - other.lo + do, other.hi + do - self.lo)
            cross_b = np.maximum(other.hi - self.lo + ds, self.hi + ds - other.lo)
            mixed = np.maximum(np.maximum(np.where(c.hw_true, ds, 0.0), np.where(c.hw_false, do, 0.0)),
                               np.maximum(np.where(c.hw_true & c.ideal_false, cross_a, 0.0),
                                          np.where(c.hw_false & c.ideal_true, cross_b, 0.0)))
        err = np.where(only_self, self.err, np.where(only_other, other.err, mixed))
        terms = None
        if self.terms is not None or other.terms is not None:
            zero = np.zeros(1)
            ts = self.terms if self.terms is not None else zero
            to = other.terms if other.terms is not None else zero
            terms = np.where(only_self[..., None], ts, np.where(only_other[..., None], to, 0.0))
        return Interval(lo, hi, err, self.fmt, self.faults | other.faults, terms)

    def _taken(self, c, when):
        """This branch's hardware range where ``c`` is ``when``: the compared value itself
        lies on that side of the threshold there."""
        if self is not c.value:
            return self.lo, self.hi
        if c.ge == when:  # taken where value >= threshold
            return np.maximum(self.lo, c.threshold), self.hi
        return self.lo, np.minimum(self.hi, c.threshold)

    def _is_clamp(self, c, other):
        """Whether this ``where`` is ``v`` on one side of the threshold and the threshold itself
        on the other, so a continuous clamp of ``v``."""
        def constant(x):
            return np.all(x.dev == 0) and np.all(x.lo == c.threshold) and np.all(x.hi == c.threshold)
        return bool((self is c.value and constant(other)) or (other is c.value and constant(self)))


def _sum(a, b):
    if a is None:
        return b
    if b is None:
        return a
    return a + b
