"""Stimulus for the LIRP: a = 0 and 1, exact axis vectors, N0 = -N1, 90° spans, random."""

import numpy as np

from . import axis_pairs, codes, concat, random_codes, rng, unit_vectors

__all__ = ["stimulus"]


def stimulus(config, count=1000, seed=0):
    vec, afmt = config.fmt("vec"), config.fmt("a")
    g = rng(seed)
    first, second = axis_pairs()  # includes N0 = -N1 (zero length at a = 1/2)
    n0 = np.tile(first, (3, 1))
    n1 = np.tile(second, (3, 1))
    a = np.repeat([0.0, 1.0, 0.5], len(first))
    directed = {"n0": codes(n0, vec), "n1": codes(n1, vec), "a": codes(a, afmt)}

    # spans of exactly 90°, swept in a over every code
    steps = afmt.one + 1
    span = {"n0": codes(np.tile([1.0, 0, 0], (steps, 1)), vec),
            "n1": codes(np.tile([0, 1.0, 0], (steps, 1)), vec),
            "a": np.arange(steps, dtype=np.int64)}

    # unit vectors within 90° of each other, and raw codes over the whole format
    u0 = unit_vectors(count, g)
    u1 = unit_vectors(count, g)
    u1 = np.where((np.sum(u0 * u1, axis=-1) < 0)[:, None], -u1, u1)
    unit = {"n0": codes(u0, vec), "n1": codes(u1, vec),
            "a": random_codes(afmt, count, g, 0, afmt.one)}
    full = {"n0": random_codes(vec, (count, 3), g), "n1": random_codes(vec, (count, 3), g),
            "a": random_codes(afmt, count, g, 0, afmt.one)}
    return concat(directed, span, unit, full)
