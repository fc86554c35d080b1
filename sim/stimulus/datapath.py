"""Stimulus for whole datapaths: physical extremes and random shading cases.

Cases are built as float vectors (span ends of N, and of L and V, which stay
fixed unless the configuration interpolates them) and encoded for the ports the
configuration has: ``n`` or ``m`` (neither when the shininess is a constant of the
hardware), ``v`` or ``v0``/``v1``, ``l<i>`` or ``l<i>_0``/``l<i>_1``.
"""

import numpy as np

from phongfx.core.registry import REGISTRY

from . import AXES, codes, concat, normalized, random_codes, rng, unit_vectors
from .extreme import Extreme, equal

__all__ = ["stimulus", "encode", "extremes"]


def encode(config, n0, n1, a, shininess, v0, v1, lights0, lights1):
    """Raw codes for ``config``'s ports from float vectors (span ends of N, V and each light).

    ``shininess`` is n per case (Figure 8 gets ``m = round(√n)``); it is ignored when
    the configuration fixes the shininess (``config.shininess`` is None: no port; the
    hardware's constant applies to every case).  ``v0``/``v1`` and ``lights0``/``lights1``
    are single vectors (ends of an interpolated V or L when the configuration has them
    local; otherwise only the first is used).
    """
    end = config.lirp.fmt("vec")
    count = len(n0)
    raw = {"n0": codes(n0, end), "n1": codes(n1, end), "a": codes(a, config.lirp.a)}
    if config.shininess is not None:
        name, _, top = config.shininess
        value = np.asarray(shininess, dtype=np.float64)
        value = np.sqrt(value) if name == "m" else value
        raw[name] = np.clip(np.round(value), 1, top).astype(np.int64)

    def wide(vector):  # one vector for every case
        return np.broadcast_to(vector, (count, 3))

    if config.local_viewer:
        raw.update(v0=codes(wide(v0), end), v1=codes(wide(v1), end))
    else:
        raw["v"] = codes(wide(v0), config.normalize.fmt("out"))
    for index in range(config.lights):
        l0, l1 = lights0[index % len(lights0)], lights1[index % len(lights1)]
        if config.local_light(index):
            raw[f"l{index}_0"], raw[f"l{index}_1"] = codes(wide(l0), end), codes(wide(l1), end)
        else:
            raw[f"l{index}"] = codes(wide(l0), config.normalize.fmt("out"))
    return raw


def _top_n(config):
    """The largest n the hardware takes (the constant one when it is fixed)."""
    if config.shininess is None:
        return config.unit.top_n(config.shininess_const)
    return config.unit.top_n(config.shininess[2])


