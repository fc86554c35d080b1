"""Random points of a scene's input domain (:class:`phongfx.scene.domain.Domain`).

:func:`sample_chunk` draws one chunk of points with the distribution that
:mod:`phongfx.scene.domain`'s docstring states, as plain arrays; ``Domain.sample`` and
``Domain.chunks`` seed it per chunk and wrap the arrays in a
:class:`~phongfx.scene.geometry.FrameGeometry`.  Everything is vectorized numpy; a point
that breaks a bound of the domain (a back-facing pose, an ``n1`` or ``N`` below
``view_cos_min``) is redrawn, so every point drawn lies in the domain.
"""

import numpy as np

from .mesh import unit

__all__ = ["ENDS", "sample_chunk", "rotations", "random_poses", "cap"]

#: fraction of points with ``a`` exactly 0, and again exactly 1 (the span's end pixels)
ENDS = 0.02
_ROUNDS = 200  # redraws before a bound is declared unreachable (each keeps about half or more)


def rotations(axes, radians):
    """(P, 3, 3) rotations by ``radians`` (P,) about the unit ``axes`` (P, 3) (Rodrigues)."""
    axes = np.broadcast_to(np.asarray(axes, dtype=np.float64), (len(radians), 3))
    c, s = np.cos(radians)[:, None, None], np.sin(radians)[:, None, None]
    x, y, z = axes[:, 0], axes[:, 1], axes[:, 2]
    zero = np.zeros_like(x)
    cross = np.stack([np.stack([zero, -z, y], -1), np.stack([z, zero, -x], -1),
                      np.stack([-y, x, zero], -1)], 1)
    return c * np.eye(3) + s * cross + (1 - c) * axes[:, :, None] * axes[:, None, :]


def _directions(rng, count):
    return unit(rng.standard_normal((count, 3)))


def random_poses(domain, count, rng):
    """(count, 3, 3) rotations drawn from the domain's pose set (module docstring of
    :mod:`phongfx.scene.domain`)."""
    if domain.pose == "motion":
        lo, hi = domain.degrees
        return rotations(domain.axis, np.radians(rng.uniform(lo, hi, count)))
    if domain.pose == "any":  # a uniform unit quaternion is a uniform (Haar) rotation
        w, x, y, z = unit(rng.standard_normal((count, 4))).T
        return np.stack([np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], -1),
                         np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], -1),
                         np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], -1)], 1)
    frame = np.radians(np.asarray(domain.still_degrees))[rng.integers(len(domain.still_degrees), size=count)]
    base = rotations(domain.axis, frame)
    # Haar measure restricted to angles <= wobble: density of the angle ∝ 1 - cos θ
    top = np.radians(domain.wobble_degrees)
    grid = np.linspace(0.0, top, 1025)
    cdf = grid - np.sin(grid)
    angle = np.interp(rng.random(count) * cdf[-1], cdf, grid) if top > 0 else np.zeros(count)
    return rotations(_directions(rng, count), angle) @ base


def cap(centre, degrees, rng):
    """(P, 3) unit vectors uniform (by area) in the caps of half-angle ``degrees`` about the
    unit rows of ``centre``."""
    count = len(centre)
    cos = rng.uniform(np.cos(np.radians(degrees)), 1.0, count)
    sin = np.sqrt(np.maximum(1 - cos * cos, 0.0))
    phi = rng.uniform(0, 2 * np.pi, count)
    helper = np.where((np.abs(centre[:, 0]) < 0.9)[:, None], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0])
    b1 = unit(np.cross(centre, helper))
    b2 = np.cross(centre, b1)
    return (cos[:, None] * centre + (sin * np.cos(phi))[:, None] * b1
            + (sin * np.sin(phi))[:, None] * b2)


def _rotate(r, v):
    return np.einsum("pij,pj->pi", r, v)


def _mesh_points(domain, material, rng):
    """(n0, surface point) of area-weighted faces of each point's material under random poses,
    redrawn until the turned face faces the viewer."""
    s = domain.surface
    count = len(material)
    n0, point = np.empty((count, 3)), np.empty((count, 3))
    pending = np.arange(count)
    for _ in range(_ROUNDS):
        if not len(pending):
            return n0, point
        face = np.empty(len(pending), dtype=np.int64)
        for m in np.unique(material[pending]):
            mine = material[pending] == m
            faces = np.flatnonzero(s.material == m)
            weight = np.cumsum(s.areas[faces])
            pick = np.searchsorted(weight, rng.random(int(mine.sum())) * weight[-1], side="right")
            face[mine] = faces[np.minimum(pick, len(faces) - 1)]
        r1, r2 = np.sqrt(rng.random(len(pending))), rng.random(len(pending))
        bary = np.stack([1 - r1, r1 * (1 - r2), r1 * r2], -1)[:, :, None]
        corners = s.faces[face]
        pose = random_poses(domain, len(pending), rng)
        front = _rotate(pose, s.face_normals[face])[:, 2] > 0
        n0[pending] = _rotate(pose, unit(np.sum(bary * s.normals[corners], 1)))
        point[pending] = _rotate(pose, np.sum(bary * s.vertices[corners], 1))
        pending = pending[~front]
    raise ValueError(f"no face of the scene faces the viewer under pose {domain.pose!r}; the domain is empty")


