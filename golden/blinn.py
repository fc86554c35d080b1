"""Golden model of the Blinn–Phong baseline: exact normalization and true ``t^n``.

Lyon (1993, "Background") says designs that compute ``(N·H)^n`` directly need
"typically 16 bits of precision" in the normalization and an exponentiation that is "an
accurate operation on a 16-bit input".  This is that design, built so every cheaper
unit can be measured against it.  Bit growth at the defaults of
:class:`~phongfx.config.BlinnConfig` (``F = 15`` fraction bits of ``vec``):

* **dot products** ``N·N``, ``N·L``, ``N·H``: ``S1.15 × S1.15`` exact in ``S3.30``, sums
  in ``S5.30``; ``q = N·N >= 0`` is held exactly in ``4.30`` (``q <= 3·2^2``, 34 bits);
* **even shift**: ``j`` = the number of leading all-zero bit pairs of ``q``'s 34-bit code
  (at most 16), ``M = Q << 2j`` so ``m = M/2^34`` lies in ``[1/4, 1)`` and
  ``q = m·4^(2 - j)``.  ``m`` is rounded to ``0.18`` (saturated: rounding up to 1 keeps
  ``1 - 2^-18``), relative error ``<= 2^-17``;
* **seed** ``y0 = T[a]``, ``a`` = the top 9 bits of ``m`` (``a >= 128``: ``m >= 1/4``);
  ``T[a] = 2/(sqrt(m0) + sqrt(m1))`` over the cell ``[m0, m1)``, which balances the relative
  error ``|y0·sqrt(m) - 1| <= 2^-A`` (``A`` address bits; worst at ``m = 1/4``), rounded
  to ``y = 1.17`` (``y0 < 2``).  Cells ``a < 2^(A-2)`` are read only for ``q = 0`` and hold 0;
* **Newton–Raphson**: ``y0²`` exact in ``2.34``, rounded to ``nr = 2.20``; ``p = m·y0²``
  exact in ``2.38``, rounded to ``2.20``; ``(3 - p)/2`` exact in ``S1.21``; ``y1 = y0·(3 -
  p)/2`` exact in ``S2.38``, rounded to ``1.17`` and saturated.  With ``y0 = (1 + e)/sqrt(m)``,
  ``y1·sqrt(m) = 1 - 3e²/2 - e³/2``: ``|e| <= 2^-9`` leaves ``<= 2^-17.4``, plus the
  roundings (``2^-21`` in ``p``, ``2^-18`` in ``y1``);
* **cosines**: ``d·2^(j-2)`` (``d`` a dot product: its code shifted left by ``j``, point
  moved by 2, exact in ``S19.32``; ``|d·2^(j-2)| <= sqrt(m)·|L| < 1.001``) rounded to ``dot = S1.17``
  (saturated), times ``y1`` exact in ``S2.34``, rounded to ``1.15`` with saturation (a
  negative dot product gives 0: Lyon's backside test) and clamped to 1.0.  ``q = 0``
  gives ``d = 0``, so both cosines are 0;
* **log2**: ``t = mu·2^-s``, ``s`` = leading zeros of ``t``'s 16-bit code (``mu`` in
  ``[1, 2)``); ``a`` = top 8 bits of ``mu``'s 15-bit fraction, ``phi`` the low 7;
  ``log2 mu ~ LT[a] + LD[a]·phi`` (the chord between table nodes rounded to ``0.20``;
  the step ``LD`` is stored as ``2^8·LD`` in ``1.12``, ``LD·phi`` is exact in ``0.27``
  (a ``13 × 7`` multiplier), rounded to ``0.20``), ``lam = LT + LD·phi - s``
  exact in ``S4.20``.  Error ``<= 2^-2A/(8 ln 2) + 2^-20`` (chord sag plus two half-LSB
  roundings); ``t = 1`` gives ``lam = 0`` exactly;
* **exponent** ``x = n·lam`` exact in ``S17.20`` (``13.0 × S4.20``, no rounding);
  ``x = floor(x) + f``; ``2^f ~ ET[b] + ED[b]·psi`` (``b`` = top 8 bits of ``f``, nodes
  ``2^(b/256)`` rounded to ``1.18``; ``2^8·ED`` in ``1.10``, ``ED·psi`` exact in ``0.30``
  (``11 × 12``) rounded to ``1.18``, sum
  exact in ``2.18``; error ``<= (ln 2)²·2^-2A/4 + 2^-18``);
* **shift and round**: ``2^f·2^floor(x)`` is exact in ``2.(18+17)`` for shifts up to
  ``F_out + 2 = 17`` (:attr:`~phongfx.config.BlinnConfig.flush`); it is rounded to
  ``out = 1.15`` (``<= 1``: a shift of 0 means ``x = 0``, so ``2^f = 1``).  A larger shift
  leaves less than ``2^-17``, which every rounding takes to 0, so the flush is the rounding
  itself.  ``t = 0`` gives 0 (``log2 0`` is not formed).

``t^n`` is formed by log/exp for every ``n``; repeated squaring would serve only powers
of two.  Measured against float Phong on the same input codes (the tests: 20000 seeded
pixels per ``n``, ``H`` within ``4/sqrt(n)`` of ``N``, ``|N|`` in 0.5..1), max (mean)
error in 8-bit levels: n = 1: 0.007 (0.001); 8: 0.051 (0.006); 64: 0.40 (0.043); 500: 3.1
(0.32); 8000: 46 (4.6).  The log/exp part alone is at most 0.32 levels at n = 8000; the
rest is the 16-bit cosine magnified ``n`` times, Lyon's point: ``n = 1000`` needs over 14
bits, ``n = 8000`` more than 16.
"""

