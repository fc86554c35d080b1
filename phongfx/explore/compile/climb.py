"""Local search for a design's worst input: hill-climbing within the scene's domain.

A random sample finds a design's bad region; its worst point is rarely the worst of that
region, because the error is a staircase of roundings over a few continuous inputs.  From
each of the worst sampled points, :func:`climb` perturbs the inputs a design is fed per
pixel, all in one batch: the span-end normals ``n0``, ``n1``, the span position ``a``, the
surface point and the span's extent (which move a point light's and a local viewer's
unit vectors), and ``n`` among its material's admissible values; it keeps a move that
raises the continuous error ``|out - (2^bits - 1)·I_ref|`` (worst channel), whose steps the
integer error follows, and adapts each start's step (larger after a success, smaller after
a failure, the 1/5th-rule's spirit).  Every candidate stays inside the domain
(:class:`phongfx.scene.domain.Domain`): span-end normals at most ``max_span_angle_deg``
apart and facing the viewer (``N·V >= view_cos_min`` at both ends), surface points and span
ends inside its ``ball``, spans at most ``max_span_length`` long; a candidate outside is
discarded.

A point is a :class:`State` (arrays, one row per point): the span's ends are ``x0 = p -
a·d`` and ``x1 = p + (1 - a)·d`` about the surface point ``p``; :func:`points` turns a
state into the :class:`~phongfx.scene.geometry.FrameGeometry` the shader is fed.
"""

from dataclasses import dataclass, replace

import numpy as np

from phongfx.scene.geometry import FrameGeometry
from phongfx.scene.mesh import unit
from phongfx.scene.regions import holds
from phongfx.scene.sampling import CHUNK

__all__ = ["State", "state_of", "points", "inside", "errors", "perturb", "climb", "neighbourhood"]


@dataclass
class State:
    """Domain points as the local search moves them (module docstring), one row each."""
    n0: np.ndarray        # (K, 3) unit
    n1: np.ndarray        # (K, 3) unit
    a: np.ndarray         # (K,)
    p: np.ndarray         # (K, 3) surface point
    d: np.ndarray         # (K, 3) span end minus span start (horizontal: no eye-space y)
    eye: np.ndarray       # (K, 3) a local viewer's position (its camera path's point), else zeros
    n_index: np.ndarray   # (K,) index into the material's admissible n values
    material: np.ndarray  # (K,) int64
    kd: np.ndarray
    ks: np.ndarray
    ka: np.ndarray
    colour: np.ndarray    # (K, 3)

    def rows(self, index):
        return State(*(np.asarray(getattr(self, f))[index] for f in self.__dataclass_fields__))

    def __len__(self):
        return len(self.a)


def _local(domain):
    """Whether a point light or a local viewer makes the span's ends matter."""
    return domain.camera[0] == "point" or any(kind == "point" for kind, *_ in domain.lights)


def _values(domain):
    return [np.asarray(values, dtype=np.int64) for _, values in domain.materials]


def _eyes(g, domain):
    """(K, 3) per point, the local viewer's position that explains its ``viewer`` best (a
    camera path's point), or zeros for a camera at infinity."""
    if domain.camera[0] != "point":
        return np.zeros((len(g.a), 3))
    path = np.asarray(domain.camera_path or (domain.camera[1],), dtype=np.float64)
    fit = np.stack([np.sum(unit(c - g.position) * g.viewer, -1) for c in path], -1)
    return path[np.argmax(fit, axis=-1)]


def state_of(g, domain):
    """The :class:`State` of the domain points ``g``: the span's extent from the first
    point light, else the local viewer (the span start on its ray nearest the surface point)."""
    a = np.asarray(g.a, dtype=np.float64)
    p = np.asarray(g.position, dtype=np.float64)
    eye = _eyes(g, domain)
    d = np.zeros_like(p)
    point = [k for k, (kind, *_) in enumerate(domain.lights) if kind == "point"]
    if _local(domain):
        source, toward = ((np.asarray(domain.lights[point[0]][1], dtype=np.float64), np.asarray(g.l0[point[0]]))
                          if point else (eye, np.asarray(g.v0)))
        x0 = source - np.sum((source - p) * toward, -1, keepdims=True) * toward
        d = np.where(a[:, None] > 1e-3, (p - x0) / np.maximum(a, 1e-3)[:, None], 0.0)
        d[:, 1] = 0.0
        length = np.linalg.norm(d, axis=-1, keepdims=True)
        d = np.where(length > domain.max_span_length, d * domain.max_span_length / np.maximum(length, 1e-300), d)
    values = _values(domain)
    material = np.asarray(g.material, dtype=np.int64)
    n = np.round(g.n).astype(np.int64)
    n_index = np.array([int(np.searchsorted(values[m], v)) for m, v in zip(material, n)], dtype=np.int64)
    return State(np.asarray(g.n0, float), np.asarray(g.n1, float), a, p, d, eye, n_index, material,
                 np.asarray(g.kd, float), np.asarray(g.ks, float), np.asarray(g.ka, float),
                 np.asarray(g.colour, float))


