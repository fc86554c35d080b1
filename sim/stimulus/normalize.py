"""Stimulus for the normalizer: unit AXES, zero, 0°..90° spans, every code on an axis, random."""

import numpy as np

from . import AXES, codes, concat, random_codes, rng, unit_vectors
from .extreme import Extreme, equal_to, zero

__all__ = ["stimulus", "extremes"]


def _span(u0, u1, steps):
    """``steps`` points of the chord ``u0 -> u1``: what the LIRP feeds the normalizer."""
    a = np.linspace(0.0, 1.0, steps)[:, None]
    return (1 - a) * u0 + a * u1


def stimulus(config, count=1000, seed=0):
    vec = config.fmt("vec")
    g = rng(seed)
    directed = np.concatenate([AXES, np.zeros((1, 3))])

    # chord midpoints of spans 0°..90° (length cos(θ/2), z from 1/2 to 1), then whole
    # 90° spans in each plane and octant, whose midpoint is the worst case y = 1/2
    theta = np.radians(np.arange(91))
    ends = np.stack([np.cos(theta), np.sin(theta), np.zeros_like(theta)], axis=-1)
    mids = (np.array([1.0, 0, 0]) + ends) / 2
    spans = [_span(p, q, 65) for p in AXES for q in AXES if abs(p @ q) < 0.5]

    # a hair longer than unit: z just above 1 checks rounding where g dips below 1
    hair = np.concatenate([AXES * (1 + k * vec.lsb) for k in (1, 2, 3)]
                          + [unit_vectors(64, g) * (1 + 4 * vec.lsb)])
    directed = codes(np.concatenate([directed, mids, *spans, hair]), vec)

    # every code along one axis (s, 0, 0) and on the diagonal (s, s, s): z up to 12
    every = np.arange(vec.min_raw, vec.max_raw + 1, dtype=np.int64)
    zeros = np.zeros_like(every)
    sweeps = np.concatenate([np.stack([every, zeros, zeros], axis=-1),
                             np.stack([every, every, every], axis=-1)])

    unit = codes(unit_vectors(count, g), vec)
    short = codes(unit_vectors(count, g) * g.uniform(0.7, 1.0, (count, 1)), vec)
    junk = random_codes(vec, (count, 3), g)
    return concat(*({"n": part} for part in (directed, sweeps, unit, short, junk)))


def _end_codes(c):
    vec = c.fmt("vec")
    n = np.array([[vec.max_raw] * 3, [vec.min_raw] * 3, [vec.max_raw, vec.min_raw, 0],
                  [vec.min_raw, 0, 0], [vec.max_raw, 0, 0]], dtype=np.int64)
    return {"n": n}


def _shrinks(c, i, o):
    # z = N'·N' saturates below 2, where g ≤ 1: every lane shrinks toward 0, keeping its sign
    n, out = i["n"], o["n"]
    return np.all((np.abs(out) <= np.abs(n)) & (np.sign(out) * np.sign(n) >= 0), axis=-1)


def extremes(block_name):
    """The normalizer's extreme rows (Lyon 1993 Figure 7a): unit axes, zero length, and
    the end codes of ``vec``, where ``z`` saturates."""
    return (
        Extreme(block_name, "exactly ±1.0 (±axes)", "N unchanged (g(1) = 1)",
                lambda c: {"n": codes(AXES, c.vec)}, equal_to("n", "n")),
        Extreme(block_name, "zero-length (all-zeros code)", "N = 0",
                lambda c: {"n": np.zeros((1, 3), dtype=np.int64)}, zero("n")),
        Extreme(block_name, "all-ones codes (|N'| up to 2√3)",
                "z saturates below 2, g ≤ 1: each lane shrinks toward 0 keeping its sign",
                _end_codes, _shrinks),
    )
