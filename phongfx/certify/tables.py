"""Exhaustive error tables of the table units' finite stages (:mod:`phongfx.golden.blinn`).

The conventional and Blinn units (Lyon 1993, "Background": "typically 16 bits of precision")
read two finite functions of a code: the normalizer's ``y1 = Y(m)`` (seed table and one
Newton–Raphson step, :func:`~phongfx.golden.blinn.reciprocal_sqrt`) of the 18-bit mantissa
``m`` of ``N·N``, and the specular power ``P(t, n)`` (log2 and exp2 tables with linear
interpolation, :func:`~phongfx.golden.blinn.power`) of the 16-bit cosine ``t``.  Every code is
run through the golden model once, so their errors are known exactly, not bounded by a formula:

* :func:`rsqrt_factor`: per mantissa code ``c`` the range of ``1 + r = Y(c)·sqrt(m)`` over the
  exact mantissas ``m`` that round to ``c`` (the hardware's ``2^(j-h)·y1`` is ``(1 + r)/sqrt(q)``
  with ``q = N·N``);
* :func:`power_error`: per ``t`` code the signed ``E(t) = P(t, n) - t^n``.

A box of the domain meets a range of codes; :class:`RangeTable` gives the largest value over
any range from maxima kept over aligned blocks of ``2^l`` codes (at most two blocks of the
smallest size that holds the range, so never under the range's own maximum).
"""

import functools

import numpy as np

from phongfx.config import BlinnConfig
from phongfx.core.format import Format
from phongfx.golden.blinn import log2_t, pow2, reciprocal_sqrt
from phongfx.golden.fixed import Fixed

__all__ = ["RangeTable", "rsqrt_factor", "power_error", "power_bound"]

#: float64's error in ``t^n`` and ``Y·sqrt(m)`` is under ``n·2^-52``: this covers it for any n
#: the units take (``n_max < 2^13``)
_SLACK = 1e-11


class RangeTable:
    """Maxima of ``values`` (float64, indexed by code) over aligned blocks of 2, 4, ... codes,
    kept in float32 rounded up (never below the float64 value)."""

    def __init__(self, values):
        values = np.asarray(values, dtype=np.float64)
        levels, offsets, at = [values], [0], len(values)
        while len(levels[-1]) > 1:
            last = levels[-1]
            if len(last) % 2:
                last = np.append(last, last[-1])
            offsets.append(at)
            levels.append(np.maximum(last[0::2], last[1::2]))
            at += len(levels[-1])
        flat = np.concatenate(levels)
        self.flat = np.nextafter(flat.astype(np.float32), np.float32(np.inf))
        self.offsets, self.size = np.array(offsets), len(values)

    def max(self, first, last):
        """Per element a bound on ``max(values[first..last])`` (inclusive code ranges, clipped
        to the table)."""
        first = np.clip(np.asarray(first, dtype=np.int64), 0, self.size - 1)
        last = np.clip(np.asarray(last, dtype=np.int64), first, self.size - 1)
        level = np.ceil(np.log2(np.maximum(last - first + 1, 1))).astype(np.int64)
        # float log2 may land one low at an exact power: one level up is still sound
        level = np.minimum(level + ((last >> level) - (first >> level) > 1), len(self.offsets) - 1)
        at = self.offsets[level]
        return np.maximum(self.flat[at + (first >> level)], self.flat[at + (last >> level)]).astype(np.float64)


def _code_range(values, fmt, rounding):
    """``(first, last)`` codes of ``fmt`` that values in ``[lo, hi]`` (a pair of arrays) round
    to, before saturation."""
    scaled = [np.asarray(v, dtype=np.float64) * 2.0 ** fmt.frac_bits for v in values]
    if rounding == "truncate":
        return np.floor(scaled[0]).astype(np.int64), np.floor(scaled[1]).astype(np.int64)
    return np.floor(scaled[0] + 0.5).astype(np.int64) - 1, np.floor(scaled[1] + 0.5).astype(np.int64) + 1


def _key(config, *names):
    return tuple((name, getattr(config, name)) for name in names)


