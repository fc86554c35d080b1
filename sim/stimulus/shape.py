"""Stimulus for the shape function: every code where ``f_k`` can be nonzero, then edges, random."""

import numpy as np

from . import EXHAUSTIVE_LIMIT, concat, random_codes, rng
from .extreme import Extreme, exactly, zero

__all__ = ["stimulus", "threshold", "nonzero_codes", "extremes"]


def threshold(config):
    """Raw ``x2`` code of ``2x = 2^(k+1)``, i.e. ``x/2^k = 1``: the output is 0 from here on."""
    return 1 << (config.k + 1 + config.fmt("x2").frac_bits)


def nonzero_codes(config, limit=EXHAUSTIVE_LIMIT):
    """Every ``x2`` code below :func:`threshold`, evenly strided if there are more than
    ``limit`` (k = 4 with ``13.12``: every other code)."""
    top = threshold(config)
    return np.arange(0, top, -(-top // limit), dtype=np.int64)


def stimulus(config, count=1000, seed=0, limit=EXHAUSTIVE_LIMIT):
    """Raw ``x2`` codes: :func:`nonzero_codes`, the 33 codes around the threshold, powers
    of two and all-ones below each, the largest code and zero, then ``count`` random."""
    x2 = config.fmt("x2")
    top = threshold(config)
    edges = np.arange(top - 16, top + 17)
    powers = 1 << np.arange(x2.width)
    directed = np.concatenate([edges, powers, powers - 1, [x2.max_raw, 0]])
    directed = directed[(directed >= 0) & (directed <= x2.max_raw)]
    full = random_codes(x2, count, rng(seed))
    return concat({"x2": nonzero_codes(config, limit)}, {"x2": directed}, {"x2": full})


def extremes(block_name):
    """The shape function's extreme rows (Lyon 1993 Figure 7d): x = 0, and x/2^k from 1 on."""
    return (
        Extreme(block_name, "all-zeros code (x = 0)", "f_k(0) = 1.0 exactly",
                lambda c: {"x2": np.zeros(1, dtype=np.int64)}, exactly("spec", 1.0)),
        Extreme(block_name, "x/2^k = 1 and past it, all-ones code", "0",
                lambda c: {"x2": np.concatenate([np.arange(16) + (1 << (c.k + 1 + c.fmt("x2").frac_bits)),
                                                 [c.fmt("x2").max_raw]])}, zero("spec")),
    )