import numpy as np

from phongfx.core.format import Format

from .fixed import Fixed, check_range

__all__ = ["blinn", "rsqrt_table", "log2_tables", "exp2_tables", "even_shift", "shifted", "scaled",
           "reciprocal_sqrt", "inverse_length", "inverse_root", "unclamped_cosine", "cosine", "clamp_one",
           "log2_t", "pow2", "power"]


def rsqrt_table(config):
    """Raw ``y`` words of the ``1/sqrt(m)`` seed table, ``2^rsqrt_addr`` of them (the
    golden model reads it, the HDL fills its ``Memory`` with it)."""
    bits = config.rsqrt_addr
    a = np.arange(1 << bits)
    low = np.maximum(a, 1 << (bits - 2)) / (1 << bits)
    seed = 2 / (np.sqrt(low) + np.sqrt((a + 1) / (1 << bits)))
    raw = Fixed.from_float(seed, config.y, "round_half_up", "saturate").raw
    return np.where(a >= 1 << (bits - 2), raw, 0)


def _chord_tables(function, bits, fmt, int_bits):
    """Nodes ``function(a/2^bits)`` rounded to ``fmt``'s fraction bits, the differences of
    neighbouring nodes (so interpolation is continuous across cells), and the format of
    the differences times ``2^bits``: the same raw codes with the point moved, so the slope
    ROM and its multiplier carry only the bits a step can set."""
    nodes = Fixed.from_float(function(np.arange((1 << bits) + 1) / (1 << bits)),
                             Format(int_bits, fmt.frac_bits), "round_half_up", "error").raw
    steps = np.diff(nodes)
    return nodes[:-1], steps, Format.covering(0, int(steps.max()), fmt.frac_bits - bits)


def log2_tables(config):
    """Raw ``(LT, LD, LD format)``: ``log2(1 + a/2^A)`` in ``log`` and ``2^A`` times the step
    to the next node (``<= 1/ln 2``: ``1.12`` at the defaults)."""
    return _chord_tables(lambda u: np.log2(1 + u), config.log_addr, config.fmt("log"), 1)


