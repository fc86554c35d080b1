"""Stimulus for the Gouraud unit: scanlines, each an ``init`` pixel then steps.

As :mod:`phongfx.sim.stimulus.euler`: junk in ``p0``, ``dp`` off ``init``; spans of 1,
2 and 2048 pixels from :mod:`phongfx.golden.euler_setup`, ``init`` back to back over
the extremes of ``p``, the extreme codes of both registers (which wrap), then seeded
random spans up to ``count`` pixels.
"""

import numpy as np

from phongfx.golden.euler_setup import quantize_gouraud, random_spans, span_setup

from . import concat, init_ends, random_scanlines, rng, scanline
from .extreme import accumulator_rows

__all__ = ["stimulus", "span", "geometric", "extremes", "PORTS"]

#: load port -> register format field
PORTS = {"p0": "p", "dp": "dp"}


def span(config, length, generator, **loads):
    """Raw inputs of one scanline of ``length`` pixels (:func:`~phongfx.sim.stimulus.scanline`
    with ``p0``, ``dp`` as the loads)."""
    return scanline(config, PORTS, length, generator, **loads)


def geometric(config, length, generator, max_angle=np.pi / 3):
    """A span from random unit normals at most ``max_angle`` apart and a random light."""
    na, nb, light = (v[0] for v in random_spans(1, max_angle, generator))
    return span(config, length, generator, **quantize_gouraud(config, span_setup(na, nb, light, length)))


def stimulus(config, count=1000, seed=0):
    """Raw input codes: the directed spans of the module docstring, then random spans."""
    g = rng(seed)
    p, dp = config.fmt("p"), config.fmt("dp")
    parts = [geometric(config, 1, g), geometric(config, 2, g), geometric(config, 2048, g)]
    parts += init_ends(config, span, g)
    for p0, step in ((p.max_raw, dp.max_raw), (p.min_raw, dp.min_raw), (0, dp.min_raw)):
        parts.append(span(config, 8, g, p0=p0, dp=step))
    return concat(*parts, *random_scanlines(config, count, g, span, geometric))


def extremes(block_name):
    """The Gouraud unit's extreme rows (Hast et al. §1): spans of 1 and 2048 pixels and the
    end codes of both registers, against the closed form ``p0 + k·dp``."""
    return accumulator_rows(block_name, span, geometric, {"dp": PORTS["dp"]})
