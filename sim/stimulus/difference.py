"""Stimulus for difference/x: R = L, R = -L, exact AXES, extreme n, near the peak, random.

With ``n_const`` set, every case takes that n (the extremes are the vector ones at the
one n the hardware has) and no ``n`` port is returned.
"""

from fractions import Fraction

import numpy as np

from . import (AXES, at_angle, axis_pairs, codes, concat, perpendicular_pairs, random_codes, random_pairs, rng,
               unit_vectors)
from .extreme import Extreme, at_shininess_ends, constant, corner, equal, round_exact, zero

__all__ = ["stimulus", "extremes"]


def stimulus(config, count=1000, seed=0):
    vec, nfmt = config.fmt("vec"), config.fmt("n")
    g = rng(seed)
    lo, hi = config.shininess_range  # 1..n_max, or the constant
    ns = sorted({lo, min(8000, hi), hi})

    # every pair of ± AXES: R = L (x = 0), R = -L (|D| = 2, +2 saturating), 90° apart
    first, second = axis_pairs()
    r, l = np.tile(first, (len(ns), 1)), np.tile(second, (len(ns), 1))
    n = np.repeat(ns, len(AXES) ** 2)
    u = unit_vectors(8, g)  # off-axis R = L and R = -L as well
    r = np.concatenate([r, np.tile(u, (2 * len(ns), 1))])
    l = np.concatenate([l, np.tile(np.concatenate([u, -u]), (len(ns), 1))])
    n = np.concatenate([n, np.repeat(ns, 2 * len(u))])
    directed = {"r": codes(r, vec), "l": codes(l, vec), "n": np.asarray(n)}

    # a few LSB apart at the largest n: D·D of a few 2^-20 must survive into 2x
    steps = np.arange(-3, 4)
    lsb = {"r": np.repeat(codes(u, vec), len(steps), axis=0),
           "n": np.full(len(u) * len(steps), hi)}
    lsb["l"] = np.clip(lsb["r"] + np.tile(steps, len(u))[:, None] * [1, -1, 0], vec.min_raw, vec.max_raw)

    # grazing approach to the peak: angles putting x on 0 .. 32 (past 2^k for every k),
    # denser near 0, so the fraction bits of 2x that the shape function uses are hit
    m = 4 * count // 10 + 1
    n_near = random_codes(nfmt, m, g, lo, hi)
    alpha = np.sqrt(2 * 32 * g.uniform(0, 1, m) ** 2 / n_near)
    r_near, l_near = at_angle(alpha, g)
    near = {"r": codes(r_near, vec), "l": codes(l_near, vec), "n": n_near}

    raw = concat(directed, lsb, near, *random_pairs(config, count, g))
    return {name: raw[name] for name in config.inputs}


def _rows(c, r, l):
    return at_shininess_ends(c, r, l, "n", c.n_max)


def _x2_exact(c, i, o):
    """2x = n·D·D (Figure 7c) with each lane of D = R − L saturated to ``d`` (so +2 becomes
    2 − 2⁻¹⁰ in S1.10, −2 stays), the rest exact, then rounded and saturated to ``x2``."""
    vec, d, x2 = c.fmt("vec"), c.fmt("d"), c.fmt("x2")
    want = []
    for r, l, n in zip(i["r"], i["l"], i["n"]):
        lanes = [round_exact(Fraction(int(a) - int(b), vec.one), d) for a, b in zip(r, l)]
        want.append(round_exact(int(n) * sum(Fraction(x, d.one) ** 2 for x in lanes), x2, c.rounding))
    return equal(o["x2"], np.array(want))


def extremes(block_name):
    """The difference unit's extreme rows (Lyon 1993 Figure 7c): R = L, |D| = 2, R ⟂ L at
    n = 1 and ``n_max``, and the end codes of ``vec``."""
    graze_r, graze_l = perpendicular_pairs()
    u = np.concatenate([AXES, unit_vectors(8, rng(1))])
    return (
        Extreme(block_name, "R = L (±axes and random), n = 1 and n_max", "2x = 0",
                lambda c: _rows(c, u, u), zero("x2")),
        Extreme(block_name, "|D| = 2 (R = −L), n = 1 and n_max",
                "2x = n·|D|², D = +2 saturated to 2 − 2⁻¹⁰ (−2 exact); sum saturated to 8192 − 2⁻¹²",
                lambda c: _rows(c, AXES, -AXES), _x2_exact),
        Extreme(block_name, "grazing (R ⟂ L, |D|² = 2), n = 1 and n_max",
                "2x = 2n exactly, saturated to 8192 − 2⁻¹²", lambda c: _rows(c, graze_r, graze_l), _x2_exact),
        Extreme(block_name, "all-ones codes (R = max, L = min), n_max", "saturates to 8192 − 2⁻¹²",
                lambda c: {"r": corner(c), "l": corner(c, high=False), "n": constant(c.n_max, 1)},
                lambda c, i, o: equal(o["x2"], c.fmt("x2").max_raw)),
    )