def exp2_tables(config):
    """Raw ``(ET, ED, ED format)``: ``2^(b/2^A)`` in ``exp`` and ``2^A`` times the step to the
    next node (``<= 2 ln 2``: ``1.10`` at the defaults)."""
    fmt = config.fmt("exp")
    return _chord_tables(np.exp2, config.exp_addr, fmt, fmt.int_bits + 1)


def even_shift(config, q):
    """``(j, m)``: ``j`` leading all-zero bit pairs of ``q``'s code, ``m = Q·4^j/2^width``
    rounded to ``config.m`` (``q = m·4^(h - j)``; ``q = 0`` gives the largest ``j``, ``m = 0``)."""
    pairs = q.fmt.width // 2
    j = np.full(q.raw.shape, pairs - 1, dtype=np.int64)
    for i in range(pairs):  # a priority encoder: the highest nonzero pair wins
        j = np.where((q.raw >> (2 * i)) & 3, pairs - 1 - i, j)
    m = Fixed(q.raw << (2 * j), Format(0, q.fmt.width))
    return j, m.quantize(config.m, config.rounding, "saturate", op="blinn m")


def reciprocal_sqrt(config, m):
    """``y1 ~ 1/sqrt(m)``: table seed and one Newton–Raphson step, in ``config.y``."""
    cfg = config
    a = m.raw >> (m.fmt.frac_bits - cfg.rsqrt_addr)
    y0 = Fixed(rsqrt_table(cfg)[a], cfg.y)
    square = (y0 * y0).quantize(cfg.nr, cfg.rounding, "saturate", op="blinn y0²")
    p = (m * square).quantize(cfg.nr, cfg.rounding, "saturate", op="blinn m·y0²")
    r = (Fixed.const(3, "2.0") - p).shift(-1)
    return (y0 * r).quantize(cfg.y, cfg.rounding, "saturate", op="blinn y1")


def inverse_length(config, vector, op):
    """``(j, y1)`` of ``vector`` (count, 3): :func:`inverse_root` of its exact ``X·X``, so
    ``1/|X| ~ 2^(j-h)·y1``: the normalization of ``N`` before Blinn's (1977) ``N·H``, and of
    ``N`` and a local ``L`` or ``V`` before Phong's (1975) ``R·V``
    (:mod:`phongfx.golden.conventional`)."""
    return inverse_root(config, vector.dot(vector), op)


def inverse_root(config, square, op):
    """``(j, y1)`` of an exact squared length ``square``: :func:`even_shift` and
    :func:`reciprocal_sqrt` of it rounded to ``q = config.q`` (``op`` names that quantize)."""
    q = square.quantize(config.q, "truncate", "error", op=op)
    j, m = even_shift(config, q)
    return j, reciprocal_sqrt(config, m)


def clamp_one(value):
    """``min(value, 1)`` in ``value``'s format: a rounded cosine (Blinn's 1977 ``N·H``, Phong's
    1975 ``R·V``) may round up past 1, which ``t^n`` must not see."""
    return value.where(value < 1, Fixed.const(1, value.fmt))


