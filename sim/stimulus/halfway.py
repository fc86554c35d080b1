"""Stimulus for the halfway block: the peak, V = -L, grazing, AXES, extremes, Lyon's scene, random."""

import numpy as np

from . import AXES, codes, concat, perpendicular_pairs, random_codes, rng, unit_vectors
from .extreme import Extreme, all_of, equal, zero

__all__ = ["stimulus", "grazing", "GRAZING_DEGREES", "extremes"]

#: φ, half the angle between V and L (each is φ from N): H = (V + L)/2 is cos φ long, along N.
GRAZING_DEGREES = (0, 30, 60, 75, 80, 85, 88, 89, 89.5, 89.9, 90)


def _frames(count, generator):
    """``count`` random orthonormal pairs (e1, e3)."""
    e3 = unit_vectors(count, generator)
    e1 = np.cross(e3, unit_vectors(count, generator))
    return e1 / np.linalg.norm(e1, axis=-1, keepdims=True), e3


def grazing(count, generator):
    """N, L, V at the peak with L and V opening to 2φ for every φ of :data:`GRAZING_DEGREES`:
    ``V = sin φ e1 + cos φ N``, ``L = -sin φ e1 + cos φ N``, so ``H`` shrinks along ``N``."""
    e1, e3 = _frames(count, generator)
    phi = np.radians(np.repeat(GRAZING_DEGREES, count))[:, None]
    e1, e3 = np.tile(e1, (len(GRAZING_DEGREES), 1)), np.tile(e3, (len(GRAZING_DEGREES), 1))
    return e3, -np.sin(phi) * e1 + np.cos(phi) * e3, np.sin(phi) * e1 + np.cos(phi) * e3


def stimulus(config, count=1000, seed=0):
    vec = config.fmt("vec")
    g = rng(seed)
    # every triple of ±AXES: components exactly ±1.0 and 0; V = -L (H = 0), V = L, 90°
    index = np.indices((len(AXES),) * 3).reshape(3, -1)
    axis = {name: codes(AXES[i], vec) for name, i in zip("nlv", index)}

    # the peak, N along H for random V, L (D ≈ 0 but for g2, whose H* may be short)
    v, l = unit_vectors(64, g), unit_vectors(64, g)
    h = v + l
    keep = np.linalg.norm(h, axis=-1) > 0.05
    peak = {"n": codes(h[keep] / np.linalg.norm(h[keep], axis=-1, keepdims=True), vec),
            "l": codes(l[keep], vec), "v": codes(v[keep], vec)}

    # H = 0 exactly: L is the negated code of V, under random normals
    v = codes(unit_vectors(32, g), vec)
    zero = {"n": codes(unit_vectors(32, g), vec), "l": -v, "v": v}

    n, l, v = grazing(8, g)
    graze = {"n": codes(n, vec), "l": codes(l, vec), "v": codes(v, vec)}

    # each vector at a corner of the format (every component min_raw or max_raw): junk
    # that saturates z, the dots and the outputs
    corner = np.array([[vec.min_raw if b else vec.max_raw for b in (i & 1, i & 2, i & 4)]
                       for i in range(8)])
    index = np.indices((8, 8, 8)).reshape(3, -1)
    corners = {name: corner[i] for name, i in zip("nlv", index)}

    # Lyon's scene (appendix, specular.m): V = (0,0,1), lights along [1,1,-1] and [1,-1,1],
    # N over the visible hemisphere
    x, y = np.meshgrid(np.linspace(-1, 1, 13), np.linspace(-1, 1, 13))
    inside = x * x + y * y <= 1
    n = np.stack([x[inside], y[inside], np.sqrt(1 - x[inside] ** 2 - y[inside] ** 2)], axis=-1)
    lights = np.array([[1, 1, -1], [1, -1, 1]]) / np.sqrt(3)
    scene = {"n": codes(np.tile(n, (2, 1)), vec), "l": codes(np.repeat(lights, len(n), axis=0), vec),
             "v": codes(np.tile([0, 0, 1.0], (2 * len(n), 1)), vec)}

    unit = {name: codes(unit_vectors(count, g), vec) for name in "nlv"}
    full = {name: random_codes(vec, (count, 3), g) for name in "nlv"}
    return concat(axis, peak, zero, graze, corners, scene, unit, full)


def extremes(block_name):
    """The halfway block's extreme rows (Lyon 1993 Figure 5): the peak, V = −L, V = L ⟂ N."""
    graze_n, graze_l = perpendicular_pairs()
    return (
        Extreme(block_name, "exactly ±1.0, V = L = N (peak)", "p = q = N (D = 0)",
                lambda c: {k: codes(AXES, c.vec) for k in "nlv"},
                lambda c, i, o: equal(o["p"], i["n"]) & equal(o["q"], i["n"])),
        Extreme(block_name, "V = −L (zero-length H)", "p = q = 0",
                lambda c: {"n": codes(np.roll(AXES, 1, axis=0), c.vec), "l": codes(-AXES, c.vec),
                           "v": codes(AXES, c.vec)}, all_of(zero("p"), zero("q"))),
        Extreme(block_name, "grazing (V = L ⟂ N)", "p = 0, q = L",
                lambda c: {"n": codes(graze_n, c.vec), "l": codes(graze_l, c.vec),
                           "v": codes(graze_l, c.vec)},
                lambda c, i, o: equal(o["p"], 0) & equal(o["q"], i["l"])),
    )
