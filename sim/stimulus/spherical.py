"""Stimulus for the spherical interpolation unit: scanlines, each an ``init`` pixel then steps.

The unit is stateful, so the vectors are an ordered sequence of pixels.  Pixels
without ``init`` carry random junk in ``b``, ``s``, ``c``, ``bd``, ``sd``, ``cd``: the
unit must ignore it.  Directed spans first (lengths 1 and 2, 2048 pixels, ``init``
back to back, ``γ`` near 0 and near π, ``n = 1`` and ``n = 500`` from
:mod:`phongfx.golden.spherical_setup`, the ROM address wrapping at ``±π`` both ways),
then random spans of random codes up to ``count`` pixels.
"""

import math

import numpy as np

from phongfx.golden.spherical_setup import quantize_setup, span_setup
from . import concat, random_codes, rng

__all__ = ["stimulus", "span"]


def span(config, length, generator, *, b, s, c, bd=None, sd=None, cd=None):
    """Raw inputs of one scanline of ``length`` pixels: ``init`` and the given raw loads
    on the first, junk on the rest (``bd``, ``sd``, ``cd`` random when not given)."""
    theta, cfmt = config.fmt("theta"), config.fmt("c")
    junk = {"b": random_codes(theta, length, generator), "s": random_codes(theta, length, generator),
            "c": random_codes(cfmt, length, generator), "bd": random_codes(theta, length, generator),
            "sd": random_codes(theta, length, generator), "cd": random_codes(cfmt, (length, 3), generator)}
    loads = {"b": b, "s": s, "c": c, "bd": bd, "sd": sd, "cd": cd}
    for name, value in loads.items():
        if value is not None:
            junk[name][0] = value
    junk["init"] = np.zeros(length, dtype=np.int64)
    junk["init"][0] = 1
    return junk


def _geometric(config, generator, length, n, gamma, offset=0.3):
    """A span whose normal turns through ``gamma`` about Y while H stays at ``offset``."""
    u1 = np.array([0.0, 0.0, 1.0])
    u2 = np.array([math.sin(gamma), 0.0, math.cos(gamma)])
    h = np.array([math.sin(offset), 0.0, math.cos(offset)])
    raw = quantize_setup(config, span_setup(u1, u2, h, h, n, length))
    diffuse = quantize_setup(config, span_setup(u1, u2, h, h, 1, length))
    return span(config, length, generator, **raw, bd=diffuse["b"], sd=diffuse["s"],
                cd=[config.fmt("c").max_raw] * 3)


def stimulus(config, count=1000, seed=0):
    """Raw input codes: the directed spans of the module docstring, then random spans."""
    g = rng(seed)
    theta, cfmt = config.fmt("theta"), config.fmt("c")
    full, top = cfmt.max_raw, theta.max_raw
    quarter = 1 << (theta.width - 2)  # π/2 in raw codes
    step = 1 << (theta.width - config.addr_bits)  # one ROM cell
    parts = [
        span(config, 1, g, b=0, s=0, c=full),
        span(config, 2, g, b=-quarter, s=quarter, c=full),
        # 2048 pixels: θ turns eight times round, through every cell and both wraps
        span(config, 2048, g, b=theta.min_raw, s=(1 << theta.width) // 256 + 1, c=full, bd=0, sd=-3),
        # ROM address wrap at +π and at -π, by the smallest and by the largest steps
        span(config, 6, g, b=top - 2, s=1, c=full, bd=theta.min_raw + 1, sd=-1),
        span(config, 4, g, b=top - step, s=top, c=full, bd=theta.min_raw, sd=theta.min_raw),
    ]
    parts += [span(config, 1, g, b=code, s=0, c=full, bd=code, sd=0)  # init back to back
              for code in range(theta.min_raw, top + 1, step)]
    for n, gamma, length in ((1, 1e-6, 8), (10, 1e-6, 8), (500, 1.2, 16), (1, math.pi - 1e-6, 8),
                             (20, math.pi - 1e-3, 8), (500, 0.05, 64)):
        parts.append(_geometric(config, g, length, n, gamma))
    while count > 0:
        length = min(int(g.integers(1, 40)), count)
        parts.append(span(config, length, g, b=random_codes(theta, 1, g)[0],
                          s=random_codes(theta, 1, g)[0], c=random_codes(cfmt, 1, g)[0]))
        count -= length
    return concat(*parts)
