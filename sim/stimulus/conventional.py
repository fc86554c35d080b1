"""Stimulus for the conventional Phong unit: axis and zero normals, ``N = L = V``
(``R·V = 1``), the light behind the surface, grazing light, edge ``n``, then random
highlights (``R`` near ``V``) and, where the config normalizes them, non-unit ``L`` and ``V``."""

import numpy as np

from . import AXES, axis_pairs, codes, concat, perpendicular_pairs, unit_vectors
from .blinn import edge_n, mixed
from .extreme import Extreme, all_of, exactly, vectors_at_shininess_ends, zero

__all__ = ["stimulus", "directed", "highlights", "extremes"]


def _lengths(config, count, generator):
    """(count, 1) lengths of the ``L`` and ``V`` inputs: 1, or 0.05..1.7 where local (the
    shortest a local vector's even shift brings up by several pairs, the longest near ``vec``'s
    end for a vector along an axis)."""
    local = (config.local_light, config.local_viewer)
    return [generator.uniform(0.05, 1.7, (count, 1)) if flag else np.ones((count, 1)) for flag in local]


def directed(config):
    """Raw ``normal``, ``light``, ``view`` rows, each with every :func:`~.blinn.edge_n`.

    * every ordered pair of unit axes as ``N`` and ``L`` with ``V`` each of the pair:
      ``N = L = V`` (``R·V = 1``), ``L = -N`` (behind: ``R·V = 1`` for ``V = L``, yet 0),
      at 90° (grazing: ``N·L = 0``); the same with ``N`` halved;
    * ``N = 0`` (``q = 0``) and the shortest nonzero ``N``: one LSB on an axis, on all three,
      and one negative LSB, lit and seen along themselves (``R·V = 1``);
    * the longest codes (components at the format's ends: junk, saturating paths) and, where
      the config normalizes them, zero-length and half-length ``L`` and ``V``.
    """
    vec = config.fmt("vec")
    first, second = axis_pairs()
    lsb = vec.lsb
    tiny = np.array([[lsb, 0, 0], [0, 0, -lsb], [lsb, lsb, lsb], [-lsb, lsb, 0]])
    along = tiny / np.linalg.norm(tiny, axis=-1, keepdims=True)
    normals = np.concatenate([first, first, first / 2, first / 2, np.zeros((1, 3)), tiny])
    lights = np.concatenate([second, second, second, second, AXES[:1], along])
    views = np.concatenate([second, first, second, first, AXES[:1], along])
    rows = {"normal": codes(normals, vec), "light": codes(lights, vec), "view": codes(views, vec)}
    ends = np.array([[vec.min_raw] * 3, [vec.max_raw] * 3, [vec.min_raw, vec.max_raw, 0]])
    parts = [rows, {"normal": ends, "light": ends, "view": ends[::-1]}]
    if config.local_light or config.local_viewer:
        axis = np.tile(AXES[:1], (2, 1))
        short = np.array([[0.0, 0, 0], [0.5, 0, 0]])
        parts.append({"normal": codes(axis, vec),
                      "light": codes(short if config.local_light else axis, vec),
                      "view": codes(short if config.local_viewer else axis, vec)})
    rows = concat(*parts)
    ns = edge_n(config)
    count = len(rows["normal"])
    out = {name: np.repeat(value, len(ns), axis=0) for name, value in rows.items()}
    out["n"] = np.tile(ns, count)
    return out


