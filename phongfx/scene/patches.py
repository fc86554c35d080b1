"""The regions of a scene's meshes: patches of faces, each with the limits its faces present.

A patch is the faces of one object and one material whose normals are nearest one of the twelve
directions of an icosahedron's vertices (Szirmay-Kalos's and Lyon's units see only normals, so
faces that point alike are the ones that share limits).  Per patch, every bound of
:mod:`phongfx.scene.domain` holds with the patch's own faces in place of all of them:

* **Span angle**: the largest pairwise vertex-normal angle of its triangles (180° past 90°).
* **N·V**: every normal a face presents is a normalized positive combination of its vertex
  normals, so within ``ρ`` of the patch's axis ``c`` (the largest vertex-normal angle from
  ``c``, when below 90°) and within ``90° + β`` of the view axis ``z`` (``β`` the patch's
  largest vertex-normal to face-normal angle: the face is drawn only facing the viewer).
  With ``R c·z`` in ``[lo, hi]`` over the pose set (:func:`z_range`: exact for ``"motion"``;
  ``"still"`` each frame's value moved by up to the wobble; ``"any"`` everything), the normal
  is ``θ`` from ``z`` with ``arccos(hi) - ρ <= θ <= min(arccos(lo) + ρ, 90° + β)``, and a
  viewer within ``γ`` of ``z`` widens both ends by ``γ``.  ``n0`` and ``n1`` are such
  combinations too: the same limits hold for them.
* **Ball**: a ball holding the patch's vertices holds its faces.  ``"motion"``: the ball about
  the middle of the box of the vertices turned to :data:`GRID` + 1 angles of the range that
  holds them, widened by the chord ``2 sin(step/4)·|v⊥|`` by which an arc strays from its
  nearest grid angle (``v⊥`` the vertex off the axis); ``"still"``: the same over the frames'
  poses, widened by the wobble's ``2 sin(w/2)·|v|``; ``"any"``, and where the patch's ball
  does not lie inside the domain's, the domain's ball.
* **n**: its material's.

A patch whose faces face the viewer under no pose of the pose set presents nothing and is left
out.  For the sampler, a patch narrows ``"motion"``'s degrees to the hull of the angles (on a
grid of :data:`GRID` steps, widened by one) and ``"still"``'s frames to those under which one of
its faces faces the viewer (unwobbled, when some frame has one: a wobble that turns a face
toward the viewer is too rare a draw).
"""

import math

import numpy as np

from .geometry import rotation, scene_mesh
from .mesh import unit
from .regions import Region
from .sampling import Surface, face_table

__all__ = ["DIRECTIONS", "GRID", "z_range", "mesh_regions"]

_GOLD = (1 + 5 ** 0.5) / 2
#: the twelve patch directions: an icosahedron's vertices
DIRECTIONS = unit(np.array([[s1, s2 * _GOLD, 0] for s1 in (-1, 1) for s2 in (-1, 1)]
                           + [[0, s1, s2 * _GOLD] for s1 in (-1, 1) for s2 in (-1, 1)]
                           + [[s2 * _GOLD, 0, s1] for s1 in (-1, 1) for s2 in (-1, 1)], dtype=np.float64))
#: angles on which a patch's visible poses are looked for (the sampler's narrowing only)
GRID = 256


def _angle(u, w):
    return np.degrees(np.arccos(np.clip(np.sum(u * w, -1), -1.0, 1.0)))


def _coefficients(axis, v):
    """``(A, B, C)`` with ``(R(t) v)·z = A + B cos t + C sin t`` for rotations about ``axis``."""
    u = np.asarray(axis, dtype=np.float64)
    along = v @ u
    return u[2] * along, v[:, 2] - u[2] * along, np.cross(u, v)[:, 2]


def z_range(vectors, pose, axis, degrees, wobble, still):
    """Per row of ``vectors`` (unit, object space), ``(lo, hi)`` of ``(R v)·z`` over the pose set
    (module docstring): ``degrees`` the ``"motion"`` range, ``still`` the frames' angles."""
    v = np.asarray(vectors, dtype=np.float64)
    if pose == "any":
        return -np.ones(len(v)), np.ones(len(v))
    a, b, c = _coefficients(axis, v)
    if pose == "motion":
        lo, hi = np.radians(degrees[0]), np.radians(degrees[1])
        turns = np.arctan2(c, b)[:, None] + np.pi * np.arange(-4, 5)[None, :]  # the extrema
        t = np.concatenate([np.broadcast_to([[lo, hi]], (len(v), 2)), turns], axis=1)
        values = np.where((t >= lo) & (t <= hi), a[:, None] + b[:, None] * np.cos(t) + c[:, None] * np.sin(t),
                          np.nan)
        return np.nanmin(values, axis=1), np.nanmax(values, axis=1)
    t = np.radians(np.asarray(still, dtype=np.float64))[None, :]
    angle = np.arccos(np.clip(a[:, None] + b[:, None] * np.cos(t) + c[:, None] * np.sin(t), -1, 1))
    w = math.radians(wobble)
    return np.cos(np.minimum(np.pi, angle + w)).min(axis=1), np.cos(np.maximum(0.0, angle - w)).max(axis=1)


def _ball(vertices, pose, axis, still, wobble, whole):
    """The patch's ball under the pose set (module docstring), or the domain's ball ``whole``
    when the patch's does not lie inside it (a region is part of the domain); ``still`` the
    frames' angles, or for ``"motion"`` its range."""
    own = _own_ball(vertices, pose, axis, still, wobble, whole)
    inside = np.linalg.norm(np.subtract(own[0], whole[0])) + own[1] <= whole[1]
    return own if inside else whole