def shifted(config, d, j):
    """``d·2^(j-h)``, exact: the dot product ``d`` shifted by :func:`even_shift`'s ``j``."""
    cfg = config
    shift = cfg.q.width // 2 - 1
    wide = Format.covering(d.fmt.min_raw << shift, d.fmt.max_raw << shift,
                           d.fmt.frac_bits + cfg.q.int_bits // 2)
    return Fixed(d.raw << j, wide)


def scaled(config, d, j):
    """:func:`shifted` rounded to ``config.dot``."""
    return shifted(config, d, j).quantize(config.dot, config.rounding, "saturate", op="blinn d'")


def unclamped_cosine(config, d, j, y1, fmt):
    """:func:`cosine` before its clamp to 1: :func:`scaled` times ``y1``, rounded to ``fmt``."""
    return (scaled(config, d, j) * y1).quantize(fmt, config.rounding, "saturate", op="blinn cosine")


def cosine(config, d, j, y1, fmt):
    """``max(d, 0)/sqrt(q)`` clamped to 1 in an unsigned ``fmt`` (``d/sqrt(q)`` clamped to 1 in
    a signed one: the conventional unit's cosines and unit vectors): :func:`unclamped_cosine`
    clamped to 1."""
    return clamp_one(unclamped_cosine(config, d, j, y1, fmt))


def log2_t(config, t):
    """``log2 t`` (``t`` in ``config.t``, nonzero) in the exact format ``S?.F_log``: leading
    zeros, then table and interpolation on the mantissa; ``t = 1`` gives exactly 0."""
    frac = t.fmt.frac_bits
    s = np.full(t.raw.shape, frac, dtype=np.int64)
    for i in range(frac + 1):  # leading zeros of t's code, up to its 2^0 bit
        s = np.where((t.raw >> i) & 1, frac - i, s)
    mantissa = (t.raw << s) & ((1 << frac) - 1)
    lam = _interpolate(log2_tables(config), mantissa, frac, config.log_addr, config.fmt("log"),
                       config.rounding)
    return lam - Fixed(s, Format.covering(0, frac, 0))


def pow2(config, x):
    """``2^x`` for ``x <= 0`` (any format with ``log``'s fraction bits), rounded to
    ``config.out``: exp table and interpolation on the fraction, shift by the integer part,
    0 past :attr:`~phongfx.config.BlinnConfig.flush`."""
    cfg = config
    xf = x.fmt.frac_bits
    floor, f = x.raw >> xf, x.raw & ((1 << xf) - 1)
    e = _interpolate(exp2_tables(cfg), f, xf, cfg.exp_addr, cfg.fmt("exp"), cfg.rounding)
    shift = np.clip(-floor, 0, cfg.flush)
    scaled = Fixed(e.raw << (cfg.flush - shift), Format(e.fmt.int_bits, e.fmt.frac_bits + cfg.flush))
    spec = scaled.quantize(cfg.out, cfg.rounding, "error", op="blinn 2^x")
    return spec.where(-floor <= cfg.flush, Fixed.const(0, cfg.out))


def power(config, t, n):
    """``t^n = 2^(n·log2 t)`` rounded to ``config.out``; 0 for ``t = 0``."""
    spec = pow2(config, n * log2_t(config, t))
    return spec.where(t.raw != 0, Fixed.const(0, config.out))


def _interpolate(tables, code, bits, addr_bits, fmt, rounding):
    """``V[a] + D[a]·phi`` for a ``bits``-bit fraction ``code``: top ``addr_bits`` address
    the tables, the rest is ``phi`` in ``0..1``."""
    low = bits - addr_bits
    a, phi = code >> low, code & ((1 << low) - 1)
    step = (Fixed(tables[1][a], tables[2]) * Fixed(phi, Format(0, low))).shift(-addr_bits).quantize(
        fmt, rounding, "error", op="blinn interpolation")
    return Fixed(tables[0][a], fmt) + step


def blinn(config, normal, light, half, n):
    """Diffuse ``max(N·L, 0)/|N|`` and specular ``(max(N·H, 0)/|N|)^n``.

    Parameters
    ----------
    config : BlinnConfig
    normal, light, half : Fixed, shape (count, 3), format ``config.vec``
        Un-normalized ``N``; unit ``L`` and ``H`` (any codes give defined outputs).
    n : Fixed, shape (count,), format ``config.n``, integers 1..``config.n_max``

    Returns
    -------
    dict
        ``{"diffuse": Fixed (count,), "specular": Fixed (count,)}`` in ``config.out``
    """
    check_range("n", n, 1, config.n_max)
    j, y1 = inverse_length(config, normal, "blinn q")
    diffuse = cosine(config, normal.dot(light), j, y1, config.out)
    t = cosine(config, normal.dot(half), j, y1, config.t)
    return {"diffuse": diffuse, "specular": power(config, t, n)}