def _lyon_points(domain, rng, count):
    """(sphere index, n0 uniform on the front hemisphere, surface point) of Lyon's spheres."""
    sphere = rng.integers(len(domain.surface.shininess), size=count)
    z = rng.random(count)
    phi = rng.uniform(0, 2 * np.pi, count)
    rho = np.sqrt(1 - z * z)
    n0 = np.stack([rho * np.cos(phi), rho * np.sin(phi), z], -1)
    return sphere, n0, n0 + np.stack([sphere, np.zeros(count), np.zeros(count)], -1)


def _in_ball(domain, rng, count):
    centre, radius = np.asarray(domain.ball[0]), domain.ball[1]
    return centre + _directions(rng, count) * (radius * np.cbrt(rng.random(count)))[:, None]


def _span_end(domain, x0, rng):
    """``x0 + d·u``: ``u`` uniform in the eye-space xz plane (spans are horizontal),
    ``d`` uniform in [-max_span_length, max_span_length] cut to stay in the ball."""
    count = len(x0)
    psi = rng.uniform(0, 2 * np.pi, count)
    u = np.stack([np.cos(psi), np.zeros(count), np.sin(psi)], -1)
    rel = x0 - np.asarray(domain.ball[0])
    b = np.sum(rel * u, -1)
    root = np.sqrt(np.maximum(b * b - (np.sum(rel * rel, -1) - domain.ball[1] ** 2), 0.0))
    lo = np.maximum(-domain.max_span_length, np.minimum(-b - root, 0.0))
    hi = np.minimum(domain.max_span_length, np.maximum(-b + root, 0.0))
    return x0 + (lo + (hi - lo) * rng.random(count))[:, None] * u


def _toward(kind, vector, points):
    if kind in ("directional", "infinity"):
        return [np.broadcast_to(np.asarray(vector, dtype=np.float64), p.shape) for p in points]
    return [unit(np.asarray(vector) - p) for p in points]


def _second_normal(domain, n0, a, views, rng):
    """``(n1, N)``: ``n1`` uniform in the cap of the span angle about ``n0``, redrawn while it
    or ``N = unit((1-a)n0 + a·n1)`` meets some viewer vector below ``view_cos_min``; after
    the last round the few left take ``n1 = n0`` (a one-normal span, in the domain)."""
    n1 = n0.copy()
    pending = np.arange(len(n0))
    for _ in range(_ROUNDS):
        if not len(pending):
            break
        got = cap(n0[pending], domain.max_span_angle_deg, rng)
        normal = unit((1 - a[pending, None]) * n0[pending] + a[pending, None] * got)
        ok = np.ones(len(pending), dtype=bool)
        if domain.view_cos_min > -1:
            for v in views:
                for n in (got, normal):
                    ok &= np.sum(n * v[pending], -1) >= domain.view_cos_min
        n1[pending[ok]] = got[ok]
        pending = pending[~ok]
    a = a[:, None]
    return n1, unit((1 - a) * n0 + a * n1)


def sample_chunk(domain, count, rng):
    """``{name: array}`` of ``count`` domain points, the fields of a
    :class:`~phongfx.scene.geometry.FrameGeometry` that vary (``l0``, ``l1``, ``light`` are
    (lights, count, 3); fixed directions are read-only broadcasts)."""
    used = np.array([i for i, (_, values) in enumerate(domain.materials) if values], dtype=np.int64)
    if not len(used):
        raise ValueError("no material admits an n: the domain is empty")
    if domain.surface.lyon:
        sphere, n0, surface = _lyon_points(domain, rng, count)
        material = np.full(count, used[0])
        n = np.asarray(domain.surface.shininess, dtype=np.float64)[sphere]
    else:
        material = used[rng.integers(len(used), size=count)]
        n = np.empty(count)
        for m in used:
            mine = material == m
            values = np.asarray(domain.materials[m][1], dtype=np.float64)
            n[mine] = values[rng.integers(len(values), size=int(mine.sum()))]
        n0, surface = _mesh_points(domain, material, rng)
    x0 = np.where((rng.random(count) < 0.5)[:, None], surface, _in_ball(domain, rng, count))
    x1 = _span_end(domain, x0, rng)
    draw = rng.random(count)
    a = np.where(draw < ENDS, 0.0, np.where(draw >= 1 - ENDS, 1.0, rng.random(count)))
    position = (1 - a)[:, None] * x0 + a[:, None] * x1
    points = (x0, x1, position)
    if domain.camera_path:
        path = np.asarray(domain.camera_path)
        views = _toward("point", path[rng.integers(len(path), size=count)], points)
    else:
        views = _toward(domain.camera[0], domain.camera[1], points)
    n1, normal = _second_normal(domain, n0, a, views, rng)
    if all(kind == "directional" for kind, _, _ in domain.lights):
        fixed = np.array([vector for _, vector, _ in domain.lights], dtype=np.float64)[:, None, :]
        l0 = l1 = light = np.broadcast_to(fixed, (len(domain.lights), count, 3))
    else:
        lights = [_toward(kind, vector, points) for kind, vector, _ in domain.lights]
        l0, l1, light = (np.stack([v[k] for v in lights]) for k in range(3))
    kd, ks, ka, colour = (np.asarray(c, dtype=np.float64)[material] for c in zip(*domain.coefficients))
    return {"a": a, "n0": n0, "n1": n1, "normal": normal, "position": position, "l0": l0, "l1": l1,
            "light": light, "v0": views[0], "v1": views[1], "viewer": views[2], "n": n, "kd": kd,
            "ks": ks, "ka": ka, "colour": colour.reshape(-1, 3), "material": material}
