"""Stimulus for the corrected Euler unit: scanlines, each an ``init`` pixel then steps.

The unit is stateful, so the vectors are an ordered sequence of pixels.  Pixels
without ``init`` carry random junk in ``p0``, ``t0``, ``ds``: the unit must ignore it.
Directed spans first (lengths 1 and 2, 2048 pixels, from
:mod:`phongfx.golden.euler_setup` with normals 60° apart; ``init`` back to back over
the extremes of ``p``; the largest and smallest codes of every register, which
wrap), then seeded random spans: geometric ones and random codes, up to ``count``
pixels.
"""

import numpy as np

from phongfx.golden.euler_setup import quantize_setup, random_spans, span_setup

from . import concat, init_ends, random_scanlines, rng, scanline
from .extreme import accumulator_rows

__all__ = ["stimulus", "span", "geometric", "extremes", "PORTS"]

#: load port -> register format field
PORTS = {"p0": "p", "t0": "t", "ds": "ds"}


def span(config, length, generator, **loads):
    """Raw inputs of one scanline of ``length`` pixels (:func:`~phongfx.sim.stimulus.scanline`
    with ``p0``, ``t0``, ``ds`` as the loads)."""
    return scanline(config, PORTS, length, generator, **loads)


def geometric(config, length, generator, max_angle=np.pi / 3, compensate=False):
    """A span from random unit normals at most ``max_angle`` apart and a random light."""
    na, nb, light = (v[0] for v in random_spans(1, max_angle, generator))
    return span(config, length, generator,
                **quantize_setup(config, span_setup(na, nb, light, length), compensate))


def stimulus(config, count=1000, seed=0):
    """Raw input codes: the directed spans of the module docstring, then random spans."""
    g = rng(seed)
    p, t, d = (config.fmt(name) for name in ("p", "t", "ds"))
    parts = [geometric(config, 1, g), geometric(config, 2, g), geometric(config, 2048, g),
             geometric(config, 2048, g, compensate=True), geometric(config, 2, g, np.pi)]
    parts += init_ends(config, span, g)
    for t0, ds in ((t.max_raw, d.max_raw), (t.min_raw, d.min_raw), (t.max_raw, d.min_raw), (0, d.max_raw)):
        parts.append(span(config, 8, g, p0=p.max_raw, t0=t0, ds=ds))
    return concat(*parts, *random_scanlines(config, count, g, span, geometric))


def extremes(block_name):
    """The corrected Euler unit's extreme rows (Hast et al. eqs. 16–17): spans of 1 and 2048
    pixels and the end codes of every register, against the closed form of eq. (14)."""
    return accumulator_rows(block_name, span, geometric, {"t0": PORTS["t0"], "ds": PORTS["ds"]})
