"""Stimulus for the harness: seeded random, directed extremes, exhaustive sets.

Each block has a module here, named like its config, golden and hdl modules, with
``stimulus(config, count, seed)`` returning raw input codes ``{port: int64 array}``:
its directed extremes first, then an exhaustive set where the input space has at most
2**16 codes, then ``count`` seeded random inputs; and ``extremes(block_name)``, its rows
of the extremes table (:class:`~phongfx.sim.stimulus.extreme.Extreme` records; the
checks the rows share are in :mod:`.extreme`).  The helpers below are shared by all of
them.  ("Vector" in this code base means a direction: N, L, V, R, H.)

May import: ``phongfx.core``, ``phongfx.config``, ``phongfx.golden``.
"""

import numpy as np

from phongfx.golden.fixed import Fixed

__all__ = ["rng", "random_codes", "lengths", "normalized", "unit_vectors", "codes", "concat", "at_angle", "AXES", "axis_pairs",
           "perpendicular_pairs", "random_pairs", "scanline", "init_ends", "random_scanlines", "EXHAUSTIVE_LIMIT"]

#: Largest input space that is checked exhaustively.
EXHAUSTIVE_LIMIT = 1 << 16


#: The six unit axis vectors ±X, ±Y, ±Z: components exactly ±1.0 and 0.
AXES = np.concatenate([np.eye(3), -np.eye(3)])


def axis_pairs():
    """Every ordered pair of :data:`AXES` as two (36, 3) arrays: equal, opposite, at 90°."""
    first, second = np.repeat(AXES, len(AXES), axis=0), np.tile(AXES, (len(AXES), 1))
    return first, second


def perpendicular_pairs():
    """The pairs of :func:`axis_pairs` at 90° as two (24, 3) arrays: a grazing light or view."""
    first, second = axis_pairs()
    keep = np.abs(np.sum(first * second, axis=-1)) < 0.5
    return first[keep], second[keep]


def rng(seed):
    return np.random.default_rng(seed)


def random_codes(fmt, shape, generator, lo=None, hi=None):
    """Uniform raw codes of ``fmt`` (optionally limited to ``lo..hi`` raw)."""
    lo = fmt.min_raw if lo is None else lo
    hi = fmt.max_raw if hi is None else hi
    return generator.integers(lo, hi, size=shape, endpoint=True, dtype=np.int64)


def lengths(v):
    """The length of each 3-vector (row) of ``v``, ``(count, 1)``: the same numbers as
    ``np.linalg.norm(v, axis=-1, keepdims=True)``, summed in its order ``(x² + y²) + z²``, in a
    sixteenth of its time (numpy reduces a 3-long axis a row at a time: a quarter of a second
    per million vectors, most of a datapath's stimulus)."""
    v = np.asarray(v, dtype=np.float64)
    x, y, z = v[..., 0], v[..., 1], v[..., 2]
    return np.sqrt((x * x + y * y) + z * z)[..., None]


def normalized(v, in_place=False):
    """Each row of ``v`` divided by its :func:`lengths`, column by column (the same numbers
    as a broadcast division, without its 3-long inner loop); ``in_place``: into ``v`` itself
    (a fresh float64 array of the caller's), which spares touching a new one."""
    v = np.asarray(v, dtype=np.float64)
    length = lengths(v)[..., 0]
    out = v if in_place else np.empty_like(v)
    for axis in range(3):
        np.divide(v[..., axis], length, out=out[..., axis])
    return out


def unit_vectors(count, generator):
    """``count`` float unit vectors, uniform on the sphere."""
    return normalized(generator.normal(size=(count, 3)), in_place=True)


def at_angle(alpha, generator):
    """Pairs of unit vectors ``(r, l)`` at angles ``alpha`` (radians), random orientation."""
    l = unit_vectors(len(alpha), generator)
    side = np.cross(l, unit_vectors(len(alpha), generator))
    side = normalized(side)
    return np.cos(alpha)[:, None] * l + np.sin(alpha)[:, None] * side, l


def codes(values, fmt):
    """Float values to raw codes of ``fmt``, rounded half up and saturated (for stimulus)."""
    return Fixed.from_float(values, fmt, rounding="round_half_up", overflow="saturate").raw


def concat(*parts):
    """Concatenate dicts of raw code arrays port by port."""
    return {name: np.concatenate([np.asarray(part[name], dtype=np.int64) for part in parts])
            for name in parts[0]}


def random_pairs(config, count, generator):
    """Two sets of ``count`` direction pairs ``r``, ``l`` with a random shininess each, for
    the blocks of Lyon (1993) Figures 7c (``n``) and 8 (``m``): seeded random unit pairs, and
    raw codes over the whole ``vec`` format (``|D|`` up to 4).  The shininess is drawn from
    the range the hardware takes, one value when it is a constant
    (:attr:`~phongfx.config.base.ConstantShininess.shininess_range`)."""
    vec, port = config.fmt("vec"), config.SHININESS
    fmt, (lo, hi) = config.fmt(port), config.shininess_range
    unit = {"r": codes(unit_vectors(count, generator), vec), "l": codes(unit_vectors(count, generator), vec),
            port: random_codes(fmt, count, generator, lo, hi)}
    full = {"r": random_codes(vec, (count, 3), generator), "l": random_codes(vec, (count, 3), generator),
            port: random_codes(fmt, count, generator, lo, hi)}
    return unit, full


def scanline(config, ports, length, generator, **loads):
    """Raw inputs of one scanline of ``length`` pixels of a stateful scanline unit (Hast et
    al.'s Euler and Gouraud units): ``init`` and the raw ``loads`` of ``ports`` ``{load
    port: register format field}`` (random when not given) on the first pixel, random junk
    on the rest, which the unit must ignore."""
    raw = {name: random_codes(config.fmt(fmt), length, generator) for name, fmt in ports.items()}
    for name, value in loads.items():
        raw[name][0] = value
    raw["init"] = np.zeros(length, dtype=np.int64)
    raw["init"][0] = 1
    return raw


def init_ends(config, span, generator):
    """Scanlines of one pixel, ``init`` back to back, over the end codes of ``p`` (and 1.0
    where ``p`` holds it); ``span`` is the unit's ``(config, length, generator, **loads)``."""
    p = config.fmt("p")
    return [span(config, 1, generator, p0=code)
            for code in (p.min_raw, p.max_raw, 0, -1, 1, min(p.one, p.max_raw))]


def random_scanlines(config, count, generator, span, geometric):
    """Random scanlines of 1..39 pixels up to ``count`` pixels, half of them ``geometric``
    (from a span setup), half ``span`` (random codes): the unit's own builders."""
    parts = []
    while count > 0:
        length = min(int(generator.integers(1, 40)), count)
        parts.append(geometric(config, length, generator) if generator.random() < 0.5
                     else span(config, length, generator))
        count -= length
    return parts
