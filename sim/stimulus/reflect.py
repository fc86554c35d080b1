"""Stimulus for Reflect: axis pairs (N = ±V, N ⟂ V), 45° normals, a lit hemisphere, random."""

import numpy as np

from . import AXES, axis_pairs, codes, concat, random_codes, rng, unit_vectors

__all__ = ["stimulus"]


def stimulus(config, count=1000, seed=0):
    vec = config.fmt("vec")
    g = rng(seed)
    # every pair of ±axis vectors: N = V (R = V), N = -V (N·V = -1), N ⟂ V (grazing, R = -V)
    first, second = axis_pairs()
    axis = {"n": codes(first, vec), "v": codes(second, vec)}

    # normals at 45° between two AXES against every axis view: N·V = ±1/√2 or 0
    diag = [s * AXES[i] + t * AXES[j] for i in range(3) for j in range(i + 1, 3)
            for s in (1, -1) for t in (1, -1)]
    diag = np.array(diag) / np.sqrt(2)
    tilt = {"n": codes(np.repeat(diag, len(AXES), axis=0), vec),
            "v": codes(np.tile(AXES, (len(diag), 1)), vec)}

    # Lyon's test scene (appendix, specular.m): V = (0,0,1), N over the visible hemisphere
    x, y = np.meshgrid(np.linspace(-1, 1, 17), np.linspace(-1, 1, 17))
    inside = x * x + y * y <= 1
    n = np.stack([x[inside], y[inside], np.sqrt(1 - x[inside] ** 2 - y[inside] ** 2)], axis=-1)
    sphere = {"n": codes(n, vec), "v": codes(np.tile([0, 0, 1.0], (len(n), 1)), vec)}

    # random unit pairs, an eighth with N = V (N·V = |N|², only near 1 off the AXES),
    # and raw codes over the whole format
    un, uv = unit_vectors(count, g), unit_vectors(count, g)
    uv[: count // 8] = un[: count // 8]
    unit = {"n": codes(un, vec), "v": codes(uv, vec)}
    full = {"n": random_codes(vec, (count, 3), g), "v": random_codes(vec, (count, 3), g)}
    return concat(axis, tilt, sphere, unit, full)
