"""Stimulus for Reflect: axis pairs (N = ±V, N ⟂ V), 45° normals, a lit hemisphere, random."""

import numpy as np

from . import AXES, axis_pairs, codes, concat, perpendicular_pairs, random_codes, rng, unit_vectors
from .extreme import Extreme, equal, equal_to

__all__ = ["stimulus", "extremes"]


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


def _end_codes(c):
    vec = c.fmt("vec")
    n = np.array([[vec.max_raw] * 3, [vec.min_raw] * 3, [0] * 3], dtype=np.int64)
    return {"n": n, "v": n}


def _end_codes_hold(c, i, o):
    # N = V = (c, c, c): R = (2·3c² − 1)·c per lane, ±6 at the corners: saturates to the
    # end of ``out`` on the side of c, and 0 stays 0
    out = c.fmt("out")
    want = np.where(i["v"] > 0, out.max_raw, np.where(i["v"] < 0, out.min_raw, 0))
    return equal(o["r"], want)


def extremes(block_name):
    """Reflect's extreme rows (Lyon 1993 Figure 7b): N = ±V, N ⟂ V, the end codes of ``vec``."""
    graze_n, graze_v = perpendicular_pairs()
    return (
        Extreme(block_name, "exactly ±1.0, N = ±V", "R = V exactly",
                lambda c: {"n": codes(np.concatenate([AXES, AXES]), c.vec),
                           "v": codes(np.concatenate([AXES, -AXES]), c.vec)}, equal_to("v", "r")),
        Extreme(block_name, "grazing (N ⟂ V)", "R = −V exactly",
                lambda c: {"n": codes(graze_n, c.vec), "v": codes(graze_v, c.vec)},
                lambda c, i, o: equal(o["r"], -i["v"])),
        Extreme(block_name, "all-ones and all-zeros codes (N = V)",
                "saturates to ±(2 − 2⁻¹⁰) on the side of V; 0 stays 0", _end_codes, _end_codes_hold),
    )
