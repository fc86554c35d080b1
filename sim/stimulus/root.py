"""Stimulus for the root-shininess unit: R = ±L, extreme m, both comparators' edges, random.

With ``m_const`` set, every case takes that m (the comparators' edges are those of the one
m the hardware has) and no ``m`` port is returned.
"""

import numpy as np

from . import (AXES, at_angle, axis_pairs, codes, concat, perpendicular_pairs, random_codes, random_pairs, rng,
               unit_vectors)
from .extreme import Extreme, at_shininess_ends, constant, corner, exactly, zero

__all__ = ["stimulus", "fraction_codes", "pairs", "extremes"]


def fraction_codes(config, m, d):
    """What Figure 8's comparators see for raw ``D`` codes ``d`` (count, 3) of format ``d``:
    ``big`` (an integer part of ``u_i = m|D_i|/2^s`` is set) and ``c·Σq_i²`` in units of
    ``2^-2f``, ``q_i`` the truncated fraction codes; the shape zeroes from ``2^(2f)`` on."""
    dfmt, f, s = config.fmt("d"), config.fmt("frac").frac_bits, config.shift
    md = np.asarray(m)[:, None] * np.minimum(np.abs(d), dfmt.max_raw)
    point = dfmt.frac_bits + s  # fraction bits of u
    big = np.any(md >= 1 << point, axis=-1)
    q = ((md >> max(point - f, 0)) << max(f - point, 0)) & ((1 << f) - 1)
    return big, np.sum(q * q, axis=-1) << (2 * s - 1 - config.k)


def pairs(config, d):
    """Raw ``R``, ``L`` codes of ``vec`` with ``R - L = D`` (``d`` raw codes of ``d``),
    exactly when the two formats have the same fraction bits."""
    vec, dfmt = config.fmt("vec"), config.fmt("d")
    shift = vec.frac_bits - dfmt.frac_bits
    d = d << shift if shift >= 0 else (d + (1 << (-shift - 1))) >> -shift
    r = np.clip(-(-d // 2), vec.min_raw, vec.max_raw)
    return r, np.clip(r - d, vec.min_raw, vec.max_raw)


def _directed(config, ms, d):
    r, l = pairs(config, np.asarray(d, dtype=np.int64))
    return {"r": r, "l": l, "m": np.asarray(ms, dtype=np.int64)}


def stimulus(config, count=1000, seed=0):
    vec, mfmt, dfmt = config.fmt("vec"), config.fmt("m"), config.fmt("d")
    g = rng(seed)
    lo, hi = config.shininess_range  # 1..m_max, or the constant
    ms = sorted({lo, min(lo + 1, hi), (lo + hi) // 2, hi})

    # every pair of ± AXES (R = L: x = 0; R = -L: |D| = 2, rectified -2 saturating;
    # 90°, a grazing light), and off-axis R = L and R = -L, at m = 1, m_max and between
    first, second = axis_pairs()
    u = unit_vectors(8, g)
    r = np.tile(np.concatenate([first, u, u]), (len(ms), 1))
    l = np.tile(np.concatenate([second, u, -u]), (len(ms), 1))
    m = np.repeat(ms, len(first) + 2 * len(u))
    axis = {"r": codes(r, vec), "l": codes(l, vec), "m": m}

    # augmented comparator, every m: along ±X, the largest |D| with u < 1 and the
    # smallest with u >= 1 (its fraction near 0: without the flag, a peak of ~1.0)
    every = np.arange(lo, hi + 1)
    edge = -(-(1 << (dfmt.frac_bits + config.shift)) // every)
    mags = np.stack([edge - 1, edge], axis=-1).ravel()
    keep = mags <= dfmt.max_raw
    mags, m = mags[keep], np.repeat(every, 2)[keep]
    d = np.zeros((2 * len(mags), 3), dtype=np.int64)
    d[:, 0] = np.concatenate([mags, -mags])
    big = _directed(config, np.tile(m, 2), d)

    # sum reaches 1: along random directions (axes too), scale |D| code by code and keep
    # the last code below and the first at or past the shape's threshold (or the flag)
    rows, mrows = [], []
    steps = np.arange(1 << (dfmt.int_bits + dfmt.frac_bits + 1))
    for mi in sorted({lo, 3, 7, 16, 40, hi} & set(every.tolist())):
        for w in np.concatenate([AXES[:3], unit_vectors(6, g)]):
            d = np.clip(np.rint(steps[:, None] * w), dfmt.min_raw, dfmt.max_raw).astype(np.int64)
            big_, v = fraction_codes(config, np.full(len(d), mi), d)
            past = np.flatnonzero(big_ | (v >= 1 << 2 * config.fmt("frac").frac_bits))
            if len(past) and past[0]:
                rows += [d[past[0] - 1], d[past[0]]]
                mrows += [mi, mi]
    threshold = _directed(config, mrows, np.array(rows).reshape(-1, 3))

    # grazing approach to the peak: x = (m²/2)·α² over 0 .. 2^(k+1), denser near 0
    n = 4 * count // 10 + 1
    m_near = random_codes(mfmt, n, g, lo, hi)
    alpha = np.sqrt(2 * 2.0 ** (config.k + 1) * g.uniform(0, 1, n) ** 2) / m_near
    r_near, l_near = at_angle(alpha, g)
    near = {"r": codes(r_near, vec), "l": codes(l_near, vec), "m": m_near}

    raw = concat(axis, big, threshold, near, *random_pairs(config, count, g))
    return {name: raw[name] for name in config.inputs}


def _rows(c, r, l):
    return at_shininess_ends(c, r, l, "m", c.m_max)


def _d2(c, i, o):
    # |D_i| = 2 is rectified and saturated to 2 − 2⁻¹⁰, so x/2^k falls just short of 1:
    # at m = 1 the ideal f_1 = 0 comes out as at most 1 LSB; larger m pass the comparator
    spec = o["spec"]
    return np.where(i["m"] == 1, (spec >= 0) & (spec <= 1), spec == 0)


def extremes(block_name):
    """The root-shininess unit's extreme rows (Lyon 1993 Figure 8): R = L, |D| = 2 at m = 1
    and ``m_max``, R ⟂ L at m = 1, and the end codes of ``vec``."""
    graze_r, graze_l = perpendicular_pairs()
    u = np.concatenate([AXES, unit_vectors(8, rng(1))])
    return (
        Extreme(block_name, "R = L, m = 1 and m_max", "spec = 1.0 exactly",
                lambda c: _rows(c, u, u), exactly("spec", 1.0)),
        Extreme(block_name, "|D| = 2 (R = −L), m = 1 and m_max",
                "m_max: 0; m = 1: ≤ 2⁻¹⁵ (ideal 0: |D| saturates to 2 − 2⁻¹⁰, x/2 = 1 − 2⁻¹⁰)",
                lambda c: _rows(c, AXES, -AXES), _d2),
        Extreme(block_name, "grazing (R ⟂ L), m = 1", "f_1(1) = (1 − 1/2)² = 1/4 exactly",
                lambda c: {"r": codes(graze_r, c.vec), "l": codes(graze_l, c.vec),
                           "m": np.ones(len(graze_r), dtype=np.int64)}, exactly("spec", 0.25)),
        Extreme(block_name, "all-ones codes (R = max, L = min), m_max", "0",
                lambda c: {"r": corner(c), "l": corner(c, high=False), "m": constant(c.m_max, 1)},
                zero("spec")),
    )