@functools.lru_cache(maxsize=16)
def _rsqrt_tables(key):
    config = BlinnConfig(**dict(key))
    fmt = config.fmt("m")
    first = 1 << (fmt.frac_bits - 2)  # m >= 1/4: the even shift's mantissa
    codes = np.arange(first, 1 << fmt.frac_bits)
    y = reciprocal_sqrt(config, Fixed(codes, fmt)).to_float()
    c = codes * fmt.lsb
    # the exact mantissas that round to c (truncation: [c, c + lsb); to nearest: within lsb/2);
    # the top code also holds every m up to 1 (saturation), and no m is under 1/4
    below, above = (0.0, fmt.lsb) if config.rounding == "truncate" else (fmt.lsb / 2, fmt.lsb / 2)
    low = np.maximum(c - below, 0.25)
    high = np.minimum(c + above, 1.0)
    high[-1] = 1.0
    return first, RangeTable(-(y * np.sqrt(low) * (1 - _SLACK))), RangeTable(y * np.sqrt(high) * (1 + _SLACK))


def _shift(q):
    """``e`` with ``q`` in ``[4^(e-1), 4^e)`` (exact: from the float's own exponent)."""
    return (np.frexp(q)[1] - 1) // 2 + 1


def rsqrt_factor(config, q):
    """``(lo, hi, m_min)``: the range of ``1 + r = 2^(j-h)·y1·sqrt(q)`` over the exact ``q = N·N``
    in ``q = (lo, hi)`` (arrays, ``lo > 0``) and the smallest mantissa ``m`` there: the even shift takes ``q`` in ``[4^(e-1), 4^e)`` to ``m =
    q·4^-e`` in ``[1/4, 1)``, so a range across one power of 4 meets two runs of mantissas (the
    top ones and the bottom ones), and across more, every mantissa."""
    first, low, high = _rsqrt_tables(_key(config, "m", "rsqrt_addr", "y", "nr", "rounding"))
    fmt = config.fmt("m")
    q_lo, q_hi = (np.asarray(v, dtype=np.float64) for v in q)
    e_lo, e_hi = _shift(q_lo), _shift(q_hi)
    one, two = e_lo == e_hi, e_hi == e_lo + 1
    m_lo, m_hi = q_lo * 4.0 ** -e_lo, q_hi * 4.0 ** -e_hi
    runs = [(np.where(one | two, m_lo, 0.25), np.where(one, m_hi, 1.0)),
            (np.where(two, 0.25, np.where(one, m_lo, 0.25)), np.where(one | two, m_hi, 1.0))]
    lo, hi = np.inf, -np.inf
    for run in runs:
        a, b = _code_range(run, fmt, config.rounding)
        lo = np.minimum(lo, -low.max(a - first, b - first))
        hi = np.maximum(hi, high.max(a - first, b - first))
    return lo, hi, np.minimum(runs[0][0], runs[1][0])


@functools.lru_cache(maxsize=4)
def _log2_codes(key):
    config = BlinnConfig(**dict(key))
    fmt = config.fmt("t")
    codes = np.arange(1, (1 << fmt.frac_bits) + 1)  # t in (0, 1]: the clamped cosine
    return log2_t(config, Fixed(codes, fmt))


@functools.lru_cache(maxsize=128)  # about 0.8 MB each
def _power_tables(key, n):
    config = BlinnConfig(**dict(key))
    fmt = config.fmt("t")
    lam = _log2_codes(_key(config, "t", "log", "log_addr", "rounding"))
    spec = pow2(config, Fixed(np.full(len(lam), n, dtype=np.int64), Format.covering(0, n, 0)) * lam).to_float()
    t = np.arange(1, (1 << fmt.frac_bits) + 1) * fmt.lsb
    error = np.concatenate([[0.0], spec - t ** n])  # t = 0 gives 0 = 0^n
    return RangeTable(error + _SLACK), RangeTable(-error + _SLACK), RangeTable(np.concatenate([[0.0], spec]))


def power_error(config, n):
    """``(E_max, -E_min, P)``: :class:`RangeTable` of ``E(t) = P(t, n) - t^n``, of ``-E`` and of
    ``P`` per ``t`` code ``0..2^F`` (``t`` in ``[0, 1]``)."""
    return _power_tables(_key(config, "t", "log", "log_addr", "exp", "exp_addr", "out", "rounding"), int(n))


