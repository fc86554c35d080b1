"""Stimulus for the Blinn–Phong baseline: axis and zero normals, the shortest
nonzero ``N``, ``t = 1`` exactly, backfacing ``H``, edge ``n``, then random highlights."""

import numpy as np

from . import AXES, at_angle, axis_pairs, codes, concat, perpendicular_pairs, random_codes, rng, unit_vectors
from .extreme import Extreme, all_of, exactly, vectors_at_shininess_ends, zero

__all__ = ["stimulus", "mixed", "directed", "edge_n", "highlights", "extremes"]


def edge_n(config):
    """Shininess values every directed vector is tried with: 1, 2, 8, 64, 500, ``n_max - 1``,
    ``n_max`` (those the range holds)."""
    return np.array(sorted({n for n in (1, 2, 8, 64, 500, config.n_max - 1, config.n_max)
                            if 1 <= n <= config.n_max}), dtype=np.int64)


def directed(config):
    """Raw ``normal``, ``light``, ``half`` rows, each with every :func:`edge_n`.

    * every ordered pair of unit axes as ``N`` and ``H`` (``t = 1``, ``0`` at 90°, ``N·H = -1``),
      ``L`` the second of the pair too; the same with ``N`` halved (``|N| = 1/2``, ``t = 1``);
    * ``N = 0`` (``q = 0``) and the shortest nonzero ``N``: one LSB on an axis, on all three,
      and one negative LSB;
    * the longest codes (``N`` components at the format's ends: junk, saturating paths).
    """
    vec = config.fmt("vec")
    first, second = axis_pairs()
    lsb = vec.lsb
    tiny = np.array([[lsb, 0, 0], [0, 0, -lsb], [lsb, lsb, lsb], [-lsb, lsb, 0]])
    # the tiny normals light from +X and see H along themselves (t = 1)
    along = tiny / np.linalg.norm(tiny, axis=-1, keepdims=True)
    normals = np.concatenate([first, first / 2, np.zeros((1, 3)), tiny])
    lights = np.concatenate([second, second, AXES[:1], np.tile(AXES[:1], (len(tiny), 1))])
    halves = np.concatenate([second, second, AXES[:1], along])
    rows = {"normal": codes(normals, vec), "light": codes(lights, vec), "half": codes(halves, vec)}
    ends = np.array([[vec.min_raw] * 3, [vec.max_raw] * 3, [vec.min_raw, vec.max_raw, 0]])
    rows = concat(rows, {"normal": ends, "light": ends, "half": ends[::-1]})
    ns = edge_n(config)
    count = len(rows["normal"])
    out = {name: np.repeat(value, len(ns), axis=0) for name, value in rows.items()}
    out["n"] = np.tile(ns, count)
    return out


def highlights(config, count, generator):
    """``count`` rows near the highlight: ``N`` unit times ``|N|`` in ``[0.5, 1]``, ``H`` at an
    angle up to ``4/sqrt(n)`` from ``N`` (where ``t^n`` is not yet 0), ``L`` random unit,
    ``n`` log-uniform in ``1..n_max``."""
    vec = config.fmt("vec")
    n = np.exp(generator.uniform(0, np.log(config.n_max), count)).round().astype(np.int64)
    n = np.clip(n, 1, config.n_max)
    alpha = generator.uniform(0, 1, count) * np.minimum(4 / np.sqrt(n), np.pi)
    h, unit_n = at_angle(alpha, generator)
    normal = unit_n * generator.uniform(0.5, 1.0, (count, 1))
    return {"normal": codes(normal, vec), "light": codes(unit_vectors(count, generator), vec),
            "half": codes(h, vec), "n": n}


def mixed(config, count, seed, directed_rows, highlights, spread):
    """Raw codes of a baseline unit (this one's or the Phong unit's): ``directed_rows``, then
    ``count`` random: half ``highlights(config, count, generator)``, a quarter
    ``spread(config, count, generator)`` (raw vector codes by port) with random ``n``, a
    quarter random codes on every port.  The generator is drawn in that order: spread,
    the junk quarter, then the highlights."""
    vec, g = config.fmt("vec"), rng(seed)
    half, quarter = count // 2, count // 4
    rest = count - half - quarter
    rows = spread(config, quarter, g)
    rows["n"] = random_codes(config.fmt("n"), quarter, g, 1, config.n_max)
    junk = {name: random_codes(vec, (rest, 3), g) for name in rows if name != "n"}
    junk["n"] = random_codes(config.fmt("n"), rest, g, 1, config.n_max)
    return concat(directed_rows, highlights(config, half, g), rows, junk)


def _spread(config, count, g):
    vec = config.fmt("vec")
    return {"normal": codes(unit_vectors(count, g) * g.uniform(0.5, 1, (count, 1)), vec),
            "light": codes(unit_vectors(count, g), vec), "half": codes(unit_vectors(count, g), vec)}


def stimulus(config, count=1000, seed=0):
    """Raw codes (:func:`mixed`): :func:`directed`, then ``count`` random: half
    :func:`highlights`, a quarter random unit ``L``, ``H`` and ``N`` of length 0.5..1, a
    quarter random codes everywhere."""
    return mixed(config, count, seed, directed(config), highlights, _spread)


def _rows(c, normal, light, half):
    """Each row of ``normal``, ``light``, ``half`` at n = 1 and at ``n_max``."""
    return vectors_at_shininess_ends(c, {"normal": normal, "light": light, "half": half}, "n", c.n_max)


def extremes(block_name):
    """The Blinn–Phong baseline's extreme rows (Lyon 1993 "Background"): N = 0, N = L = H,
    N·H = −1 with a grazing light, at n = 1 and ``n_max``."""
    graze_n, graze_l = perpendicular_pairs()
    z = np.array([0.0, 0, 1])
    return (
        Extreme(block_name, "zero-length N (all-zeros code), n = 1 and n_max", "diffuse = specular = 0",
                lambda c: _rows(c, [[0, 0, 0]], [z], [z]), all_of(zero("diffuse"), zero("specular"))),
        Extreme(block_name, "exactly ±1.0: N = L = H, n = 1 and n_max", "diffuse = specular = 1.0 exactly",
                lambda c: _rows(c, AXES, AXES, AXES),
                all_of(exactly("diffuse", 1.0), exactly("specular", 1.0))),
        Extreme(block_name, "N·H = −1 and grazing L (N ⟂ L), n = 1 and n_max", "diffuse = specular = 0",
                lambda c: _rows(c, graze_n, graze_l, -graze_n), all_of(zero("diffuse"), zero("specular"))),
    )
