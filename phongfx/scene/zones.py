"""Unit vectors drawn on the sphere, in its caps and zones, points in a ball and span ends
(:mod:`phongfx.scene.sampling` draws a domain's points from them), and the span ends of a
region of Lyon's spheres drawn about the pixel's normal (:mod:`phongfx.scene.regions`)."""

import numpy as np

from .mesh import unit

__all__ = ["BAND_ROUNDS", "cap", "directions", "in_ball", "span_end", "band_points", "facing_draw"]

#: redraws of a band's span ends before the few points left take a one-normal span (a normal
#: at the limb keeps few wide spans with both ends on the front hemisphere: more rounds cost
#: more than the points they place)
BAND_ROUNDS = 12


def cap(centre, degrees, rng, cos_max=1.0):
    """(P, 3) unit vectors uniform (by area) in the caps of half-angle ``degrees`` about the
    unit rows of ``centre``; ``cos_max`` < 1: in the zone of the cap outside the angle
    ``acos(cos_max)``."""
    count = len(centre)
    cos = rng.uniform(np.cos(np.radians(degrees)), cos_max, count)
    sin = np.sqrt(np.maximum(1 - cos * cos, 0.0))
    phi = rng.uniform(0, 2 * np.pi, count)
    u, v = sin * np.cos(phi), sin * np.sin(phi)
    # a tangent basis without branches (Duff et al., "Building an Orthonormal Basis, Revisited")
    x, y, z = centre[:, 0], centre[:, 1], centre[:, 2]
    sign = np.where(z >= 0, 1.0, -1.0)
    a = -1.0 / (sign + z)
    b = x * y * a
    out = np.empty((count, 3))
    out[:, 0] = cos * x + u * (1 + sign * x * x * a) + v * b
    out[:, 1] = cos * y + u * (sign * b) + v * (sign + y * y * a)
    out[:, 2] = cos * z - u * (sign * x) - v * y
    return out


def directions(rng, count):
    """(count, 3) uniform unit vectors (z uniform in [-1, 1]: Archimedes' hat-box theorem)."""
    z = rng.uniform(-1.0, 1.0, count)
    phi = rng.uniform(0.0, 2 * np.pi, count)
    rho = np.sqrt(1 - z * z)
    out = np.empty((count, 3))
    out[:, 0], out[:, 1], out[:, 2] = rho * np.cos(phi), rho * np.sin(phi), z
    return out


def in_ball(domain, rng, count):
    """(count, 3) points uniform in the domain's ball."""
    centre, radius = np.asarray(domain.ball[0]), domain.ball[1]
    return centre + directions(rng, count) * (radius * np.cbrt(rng.random(count)))[:, None]


def span_end(domain, x0, rng):
    """``x0 + d·u``: ``u`` uniform in the eye-space xz plane (spans are horizontal),
    ``d`` uniform in [-max_span_length, max_span_length] cut to stay in the ball."""
    count = len(x0)
    psi = rng.uniform(0, 2 * np.pi, count)
    cos, sin = np.cos(psi), np.sin(psi)
    rel = x0 - np.asarray(domain.ball[0])
    b = rel[:, 0] * cos + rel[:, 2] * sin
    root = np.sqrt(np.maximum(b * b - (np.einsum("ij,ij->i", rel, rel) - domain.ball[1] ** 2), 0.0))
    lo = np.maximum(-domain.max_span_length, np.minimum(-b - root, 0.0))
    hi = np.minimum(domain.max_span_length, np.maximum(-b + root, 0.0))
    d = lo + (hi - lo) * rng.random(count)
    x1 = x0.copy()
    x1[:, 0] += d * cos
    x1[:, 2] += d * sin
    return x1


def band_points(domain, a, rng):
    """``(n0, n1, N)`` of a region of Lyon's spheres (:mod:`phongfx.scene.regions`), the pixel's
    normal first: ``N`` uniform in the region's zone of ``N·V``, span ends ``t`` apart (uniform
    by area in the cap of the region's span angle: wide spans, the hard ones, are favoured)
    along a uniform direction ``d`` about ``N``, placed so that ``unit((1-a)n0 + a·n1) = N``:
    ``n0`` at ``atan2(a·sin t, 1 - a + a·cos t)`` from ``N``.  Ends outside the region's
    ``ends_cos`` are redrawn; after the last round the few left take ``t = 0``."""
    count = len(a)
    view = np.broadcast_to(np.asarray(domain.camera[1], dtype=np.float64), (count, 3))
    normal = cap(view, np.degrees(np.arccos(np.clip(domain.view_cos_min, -1, 1))), rng, domain.view_cos_max)
    n0, n1 = normal.copy(), normal.copy()
    pending = np.arange(count)
    lo, hi = domain.ends_cos
    for _ in range(BAND_ROUNDS):
        if not len(pending):
            break
        t = np.arccos(rng.uniform(np.cos(np.radians(domain.max_span_angle_deg)), 1.0, len(pending)))
        side = cap(normal[pending], 90.0, rng)
        d = unit(side - np.einsum("ij,ij->i", side, normal[pending])[:, None] * normal[pending])
        w = a[pending]
        start = np.arctan2(w * np.sin(t), 1 - w + w * np.cos(t))
        got0 = np.cos(start)[:, None] * normal[pending] - np.sin(start)[:, None] * d
        got1 = np.cos(t - start)[:, None] * normal[pending] + np.sin(t - start)[:, None] * d
        ok = np.ones(len(pending), dtype=bool)
        for end in (got0, got1):
            ok &= (end @ view[0] >= lo) & (end @ view[0] <= hi)
        n0[pending[ok]], n1[pending[ok]] = got0[ok], got1[ok]
        pending = pending[~ok]
    return n0, n1, normal


def facing_draw(face_normals, toward, local, pending, group, rng):
    """For the ``pending`` points (indices; point ``p`` has the pose ``toward[p // group]``, the
    eye-space z of its rotation, under which its face draws kept facing away), a face uniformly
    among the ``face_normals`` (F, 3) that face the viewer under that pose, written into
    ``local``; returns the points whose pose has no such face."""
    groups = pending // group
    unique, column = np.unique(groups, return_inverse=True)
    facing = face_normals @ toward[unique].T > 0  # (F, U)
    total = facing.sum(axis=0)[column]
    ok = total > 0
    k = (rng.random(len(pending)) * np.maximum(total, 1)).astype(np.int64)
    local[pending[ok]] = np.argmax(np.cumsum(facing, axis=0)[:, column[ok]] > k[ok][None, :], axis=0)
    return pending[~ok]