def power_bound(config, n, ideal, dev, hardware=None, bands=()):
    """``(bound, spec_hi, ideal_hi)`` per element: a bound on ``|P(t_hw, n) - t^n|`` for an
    ideal ``t`` in ``ideal = (a, b)`` (within ``[0, 1]``) and a hardware code ``t_hw`` within
    ``dev`` of it (and in ``hardware = (lo, hi)`` when given), the largest ``P(t_hw)`` and the
    largest ``t^n``; ``n`` an int array (one value or per element).

    ``P(t_hw) - t^n = E(t_hw) + (t_hw^n - t^n)``: ``E`` over the codes from :func:`power_error`,
    the second term at most ``max min(t + dev, 1)^n - t^n`` (rising with ``t`` until ``t + dev``
    reaches 1, falling after: largest at ``t = clip(1 - dev, a, b)``) and at least
    ``-max(t^n - max(t - dev, 0)^n)`` (rising with ``t``: at ``b``), with ``t_hw`` between the
    first and the last code of its range (near ``t = 1`` at a large ``n``, where the code's own
    step is most of ``dev``, that is what a bound needs); the signs of both parts are kept, as the
    table's error is mostly one-signed.

    ``bands``: ``((lo, hi), dev_b)`` per band of ``t`` (arrays like ``a``; ``lo > hi`` where an
    element's range misses the band), within which ``t_hw`` is within the smaller ``dev_b`` of
    ``t`` (``dev`` the largest, over the whole range): the second term is then the largest over
    the bands, each with its own deviation."""
    fmt = config.fmt("t")
    a, b = (np.clip(np.asarray(v, dtype=np.float64), 0.0, 1.0) for v in ideal)
    lo, hi = np.maximum(a - dev, 0.0), np.minimum(b + dev, 1.0)
    if hardware is not None:
        lo, hi = np.maximum(lo, hardware[0]), np.minimum(hi, hardware[1])
    # the hardware's t is a code: the first and last codes in the range (a hair of slack for
    # float64's rounding of lo and hi)
    scale = 2.0 ** fmt.frac_bits
    first = np.ceil(lo * scale - 1e-6).astype(np.int64)
    last = np.maximum(np.floor(hi * scale + 1e-6).astype(np.int64), first)
    low, top = first / scale, last / scale
    n = np.broadcast_to(np.asarray(n, dtype=np.int64), a.shape)
    e_hi, e_lo, spec_hi = (np.empty(a.shape) for _ in range(3))
    for value in np.unique(n):
        pick = n == value
        up, down, spec = power_error(config, int(value))
        e_hi[pick] = up.max(first[pick], last[pick])
        e_lo[pick] = -down.max(first[pick], last[pick])
        spec_hi[pick] = spec.max(first[pick], last[pick])
    rise, fall = np.zeros(a.shape), np.zeros(a.shape)
    for (band_lo, band_hi), band_dev in (bands or [((a, b), dev)]):
        meet = np.flatnonzero(np.ravel(band_lo <= band_hi))
        u, v, d = (np.clip(np.ravel(np.broadcast_to(x, a.shape))[meet], 0.0, 1.0) if i < 2
                   else np.ravel(np.broadcast_to(x, a.shape))[meet] for i, x in enumerate((band_lo, band_hi, band_dev)))
        m, t_top, t_low = np.ravel(n)[meet], np.ravel(top)[meet], np.ravel(low)[meet]
        x = np.clip(t_top - d, u, v)
        up = np.maximum(np.minimum(x + d, t_top) ** m - x ** m, 0.0) * (1 + 1e-12)
        down = np.maximum(v ** m - np.maximum(v - d, t_low) ** m, 0.0) * (1 + 1e-12)
        rise.flat[meet] = np.maximum(rise.flat[meet], up)
        fall.flat[meet] = np.maximum(fall.flat[meet], down)
    bound = np.maximum(np.abs(e_hi + rise), np.abs(e_lo - fall))
    return bound, spec_hi, b ** n * (1 + 1e-12)