def stimulus(config, count=1000, seed=0):
    g = rng(seed)
    top = _top_n(config)
    z = np.array([0.0, 0, 1])
    # normals that reflect V = z exactly onto each light (R = L, x = 0), a = 0 and 1,
    # N0 = -N1 (zero-length N' at a = 1/2), grazing light, V = -L (zero-length H),
    # shininess 1 and the largest
    lights = [np.array([1.0, 1, -1]) / np.sqrt(3), np.array([1.0, -1, 1]) / np.sqrt(3)]
    halfway = [(l + z) / np.linalg.norm(l + z) for l in lights]
    n0 = np.concatenate([halfway, AXES, AXES, AXES[:3]])
    n1 = np.concatenate([halfway, AXES, AXES, -AXES[:3]])
    a = np.concatenate([[0, 1.0], np.zeros(6), np.ones(6), [0.5] * 3])
    directed = [encode(config, n0, n1, a, np.full(len(n0), n), z, z, lights, lights)
                for n in ((1, 4, 256, top) if config.shininess is not None else (top,))]
    grazing = [np.array([1.0, 0, 0]), np.array([0, -1.0, 0])]
    directed.append(encode(config, n0, n1, a, np.full(len(n0), top), z, z, grazing, grazing))
    directed.append(encode(config, n0, n1, a, np.full(len(n0), 16), z, z, [-z], [-z]))

    # random: N, L, V span ends 0..60° apart; shininess log-uniform
    def pairs(size):
        start = unit_vectors(size, g)
        end = start + 0.5 * unit_vectors(size, g)
        return start, normalized(end, in_place=True)

    u0, u1 = pairs(count)
    shininess = np.exp(g.uniform(0, np.log(top), count))
    raw = encode(config, u0, u1, np.zeros(count), shininess, z, z, [z], [z])
    raw["a"] = random_codes(config.lirp.fmt("a"), count, g, 0, config.lirp.fmt("a").one)
    for name in [p for p in config.inputs if p[0] in "lv"]:
        if name.endswith("_1") or name == "v1":
            continue
        start, end = pairs(count)
        if name.endswith("_0") or name == "v0":
            raw[name] = codes(start, config.lirp.fmt("vec"))
            raw[name[:-1] + "1"] = codes(end, config.lirp.fmt("vec"))
        else:
            raw[name] = codes(start, config.normalize.fmt("out"))
    if config.shininess is None:
        # one n, perhaps a high one, which random normals hardly ever light: aim N near the
        # normal mirroring V onto each light (a tilt δ gives x ≈ 2n·δ², here up to 12.5)
        tilt = 2.5 / np.sqrt(top)
        for mirror in halfway:
            near = mirror + unit_vectors(count // 4, g) * g.uniform(0, tilt, count // 4)[:, None]
            near = normalized(near, in_place=True)
            directed.append(encode(config, near, near, np.zeros(len(near)), np.full(len(near), top),
                                   z, z, lights, lights))
    return concat(*directed, raw)


def _cases(c, n0, n1, a, v, lights, ns):
    """The span ends ``n0``, ``n1`` at ``a`` under view ``v`` and ``lights``, once per n of ``ns``."""
    n0, n1 = np.atleast_2d(n0), np.atleast_2d(n1)
    return concat(*(encode(c, n0, n1, np.full(len(n0), a), np.full(len(n0), n), v, v, lights, lights)
                    for n in ns))


def _every_light(spec, diff):
    """Check: every light's ``spec`` and ``diff`` outputs are exactly these values."""
    def holds(c, i, o):
        ok = np.ones(len(o["spec0"]), dtype=bool)
        for index in range(c.lights):
            for name, value in ((f"spec{index}", spec), (f"diff{index}", diff)):
                ok &= equal(o[name], c.outputs[name][0].exact_raw(value))
        return ok
    return holds


def extremes(block_name):
    """A whole datapath's extreme rows (Lyon 1993 Figures 7, 8 and 5: ``fig7``, ``fig8``,
    ``halfway_datapath``): N = V = L, a zero-length N' at 180°, a grazing light, V = −L."""
    z, x = np.array([0.0, 0, 1]), np.array([1.0, 0, 0])
    # V = −L: D = R − L has |D| = 2, past 2^k, but the halfway vector H = (V + L)/2 is 0
    halfway = REGISTRY[block_name].default_config().unit.bisector
    spec_vl = 1.0 if halfway else 0.0
    note = "H = (V+L)/2 = 0 gives D = 0: a full highlight, ungated by N·L < 0" if halfway else "|D| = 2: x ≥ 2^k"
    return (
        Extreme(block_name, "exactly ±1.0: N = V = L (R = L), n = 1 and n_max",
                "spec = 1.0 and diff = 1.0 exactly",
                lambda c: concat(*(_cases(c, z, z, a, z, [z], (1, _top_n(c))) for a in (0.0, 1.0))),
                _every_light(1.0, 1.0)),
        Extreme(block_name, "zero-length N' at 180° (N0 = −N1, a = 1/2), n_max",
                "N = 0: diff = 0; spec = 0 (x ≥ 2^k at the largest n)",
                lambda c: _cases(c, AXES[:3], -AXES[:3], 0.5, z, [z, x], (_top_n(c),)), _every_light(0.0, 0.0)),
        Extreme(block_name, "grazing light (N ⟂ L), n_max", "diff = 0, spec = 0",
                lambda c: _cases(c, z, z, 0.0, z, [x, -x[[1, 0, 2]]], (_top_n(c),)), _every_light(0.0, 0.0)),
        Extreme(block_name, "V = −L (N = V), n_max", f"diff = 0 (N·L = −1); spec = {spec_vl:g} ({note})",
                lambda c: _cases(c, z, z, 0.0, z, [-z], (_top_n(c),)), _every_light(spec_vl, 0.0)),
    )