def _toward(kind, vector, x):
    if kind in ("directional", "infinity"):
        v = np.asarray(vector, dtype=np.float64)
        return np.broadcast_to(v / np.linalg.norm(v), x.shape).copy()
    return unit(np.asarray(vector, dtype=np.float64) - x)


def points(s, domain, rgb, bits):
    """The :class:`FrameGeometry` (one pixel per span) the shader is fed at the state ``s``."""
    a = s.a[:, None]
    x0, x1 = s.p - a * s.d, s.p + (1 - a) * s.d
    ends = (x0, x1, s.p)
    lights = [[_toward(kind, vector, x) for x in ends] for kind, vector, *_ in domain.lights]
    l0, l1, light = (np.stack([v[k] for v in lights]) for k in range(3))
    if domain.camera[0] == "point":
        v0, v1, viewer = (unit(s.eye - x) for x in ends)
    else:
        v0, v1, viewer = (_toward(domain.camera[0], domain.camera[1], x) for x in ends)
    values = _values(domain)
    n = np.array([values[m][i] for m, i in zip(s.material, s.n_index)], dtype=np.float64)
    count = len(s)
    zeros = np.zeros(count, dtype=np.int64)
    return FrameGeometry(0, 0, zeros, zeros, np.arange(count), s.a, s.n0, s.n1, unit((1 - a) * s.n0 + a * s.n1),
                         s.p, l0, l1, light, v0, v1, viewer, np.asarray(rgb, dtype=np.float64), n, s.kd, s.ks,
                         s.ka, s.colour, s.material, None, -1, bits)


def inside(s, g, domain):
    """(K,) bool: the points of state ``s`` (fed as ``g = points(s, ...)``) lie in the domain:
    span-end normals within its span angle, every normal (``n0``, ``n1``, ``N``) facing every
    viewer vector of the span (``>= view_cos_min``), surface point and span ends in its ball,
    the span no longer than its longest, and in one of the domain's regions when it has them."""
    ok = np.sum(s.n0 * s.n1, -1) >= np.cos(np.radians(domain.max_span_angle_deg)) - 1e-12
    if domain.view_cos_min > -1:
        for n in (s.n0, s.n1, g.normal):
            for v in (g.v0, g.v1, g.viewer):
                ok &= np.sum(n * v, -1) >= domain.view_cos_min
    centre, radius = np.asarray(domain.ball[0], dtype=np.float64), domain.ball[1]
    a = s.a[:, None]
    for x in (s.p, s.p - a * s.d, s.p + (1 - a) * s.d):
        ok &= np.linalg.norm(x - centre, axis=-1) <= radius
    if domain.regions:  # and in one of the domain's regions, each tighter than the whole
        ok &= holds(domain.regions, s.n0, s.n1, g.normal, (g.v0, g.v1, g.viewer), s.material, g.n,
                    (s.p, s.p - a * s.d, s.p + (1 - a) * s.d))
    return ok & (np.linalg.norm(s.d, axis=-1) <= domain.max_span_length)


def errors(evaluate, s, domain, rgb, bits):
    """``(levels, unrounded)`` (K,) each of the state ``s`` by ``evaluate`` (``g -> (levels,
    unrounded)``), a chunk of points at a time; ``unrounded`` is ``-inf`` where a point lies
    outside the domain (:func:`inside`)."""
    levels, unrounded = [], []
    for lo in range(0, len(s), CHUNK):
        part = s.rows(np.arange(lo, min(lo + CHUNK, len(s))))
        g = points(part, domain, rgb, bits)
        e, u = evaluate(g)
        levels.append(e)
        unrounded.append(np.where(inside(part, g, domain), u, -np.inf))
    return np.concatenate(levels), np.concatenate(unrounded)


