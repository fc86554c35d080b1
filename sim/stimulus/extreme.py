"""Extreme-input rows: one block at one extreme class of its inputs, and what it must do there.

Each block's stimulus module has ``extremes(block_name)``, the tuple of its
:class:`Extreme` rows: exactly ±1.0, zero-length interpolated vectors at 180°, n = 1 and
8000, m = 1 and 63, |D| = 2, R = L, grazing light, V = −L, spans of 1 and 2048 pixels,
ROM address wrap, smallest and largest divisor, all-ones and all-zeros codes — those that
apply to the block.  A row's expected behaviour is the one each golden module's docstring
states (Lyon 1993 Figures 7–8 and 5, Schlick 1994 eq. (3), Szirmay-Kalos et al. 2000
Figure 12, Hast et al. eqs. 16–17), checked from exact constants and closed forms in
Python integers or Fractions, never from the model under test.  This module holds the
record and the checks several blocks' rows share; ``phongfx tables extremes``
(:mod:`phongfx.explore.tables.extremes`) runs the rows.

Deterministic: random directions come from a generator seeded per row.
"""

from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from phongfx.golden.euler import segments

from . import codes, concat, rng

__all__ = ["Extreme", "vectors_at_shininess_ends", "at_shininess_ends", "equal", "round_exact", "wrap", "constant",
           "corner", "exactly", "zero", "equal_to", "all_of", "accumulator_rows"]


@dataclass(frozen=True)
class Extreme:
    """An extreme input class of one block.

    ``build(config)`` gives raw input codes ``{port: int64 array}``; ``holds(config,
    inputs, outputs)`` a bool per vector: the golden output shows ``expected``.
    """

    block: str
    name: str
    expected: str
    build: object
    holds: object


def equal(got, want):
    """Per vector: every lane of ``got`` equals ``want`` (broadcast)."""
    got = np.asarray(got)
    return np.all(np.reshape(got == want, (len(got), -1)), axis=-1)


def round_exact(value, fmt, rounding="round_half_up"):
    """Exact Fraction ``value`` to a raw code of ``fmt``, saturated: floored, or rounded half
    up (the two roundings the blocks' defaults use)."""
    scaled = value * fmt.one
    code = scaled.numerator // scaled.denominator
    if rounding == "round_half_up" and scaled - code >= Fraction(1, 2):
        code += 1
    return min(max(code, fmt.min_raw), fmt.max_raw)


def wrap(code, fmt):
    """A Python int to ``fmt``'s register width, two's complement (the adders wrap)."""
    code &= (1 << fmt.width) - 1
    return code - (1 << fmt.width) if fmt.signed and code >> (fmt.width - 1) else code


def constant(code, lanes=3, count=1):
    """``count`` vectors of ``lanes`` lanes (a scalar port when ``lanes`` is 1), all ``code``."""
    return np.full((count, lanes) if lanes > 1 else count, code, dtype=np.int64)


def corner(config, name="vec", high=True):
    """One vector with every lane at the top (or bottom) code of format field ``name``."""
    fmt = config.fmt(name)
    return constant(fmt.max_raw if high else fmt.min_raw)


def exactly(name, value):
    """Check: every vector's ``name`` output is exactly ``value`` (a float its format holds)."""
    def holds(c, i, o):
        fmt = c.outputs[name][0]
        return equal(o[name], fmt.exact_raw(value))
    return holds


def zero(name):
    """Check: every vector's ``name`` output is exactly 0."""
    return exactly(name, 0.0)


def equal_to(port, name):
    """Check: output ``name`` equals input ``port``, code for code."""
    return lambda c, i, o: equal(o[name], i[port])


def all_of(*checks):
    """Check: every one of ``checks`` holds."""
    def holds(c, i, o):
        return np.all([check(c, i, o) for check in checks], axis=0)
    return holds


def vectors_at_shininess_ends(config, vectors, port, top):
    """Raw inputs: each row of the ``vectors`` (port name -> floats, (count, 3), coded in
    ``config.vec``) at shininess ``port`` = 1 and at ``top`` (the block's largest)."""
    ends = sorted({1, top})
    rows = {name: np.tile(codes(v, config.vec), (len(ends), 1)) for name, v in vectors.items()}
    rows[port] = np.repeat(np.asarray(ends, dtype=np.int64), len(next(iter(vectors.values()))))
    return rows


def at_shininess_ends(config, r, l, port, top):
    """:func:`vectors_at_shininess_ends` of the direction pairs ``r``, ``l``."""
    return vectors_at_shininess_ends(config, {"r": r, "l": l}, port, top)


def _closed_form(c, i, o, steps):
    """Hast et al. eq. (14) in Python integers: ``p_k = p0 + k·t0 + k(k−1)/2·ds`` (Gouraud:
    ``p0 + k·dp``) on ``p``'s grid, wrapped like the register; ``level = floor(2^F·p)``
    clamped to ``out``."""
    p, out = c.fmt("p"), c.fmt("out")
    last, k = segments(i["init"])
    want = []
    for j, kk in zip(last, k):
        value = int(i["p0"][j])
        for order, (port, fmt) in enumerate(steps, start=1):
            coeff = kk if order == 1 else kk * (kk - 1) // 2
            value += coeff * (int(i[port][j]) << (p.frac_bits - c.fmt(fmt).frac_bits))
        want.append(wrap(value, p))
    want = np.array(want)
    level = np.clip(want >> (p.frac_bits - out.frac_bits), out.min_raw, out.max_raw)
    return equal(o["p"], want) & equal(o["level"], level)


def accumulator_rows(block, span, geometric, steps):
    """The rows of a scanline unit accumulating ``p`` from ``init`` (Hast et al.'s corrected
    Euler unit, and Gouraud's, its first-order case): ``span`` and ``geometric`` are the
    block's stimulus functions, ``steps`` its step loads ``{port: register format field}``
    in order (``t0`` then ``ds``; ``dp``), checked against the closed form."""
    steps = tuple(steps.items())

    def form(c, i, o):
        return _closed_form(c, i, o, steps)

    def ends(c):
        p = c.fmt("p")
        return concat(*(span(c, 1, rng(j), p0=code) for j, code in enumerate(
            (p.min_raw, p.max_raw, 0, -1, min(p.one, p.max_raw)))))

    return (
        Extreme(block, "span of 1 pixel, p0 at the ends and 1.0",
                "p = p0; level = floor(256·p0) in 0..255", ends, form),
        Extreme(block, "span of 2048 pixels (geometric setup)",
                "closed form p0 + k·t0 + k(k−1)/2·ds, wrapped",
                lambda c: geometric(c, 2048, rng(3)), form),
        Extreme(block, "all-ones codes (registers wrap)", "closed form, wrapped modulo 2^width",
                lambda c: span(c, 8, rng(4), p0=c.fmt("p").max_raw,
                               **{port: c.fmt(fmt).max_raw for port, fmt in steps}), form),
        Extreme(block, "all-zeros codes", "p = 0, level = 0",
                lambda c: span(c, 8, rng(5), p0=0, **{port: 0 for port, _ in steps}),
                all_of(zero("p"), zero("level"))),
    )
