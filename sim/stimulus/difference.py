"""Stimulus for difference/x: R = L, R = -L, exact AXES, extreme n, near the peak, random.

With ``n_const`` set, every case takes that n (the extremes are the vector ones at the
one n the hardware has) and no ``n`` port is returned.
"""

import numpy as np

from . import AXES, at_angle, axis_pairs, codes, concat, random_codes, rng, unit_vectors

__all__ = ["stimulus"]


def stimulus(config, count=1000, seed=0):
    vec, nfmt = config.fmt("vec"), config.fmt("n")
    g = rng(seed)
    # the n range the hardware takes: 1..n_max, or the constant
    lo, hi = (config.n_const, config.n_const) if config.n_const else (1, config.n_max)
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

    # seeded random unit pairs, and raw codes over the whole vec format (|D| up to 4)
    unit = {"r": codes(unit_vectors(count, g), vec), "l": codes(unit_vectors(count, g), vec),
            "n": random_codes(nfmt, count, g, lo, hi)}
    full = {"r": random_codes(vec, (count, 3), g), "l": random_codes(vec, (count, 3), g),
            "n": random_codes(nfmt, count, g, lo, hi)}
    raw = concat(directed, lsb, near, unit, full)
    return {name: raw[name] for name in config.inputs}