def perturb(s, sigma, rng, domain):
    """A random neighbour of each row of ``s``, at relative step ``sigma`` (K,)."""
    k, step = len(s), sigma[:, None]
    n0 = unit(s.n0 + step * rng.normal(size=(k, 3)))
    n1 = unit(s.n1 + step * rng.normal(size=(k, 3)))
    a = np.clip(s.a + sigma * rng.normal(size=k), 0.0, 1.0)
    p, d = s.p, s.d
    if _local(domain):  # positions matter only toward a point light or a local viewer
        p = p + step * domain.ball[1] * rng.normal(size=(k, 3))
        d = d + step * domain.max_span_length * rng.normal(size=(k, 3)) * [1.0, 0.0, 1.0]
    top = np.array([len(v) - 1 for v in _values(domain)])[s.material]
    jump = np.where(rng.random(k) < 0.25, rng.integers(-1, 2, size=k), 0)
    return replace(s, n0=n0, n1=n1, a=a, p=p, d=d, n_index=np.clip(s.n_index + jump, 0, top))


def climb(evaluate, start, domain, rgb, bits, rng, *, rounds=40, batch=32, sigma=0.05):
    """Hill-climb from every row of ``start`` (module docstring).

    :param evaluate: ``g -> (levels, unrounded)``, each (P,): the error of the points ``g``.
    :returns: ``(best, ends, evaluated)``: ``best`` the worst point found ``(levels,
        unrounded, state)`` (one row; by integer error, ties by the continuous one), ``ends``
        where each start's climb ended ``(levels, unrounded, state)`` (one row each) and how
        many points were evaluated.
    """
    cur_e, cur_u = errors(evaluate, start, domain, rgb, bits)
    best = _best(start, cur_e, cur_u, cur_u > -np.inf)
    steps, evaluated, count = np.full(len(start), float(sigma)), len(start), len(start)
    current, every = start, np.arange(len(start))
    for _ in range(rounds):
        rows = np.repeat(every, batch)
        candidates = perturb(current.rows(rows), steps[rows], rng, domain)
        e, u = errors(evaluate, candidates, domain, rgb, bits)
        evaluated += len(rows)
        best = max(best, _best(candidates, e, u, u > -np.inf), key=lambda b: b[:2])
        u = u.reshape(count, batch)
        pick = np.argmax(u, axis=1)
        gain = u[every, pick] > cur_u
        chosen = every * batch + pick
        moved = current.rows(every)
        for name in moved.__dataclass_fields__:
            getattr(moved, name)[gain] = getattr(candidates, name)[chosen[gain]]
        cur_u = np.where(gain, u[every, pick], cur_u)
        cur_e = np.where(gain, e[chosen], cur_e)
        steps = np.clip(np.where(gain, steps * 1.5, steps * 0.6), 1e-7, 0.5)
        current = moved
    return best, (cur_e, cur_u, current), evaluated


def _best(s, levels, unrounded, ok):
    """``(levels, unrounded, state row)`` of the worst point of ``s`` in the domain."""
    if not np.any(ok):
        return (-1, -np.inf, None)
    index = np.flatnonzero(ok)
    worst = index[np.lexsort((unrounded[index], levels[index]))[-1]]
    return (int(levels[worst]), float(unrounded[worst]), s.rows([worst]))


def neighbourhood(s, domain, rgb, bits, count, rng, sigma=0.02):
    """The points of ``s`` (one row) and ``count - 1`` random neighbours of it in the domain,
    at steps up to ``sigma``: the hard points a failed witness adds to the search."""
    rows = np.zeros(4 * count, dtype=np.int64)
    candidates = perturb(s.rows(rows), sigma * rng.random(len(rows)), rng, domain)
    ok = np.flatnonzero(inside(candidates, points(candidates, domain, rgb, bits), domain))[:count - 1]
    both = s.rows(np.r_[0, np.zeros(len(ok), dtype=np.int64)])
    for name in both.__dataclass_fields__:
        getattr(both, name)[1:] = getattr(candidates, name)[ok]
    return points(both, domain, rgb, bits)
