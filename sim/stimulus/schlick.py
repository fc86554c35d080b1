"""Stimulus for Schlick's unit: extreme ``t`` × extreme ``n``, every ``t`` for a few ``n``, random."""

import numpy as np

from . import EXHAUSTIVE_LIMIT, concat, random_codes, rng

__all__ = ["stimulus", "directed", "sweep_n"]


def sweep_n(config):
    """The ``n`` swept over every ``t`` code: a small one and ``n_max`` (where ``S`` is
    steepest near ``t = 1`` and the divisor largest)."""
    return sorted({min(6, config.n_max), config.n_max})


def directed(config):
    """Every pair of edge ``t`` and edge ``n``.

    ``t``: 0, 1 LSB, 1/2, 1 - LSB (the all-ones fraction code), 1.0.  ``n``: 1, 2, all-ones
    codes ``2^j - 1`` up to ``n_max``, ``n_max - 1``, ``n_max``.  They hold the smallest
    divisor (``D = 1``: ``t = 1`` or ``n = 1``), the largest (``t = 0``, ``n_max``) and the
    largest with a nonzero quotient (``t`` = 1 LSB, ``n_max``).
    """
    one = config.fmt("t").one
    ts = np.array([0, 1, one // 2, one - 1, one])
    ns = {1, 2, config.n_max, max(config.n_max - 1, 1)}
    ns |= {(1 << j) - 1 for j in range(1, config.n_max.bit_length() + 1) if (1 << j) - 1 <= config.n_max}
    ns = np.array(sorted(n for n in ns if n <= config.n_max))
    return {"t": np.tile(ts, len(ns)), "n": np.repeat(ns, len(ts))}


def stimulus(config, count=1000, seed=0, limit=EXHAUSTIVE_LIMIT):
    """Raw ``t``, ``n`` codes: :func:`directed`, every ``t`` in ``0..1`` for each of
    :func:`sweep_n` (evenly strided to ``limit`` codes per ``n``: ``1.15`` has 32769, all
    swept), then ``count`` random: half uniform ``t``, half ``t`` within ``1/n`` of 1, where
    the highlight is."""
    t_fmt, n_fmt = config.fmt("t"), config.fmt("n")
    one = t_fmt.one
    ns = sweep_n(config)
    step = -(-(one + 1) // limit)
    ts = np.arange(0, one + 1, step, dtype=np.int64)
    exhaustive = {"t": np.tile(ts, len(ns)), "n": np.repeat(ns, len(ts))}

    g = rng(seed)
    half = count // 2
    n = random_codes(n_fmt, count, g, 1, config.n_max)
    near = one - (g.uniform(0, 1, count - half) * one / n[half:]).astype(np.int64)
    t = np.concatenate([random_codes(t_fmt, half, g, 0, one), near])
    return concat(directed(config), exhaustive, {"t": t, "n": n})
