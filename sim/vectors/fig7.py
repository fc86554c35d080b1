"""Stimulus for the whole Figure 7 datapath: physical extremes and random shading cases."""

import numpy as np

from . import AXES, codes, concat, random_codes, rng, unit_vectors

__all__ = ["vectors"]


def _case(config, n0, n1, a, n, v, lights):
    vec = config.lirp.fmt("vec")
    count = len(n0)
    raw = {"n0": codes(n0, vec), "n1": codes(n1, vec), "a": codes(a, config.lirp.a),
           "n": np.asarray(n, dtype=np.int64), "v": codes(np.broadcast_to(v, (count, 3)), vec)}
    for index in range(config.lights):
        raw[f"l{index}"] = codes(np.broadcast_to(lights[index % len(lights)], (count, 3)), vec)
    return raw


def vectors(config, count=1000, seed=0):
    g = rng(seed)
    n_max = config.difference.n_max
    z = np.array([0.0, 0, 1])
    # normals that reflect V = z exactly onto each light (R = L, x = 0), a = 0 and 1,
    # N0 = -N1 (zero-length N' at a = 1/2), grazing light, n = 1 and n = n_max
    lights = [np.array([1.0, 1, -1]) / np.sqrt(3), np.array([1.0, -1, 1]) / np.sqrt(3)]
    halfway = [(l + z) / np.linalg.norm(l + z) for l in lights]
    n0 = np.concatenate([halfway, AXES, AXES, AXES[:3]])
    n1 = np.concatenate([halfway, AXES, AXES, -AXES[:3]])
    a = np.concatenate([[0, 1.0], np.zeros(6), np.ones(6), [0.5] * 3])
    directed = [_case(config, n0, n1, a, np.full(len(n0), shininess), z, lights)
                for shininess in (1, 4, 256, n_max)]
    grazing = [np.array([1.0, 0, 0]), np.array([0, -1.0, 0])]
    directed.append(_case(config, n0, n1, a, np.full(len(n0), n_max), z, grazing))

    # random: normals 0..60° apart, random lights and viewer in front of the surface
    u0 = unit_vectors(count, g)
    u1 = u0 + 0.5 * unit_vectors(count, g)
    u1 /= np.linalg.norm(u1, axis=-1, keepdims=True)
    v = unit_vectors(count, g)
    random = {"n0": codes(u0, config.lirp.vec), "n1": codes(u1, config.lirp.vec),
              "a": random_codes(config.lirp.fmt("a"), count, g, 0, config.lirp.fmt("a").one),
              "n": np.round(np.exp(g.uniform(0, np.log(n_max), count))).astype(np.int64),
              "v": codes(v, config.lirp.vec)}
    for index in range(config.lights):
        random[f"l{index}"] = codes(unit_vectors(count, g), config.lirp.vec)
    return concat(*directed, random)