def highlights(config, count, generator, n=None):
    """``count`` rows near the highlight: ``N`` unit times ``|N|`` in ``[0.5, 1]``, ``L`` a random
    unit vector in front of it, ``V`` at an angle up to ``4/sqrt(n)`` from ``R = 2(N·L)N - L``
    (where ``t^n`` is not yet 0), ``L`` and ``V`` scaled by :func:`_lengths`, ``n``
    log-uniform in ``1..n_max`` (or the given one)."""
    vec = config.fmt("vec")
    if n is None:
        n = np.exp(generator.uniform(0, np.log(config.n_max), count)).round().astype(np.int64)
    n = np.clip(np.broadcast_to(np.asarray(n, dtype=np.int64), (count,)), 1, config.n_max)
    alpha = generator.uniform(0, 1, count) * np.minimum(4 / np.sqrt(n), np.pi)
    unit_n = unit_vectors(count, generator)
    light = unit_vectors(count, generator)
    light = np.where(np.sum(light * unit_n, -1, keepdims=True) < 0, -light, light)
    r = 2 * np.sum(light * unit_n, -1, keepdims=True) * unit_n - light
    side = np.cross(r, unit_vectors(count, generator))
    side /= np.linalg.norm(side, axis=-1, keepdims=True)
    view = np.cos(alpha)[:, None] * r + np.sin(alpha)[:, None] * side
    length_l, length_v = _lengths(config, count, generator)
    normal = unit_n * generator.uniform(0.5, 1.0, (count, 1))
    return {"normal": codes(normal, vec), "light": codes(light * length_l, vec),
            "view": codes(view * length_v, vec), "n": n}


def _spread(config, count, g):
    vec = config.fmt("vec")
    length_l, length_v = _lengths(config, count, g)
    return {"normal": codes(unit_vectors(count, g) * g.uniform(0.5, 1, (count, 1)), vec),
            "light": codes(unit_vectors(count, g) * length_l, vec),
            "view": codes(unit_vectors(count, g) * length_v, vec)}


def stimulus(config, count=1000, seed=0):
    """Raw codes (:func:`~phongfx.sim.stimulus.blinn.mixed`): :func:`directed`, then ``count``
    random: half :func:`highlights`, a quarter random ``L``, ``V`` (lengths by
    :func:`_lengths`) and ``N`` of length 0.5..1, a quarter random codes everywhere."""
    return mixed(config, count, seed, directed(config), highlights, _spread)


def _rows(c, normal, light, view):
    """Each row of ``normal``, ``light``, ``view`` at n = 1 and at ``n_max``."""
    return vectors_at_shininess_ends(c, {"normal": normal, "light": light, "view": view}, "n", c.n_max)


def extremes(block_name):
    """The conventional Phong unit's extreme rows (Phong 1975 via Lyon 1993 "Background"):
    N = 0; N = L = V (R·V = 1); V = −L (R·V = −1); the light behind with R·V = 1; a grazing
    light with R·V = 1; each at n = 1 and ``n_max``."""
    graze_n, graze_l = perpendicular_pairs()
    z = np.array([0.0, 0, 1])
    return (
        Extreme(block_name, "zero-length N (all-zeros code), n = 1 and n_max", "diffuse = specular = 0",
                lambda c: _rows(c, [[0, 0, 0]], [z], [z]), all_of(zero("diffuse"), zero("specular"))),
        Extreme(block_name, "exactly ±1.0: N = L = V (R·V = 1), n = 1 and n_max",
                "diffuse = specular = 1.0 exactly", lambda c: _rows(c, AXES, AXES, AXES),
                all_of(exactly("diffuse", 1.0), exactly("specular", 1.0))),
        Extreme(block_name, "V = −L = −N (R·V = −1), n = 1 and n_max", "diffuse = 1.0, specular = 0",
                lambda c: _rows(c, AXES, AXES, -AXES), all_of(exactly("diffuse", 1.0), zero("specular"))),
        Extreme(block_name, "light behind: L = V = −N (N·L = −1, R·V = 1), n = 1 and n_max",
                "diffuse = specular = 0 (the backside test)", lambda c: _rows(c, AXES, -AXES, -AXES),
                all_of(zero("diffuse"), zero("specular"))),
        Extreme(block_name, "grazing L (N ⟂ L) and V = −L (R·V = 1), n = 1 and n_max",
                "diffuse = specular = 0 (N·L = 0 is behind)", lambda c: _rows(c, graze_n, graze_l, -graze_l),
                all_of(zero("diffuse"), zero("specular"))),
    )
