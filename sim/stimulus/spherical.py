"""Stimulus for the spherical interpolation unit: scanlines, each an ``init`` pixel then steps.

The unit is stateful, so the vectors are an ordered sequence of pixels.  Pixels
without ``init`` carry random junk in ``b``, ``s``, ``c``, ``bd``, ``sd``, ``cd``: the
unit must ignore it.  Directed spans first (lengths 1 and 2, 2048 pixels, ``init``
back to back, ``γ`` near 0 and near π, ``n = 1`` and ``n = 500`` from
:mod:`phongfx.golden.spherical_setup`, the ROM address wrapping at ``±π`` both ways),
then random spans of random codes up to ``count`` pixels.
"""

import math
from fractions import Fraction

import numpy as np

from phongfx.core.registry import get_block
from phongfx.golden.euler import segments
from phongfx.golden.spherical_setup import quantize_setup, span_setup

from . import concat, random_codes, rng
from .extreme import Extreme, all_of, equal, round_exact, wrap, zero

__all__ = ["stimulus", "span", "extremes"]


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


def _spans(c, spans):
    """Spans ``(length, b, s, c, bd, sd[, cd])`` back to back, the junk of span j seeded j."""
    parts = []
    for seed, (length, b, s, cval, bd, sd, *cd) in enumerate(spans):
        parts.append(span(c, length, rng(seed), b=b, s=s, c=cval, bd=bd, sd=sd,
                          cd=[cd[0]] * 3 if cd else None))
    return concat(*parts)


def _fresh(c, i, o):
    # θ accumulates modulo 2π (Figure 12's adder wraps): pixel X of a span equals a fresh
    # init at b + X·s (and b_d + X·s_d) wrapped to the register
    theta = c.fmt("theta")
    last, k = segments(i["init"])
    fresh = {"init": np.ones_like(i["init"]), "s": np.zeros_like(i["s"]), "sd": np.zeros_like(i["sd"]),
             "b": np.array([wrap(int(b) + int(kk) * int(s), theta) for b, s, kk in
                            zip(i["b"][last], i["s"][last], k)]),
             "bd": np.array([wrap(int(b) + int(kk) * int(s), theta) for b, s, kk in
                             zip(i["bd"][last], i["sd"][last], k)]),
             "c": i["c"][last], "cd": i["cd"][last]}
    want = get_block("spherical", config=c).golden(fresh)
    return equal(o["spec"], want["spec"]) & equal(o["diff"], want["diff"])


def _peak(c, i, o):
    # θ = 0: cos²0 = cos 0 = 1 saturates the ROM word to 1 − 2^-D; out = C·(1 − 2^-D) rounded
    rom, cfmt, out = c.fmt("rom"), c.fmt("c"), c.fmt("out")
    word = Fraction(rom.max_raw, rom.one)
    spec = [round_exact(Fraction(int(x), cfmt.one) * word, out, c.rounding) for x in i["c"]]
    return equal(o["spec"], np.array(spec)) & equal(o["diff"], np.array(spec)[:, None])


def extremes(block_name):
    """The spherical unit's extreme rows (Szirmay-Kalos et al. 2000 Figure 12): spans of 1
    and 2048 pixels, the ROM address wrapping at ±π, and C = 0."""
    def theta(c):
        return c.fmt("theta")

    def top(c):
        return c.fmt("c").max_raw

    return (
        Extreme(block_name, "span of 1 pixel at θ = 0", "C·(1 − 2⁻⁶) rounded (cos² 0 = 1 saturates the ROM)",
                lambda c: _spans(c, [(1, 0, 0, x, 0, 0, x) for x in (top(c), 1, c.fmt("c").one)]), _peak),
        Extreme(block_name, "span of 1 pixel at θ = π/2 and −π", "0 (cos ≤ 0 past ±π/2)",
                lambda c: _spans(c, [(1, q, 0, top(c), q, 0, top(c))
                                     for q in (1 << (theta(c).width - 2), theta(c).min_raw)]),
                all_of(zero("spec"), zero("diff"))),
        Extreme(block_name, "span of 2048 pixels (θ turns 8 times)", "pixel X = fresh init at b + X·s mod 2π",
                lambda c: _spans(c, [(2048, theta(c).min_raw, (1 << theta(c).width) // 256 + 1,
                                      top(c), 0, -3)]), _fresh),
        Extreme(block_name, "ROM address wrap at ±π (all-ones codes)", "pixel X = fresh init at b + X·s mod 2π",
                lambda c: _spans(c, [(6, theta(c).max_raw - 2, 1, top(c), theta(c).min_raw + 1, -1),
                                     (4, theta(c).max_raw, theta(c).max_raw, top(c),
                                      theta(c).min_raw, theta(c).min_raw)]), _fresh),
        Extreme(block_name, "all-zeros codes (C = 0)", "0",
                lambda c: _spans(c, [(4, 0, 5, 0, 0, 5, 0)]), all_of(zero("spec"), zero("diff"))),
    )
