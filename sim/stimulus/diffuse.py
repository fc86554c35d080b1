"""Stimulus for Diffuse: axis pairs (N = ±L, N ⟂ L), grazing lights either side, random."""

import numpy as np

from . import AXES, axis_pairs, codes, concat, perpendicular_pairs, random_codes, rng, unit_vectors
from .extreme import Extreme, corner, equal, exactly, zero

__all__ = ["stimulus", "extremes"]


def stimulus(config, count=1000, seed=0):
    vec = config.fmt("vec")
    g = rng(seed)
    # every pair of ±axis vectors: N = L (exactly 1.0), N = -L and N ⟂ L (both 0)
    first, second = axis_pairs()
    axis = {"n": codes(first, vec), "l": codes(second, vec)}

    # N = L and N = -L off the AXES: 1.0 give or take the quantization of |N|, and 0
    u = codes(unit_vectors(count // 8, g), vec)
    same = {"n": np.concatenate([u, u]), "l": np.concatenate([u, -u])}

    # grazing: L = (b, -a, 0) is exactly ⟂ N = (a, b, c); one raw step on each lane of L
    # then moves N·L by ±N_i LSB, either side of the backside test
    n = codes(unit_vectors(count // 8, g), vec)
    flat = np.stack([n[:, 1], -n[:, 0], np.zeros(len(n), dtype=np.int64)], axis=-1)
    steps = np.concatenate([np.zeros((1, 3)), np.eye(3), -np.eye(3)]).astype(np.int64)
    graze = {"n": np.tile(n, (len(steps), 1)),
             "l": np.clip(np.concatenate([flat + s for s in steps]), vec.min_raw, vec.max_raw)}

    # random unit pairs, and raw codes over the whole format
    unit = {"n": codes(unit_vectors(count, g), vec), "l": codes(unit_vectors(count, g), vec)}
    full = {"n": random_codes(vec, (count, 3), g), "l": random_codes(vec, (count, 3), g)}
    return concat(axis, same, graze, unit, full)


def extremes(block_name):
    """Diffuse's extreme rows (Lyon 1993 "Background", Lambert): N = ±L, N ⟂ L, and the top
    codes of ``vec``."""
    graze_n, graze_l = perpendicular_pairs()
    return (
        Extreme(block_name, "exactly ±1.0, N = L", "1.0 exactly",
                lambda c: {"n": codes(AXES, c.vec), "l": codes(AXES, c.vec)}, exactly("diff", 1.0)),
        Extreme(block_name, "N = −L", "0 (backside test)",
                lambda c: {"n": codes(AXES, c.vec), "l": codes(-AXES, c.vec)}, zero("diff")),
        Extreme(block_name, "grazing light (N ⟂ L)", "0",
                lambda c: {"n": codes(graze_n, c.vec), "l": codes(graze_l, c.vec)}, zero("diff")),
        Extreme(block_name, "all-ones codes (N = L = max)", "saturates to 2 − 2⁻¹⁰",
                lambda c: {"n": corner(c), "l": corner(c)},
                lambda c, i, o: equal(o["diff"], c.fmt("out").max_raw)),
    )
