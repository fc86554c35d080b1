"""Stimulus for the LIRP: a = 0 and 1, exact axis vectors, N0 = -N1, 90° spans, random."""

import numpy as np

from . import AXES, axis_pairs, codes, concat, random_codes, rng, unit_vectors
from .extreme import Extreme, constant, equal, equal_to, zero

__all__ = ["stimulus", "extremes"]


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


def _axes(c):
    n1, n0 = axis_pairs()  # N0 runs through the six axes for each N1
    return {"n0": codes(np.tile(n0, (2, 1)), c.vec), "n1": codes(np.tile(n1, (2, 1)), c.vec),
            "a": codes(np.repeat([0.0, 1.0], len(n0)), c.a)}


def _ends(c, i, o):
    # a = 0 gives N0, a = 1 gives N1, exactly (out = vec by default)
    a0 = i["a"] == 0
    return equal(o["n"], np.where(a0[:, None], i["n0"], i["n1"]))


def _end_codes(c):
    vec, afmt = c.fmt("vec"), c.fmt("a")
    ends = np.array([vec.max_raw, vec.min_raw, 0, -1])
    a = np.array([0, 1, afmt.one // 2, afmt.one])
    n = np.repeat(ends, len(a))[:, None] * np.ones(3, dtype=np.int64)
    return {"n0": n, "n1": n, "a": np.tile(a, len(ends))}


def extremes(block_name):
    """The LIRP's extreme rows (Lyon 1993 Figure 7a): the span ends, N0 = −N1 at a = 1/2,
    the end codes of ``vec``."""
    return (
        Extreme(block_name, "exactly ±1.0 (a = 0 and 1, ±axes)", "N = N0 at a = 0, N1 at a = 1, exactly",
                _axes, _ends),
        Extreme(block_name, "zero-length at 180° (N0 = −N1, a = 1/2)", "N = 0 exactly",
                lambda c: {"n0": codes(AXES, c.vec), "n1": codes(-AXES, c.vec),
                           "a": constant(c.fmt("a").one // 2, 1, 6)}, zero("n")),
        Extreme(block_name, "all-ones and all-zeros codes (N0 = N1)",
                "N = N0 exactly for every a (no overflow)", _end_codes, equal_to("n0", "n")),
    )