def _own_ball(vertices, pose, axis, still, wobble, whole):
    if pose == "any":
        return whole
    if pose == "motion":  # the vertices at GRID angles; an arc strays from its nearest by a chord
        lo, hi = still
        step = math.radians(hi - lo) / GRID
        placed = [vertices @ rotation(axis, t).T for t in np.linspace(lo, hi, GRID + 1)]
        off = np.linalg.norm(vertices - np.outer(vertices @ np.asarray(axis), axis), axis=-1)
        slack = 2 * math.sin(step / 4) * float(np.max(off))
    else:
        placed = [vertices @ rotation(axis, t).T for t in still]
        slack = 2 * math.sin(math.radians(wobble) / 2) * float(np.max(np.linalg.norm(vertices, axis=-1)))
    every = np.concatenate(placed)
    centre = 0.5 * (every.min(axis=0) + every.max(axis=0))
    return tuple(float(x) for x in centre), float(np.max(np.linalg.norm(every - centre, axis=-1))) + slack


def _narrowed(face_normals, pose, axis, degrees, still, wobble):
    """The pose fields the sampler draws the patch from (module docstring), or None when no
    face of the patch faces the viewer under any pose."""
    if np.max(z_range(face_normals, pose, axis, degrees, wobble, still)[1]) <= 0:
        return None
    if pose == "any":
        return ()
    if pose == "still":
        keep = [t for t in still if np.max(z_range(face_normals, pose, axis, degrees, 0.0, (t,))[1]) > 0]
        return (("still_degrees", tuple(keep or [t for t in still if np.max(
            z_range(face_normals, pose, axis, degrees, wobble, (t,))[1]) > 0])),)
    t = np.linspace(np.radians(degrees[0]), np.radians(degrees[1]), GRID + 1)
    a, b, c = _coefficients(axis, face_normals)
    seen = np.any(a[:, None] + b[:, None] * np.cos(t) + c[:, None] * np.sin(t) > 0, axis=0)
    if not np.any(seen):
        return ()
    step = (degrees[1] - degrees[0]) / GRID
    lo, hi = np.degrees(t[np.flatnonzero(seen)[[0, -1]]])
    return (("degrees", (max(degrees[0], float(lo) - step), min(degrees[1], float(hi) + step))),)


def mesh_regions(spec, materials, pose, degrees, wobble, still, tilt, whole_ball, claim=None):
    """The patches of ``spec``'s meshes (module docstring) as :class:`~phongfx.scene.regions.Region`
    records: ``materials`` the domain's, ``tilt`` its ``γ``, ``whole_ball`` its ball;
    ``claim`` a ``[domain]`` ``max_span_angle_deg`` that caps every patch's."""
    mesh, owner = scene_mesh(spec)
    axis = unit(np.asarray(spec.frames.axis, dtype=np.float64)[None])[0]
    tri = mesh.vertices[mesh.faces]
    cross = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    area = np.linalg.norm(cross, axis=-1)
    keep = area > 0
    face_normal = np.zeros_like(cross)
    face_normal[keep] = cross[keep] / area[keep, None]
    normals = unit(mesh.normals)
    names = [name for name, _ in materials]
    material = np.array([names.index(obj.material) for obj in spec.objects])[owner]
    nearest = np.argmax(face_normal @ DIRECTIONS.T, axis=1)
    out = []
    for group in sorted(set(zip(owner[keep].tolist(), material[keep].tolist(), nearest[keep].tolist()))):
        o, m, d = group
        mine = np.flatnonzero(keep & (owner == o) & (material == m) & (nearest == d))
        vn = normals[mesh.faces[mine]]  # (F, 3, 3)
        narrowed = _narrowed(face_normal[mine], pose, axis, degrees, still, wobble)
        if narrowed is None:
            continue
        pair = max(float(np.max(_angle(vn[:, i], vn[:, (i + 1) % 3]))) for i in range(3))
        span = pair if pair <= 90.0 else 180.0
        span = span if claim is None else min(span, claim)
        cap = max(float(np.max(_angle(vn[:, i], face_normal[mine]))) for i in range(3))
        centre = unit(np.sum(vn.reshape(-1, 3), axis=0)[None])[0]
        rho = float(np.max(_angle(vn.reshape(-1, 3), centre[None])))
        z_lo, z_hi = (float(x[0]) for x in z_range(centre[None], pose, axis, degrees, wobble, still))
        far = 90.0 + cap if cap <= 90.0 else 180.0
        if rho < 90.0:
            far = min(far, math.degrees(math.acos(z_lo)) + rho)
        near = max(0.0, math.degrees(math.acos(z_hi)) - rho) if rho < 90.0 else 0.0
        cos_min = math.cos(math.radians(min(180.0, far + tilt)))
        cos_max = math.cos(math.radians(max(0.0, near - tilt)))
        table = face_table(mesh.vertices, normals, mesh.faces[mine], face_normal[mine], area[mine])
        own = tuple((name, values if i == m else ()) for i, (name, values) in enumerate(materials))
        vertices = mesh.vertices[np.unique(mesh.faces[mine])]
        out.append(Region(
            f"{spec.objects[o].kind} {o} ({names[m]}), faces toward ({', '.join(f'{x:.2f}' for x in DIRECTIONS[d])})",
            own, cos_min, cos_max, (cos_min, cos_max), span,
            _ball(vertices, pose, axis, degrees if pose == "motion" else still, wobble, whole_ball),
            {"object": o, "faces": int(len(mine)), "axis": [round(float(x), 4) for x in centre],
             "cone_deg": round(rho, 4)},
            Surface(False, tables=tuple(table if i == m else None for i in range(len(materials)))), narrowed))
    return tuple(out)
