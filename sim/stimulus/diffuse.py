"""Stimulus for Diffuse: axis pairs (N = ±L, N ⟂ L), grazing lights either side, random."""

import numpy as np

from . import axis_pairs, codes, concat, random_codes, rng, unit_vectors

__all__ = ["stimulus"]


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
