"""Stimulus for Schlick's unit: extreme ``t`` × extreme ``n``, every ``t`` for a few ``n``, random."""

from fractions import Fraction

import numpy as np

from . import EXHAUSTIVE_LIMIT, concat, random_codes, rng
from .extreme import Extreme, equal, exactly, round_exact, zero

__all__ = ["stimulus", "directed", "sweep_n", "extremes"]


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


def _grid(ts, ns):
    """Every raw ``t`` of ``ts`` with every ``n`` of ``ns``."""
    ts, ns = np.asarray(ts, dtype=np.int64), np.asarray(ns, dtype=np.int64)
    return {"t": np.tile(ts, len(ns)), "n": np.repeat(ns, len(ts))}


def _floor(c, i, o):
    # Schlick (1994) eq. (3) S = t/(n − n·t + t), the exact quotient floored to ``out``
    one, out = c.fmt("t").one, c.fmt("out")
    want = [round_exact(Fraction(int(t), one) / (n - n * Fraction(int(t), one) + Fraction(int(t), one)),
                        out, c.rounding) for t, n in zip(i["t"], i["n"])]
    return equal(o["spec"], np.array(want))


def extremes(block_name):
    """Schlick's unit's extreme rows (Schlick 1994 eq. (3)): the smallest and largest
    divisor, n = 1, and the all-ones codes of ``t`` and ``n``."""
    return (
        Extreme(block_name, "smallest divisor: t = 1.0, n = 1 … n_max", "S = 1.0 exactly",
                lambda c: _grid([c.fmt("t").one], sorted({1, 2, c.n_max})), exactly("spec", 1.0)),
        Extreme(block_name, "n = 1 (divisor 1)", "S = t exactly",
                lambda c: _grid([0, 1, c.fmt("t").one // 2, c.fmt("t").one - 1, c.fmt("t").one], [1]),
                lambda c, i, o: equal(o["spec"], i["t"])),
        Extreme(block_name, "largest divisor: t = 0, n = n_max", "0",
                lambda c: _grid([0], [c.n_max]), zero("spec")),
        Extreme(block_name, "all-ones codes: t = 1 − 2⁻¹⁵, 1 LSB; n = 2^j − 1, n_max",
                "floor of the exact t/(n − n·t + t)",
                lambda c: _grid([1, c.fmt("t").one - 1],
                                [n for n in (1, 3, 255, 4095, c.n_max - 1, c.n_max) if n <= c.n_max]),
                _floor),
    )
