"""Random points of a scene's input domain (:class:`phongfx.scene.domain.Domain`).

:func:`sample_chunk` draws one chunk of points with the distribution that
:mod:`phongfx.scene.domain`'s docstring states, as plain arrays; :func:`draw` and
:func:`draw_chunks` (``Domain.sample``, ``Domain.chunks``) seed it per chunk and wrap the
arrays in a :class:`~phongfx.scene.geometry.FrameGeometry`.  Everything is vectorized numpy;
a point that breaks a bound of the domain (a back-facing face, an ``n1`` or ``N`` below
``view_cos_min``) is redrawn, so every point drawn lies in the domain.
"""

from dataclasses import dataclass

import numpy as np

from .geometry import FrameGeometry
from .zones import band_points, cap, directions, facing_draw, in_ball, span_end

__all__ = ["CHUNK", "ENDS", "GROUP", "draw", "draw_chunks", "draw_chunk", "sample_chunk", "Surface", "FaceTable", "face_table",
           "random_poses", "random_rotations", "cap", "span_end"]

#: points drawn per generator: ``draw(domain, count, seed)`` is its chunks of this size, concatenated
CHUNK = 1 << 16
#: fraction of points with ``a`` exactly 0, and again exactly 1 (the span's end pixels)
ENDS = 0.02
_ROUNDS = 200  # redraws before a bound is declared unreachable (each keeps about half or more)
#: points that share one pose (drawn per group, so that the faces facing the viewer under
#: it are found once for all of them rather than by rejecting back faces point by point)
GROUP = 16


def _dot(u, w):
    """Row-wise dot products of (P, 3) arrays (einsum: a reduction over an axis of 3 is slow)."""
    return np.einsum("ij,ij->i", u, w)


def _unit(v):
    """Each row of ``v`` (P, k) scaled to length 1."""
    return v / np.maximum(np.sqrt(_dot(v, v)), 1e-300)[:, None]


def _cross(u, w):
    """Row-wise cross products of (P, 3) arrays (``np.cross`` is twice as slow)."""
    out = np.empty(np.broadcast_shapes(u.shape, w.shape))
    out[:, 0] = u[:, 1] * w[:, 2] - u[:, 2] * w[:, 1]
    out[:, 1] = u[:, 2] * w[:, 0] - u[:, 0] * w[:, 2]
    out[:, 2] = u[:, 0] * w[:, 1] - u[:, 1] * w[:, 0]
    return out


def _axis_angle(axes, radians):
    """(P, 4) unit quaternions ``(w, x, y, z)`` of rotations by ``radians`` about unit ``axes``."""
    half = np.asarray(radians, dtype=np.float64) / 2
    axes = np.broadcast_to(np.asarray(axes, dtype=np.float64), (len(half), 3))
    return np.concatenate([np.cos(half)[:, None], np.sin(half)[:, None] * axes], axis=1)


def _product(p, q):
    """Quaternion products ``p·q`` (rotation ``q`` first, then ``p``)."""
    w1, v1, w2, v2 = p[:, :1], p[:, 1:], q[:, :1], q[:, 1:]
    return np.concatenate([w1 * w2 - _dot(v1, v2)[:, None], w1 * v2 + w2 * v1 + _cross(v1, v2)], axis=1)


def random_poses(domain, count, rng):
    """(count, 4) unit quaternions drawn from the domain's pose set (module docstring of
    :mod:`phongfx.scene.domain`): ``"motion"`` a uniform angle about the axis, ``"any"``
    uniform (a uniform unit quaternion is a Haar-uniform rotation), ``"still"`` a uniform
    frame's pose, then a wobble about a uniform axis with the Haar density of its angle,
    ``∝ 1 - cos θ``, up to ``wobble_degrees``."""
    if domain.pose == "motion":
        lo, hi = domain.degrees
        return _axis_angle(domain.axis, np.radians(rng.uniform(lo, hi, count)))
    if domain.pose == "any":
        return _unit(rng.standard_normal((count, 4)))
    frames = np.radians(np.asarray(domain.still_degrees))
    base = _axis_angle(domain.axis, frames[rng.integers(len(frames), size=count)])
    top = np.radians(domain.wobble_degrees)
    grid = np.linspace(0.0, top, 1025)
    cdf = grid - np.sin(grid)
    angle = np.interp(rng.random(count) * cdf[-1], cdf, grid) if top > 0 else np.zeros(count)
    return _product(_axis_angle(directions(rng, count), angle), base)


def random_rotations(domain, count, rng):
    """(count, 3, 3) rotation matrices drawn from the domain's pose set (:func:`random_poses`),
    for whoever rasterizes whole frames of random poses."""
    return _matrices(random_poses(domain, count, rng))


def _matrices(q):
    """(G, 3, 3) rotation matrices of the unit quaternions ``q`` (G, 4)."""
    w, x, y, z = q.T
    return np.stack([np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], -1),
                     np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], -1),
                     np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], -1)], 1)


@dataclass(frozen=True)
class Surface:
    """What :func:`sample_chunk` draws surface points from (:mod:`phongfx.scene.domain`):
    meshes, per material index their :class:`FaceTable` (None: no face); Lyon's spheres
    (``lyon`` True), the ``shininess`` of each sphere from sphere ``first`` on."""
    lyon: bool
    tables: tuple = ()
    shininess: tuple = ()
    first: int = 0  # Lyon: the index of the sphere ``shininess[0]`` is (a region holds one sphere)


@dataclass(frozen=True)
class FaceTable:
    """The faces of one material as :func:`sample_chunk` draws them: per face its corners'
    unit ``normals`` and ``vertices`` (F, 3, 3), unit winding normal ``face_normals`` (F, 3),
    and Walker's alias table (``prob``, ``alias``) of its area: a face by area in O(1)."""
    normals: np.ndarray
    vertices: np.ndarray
    face_normals: np.ndarray
    prob: np.ndarray
    alias: np.ndarray

    def draw(self, count, rng):
        """(count,) face indices, each with probability proportional to its area."""
        index = rng.integers(len(self.prob), size=count)
        return np.where(rng.random(count) < self.prob[index], index, self.alias[index])


def face_table(vertices, normals, faces, face_normals, areas):
    """The :class:`FaceTable` of ``faces`` (F, 3) of a mesh's ``vertices`` and unit vertex
    ``normals``, with their ``face_normals`` and ``areas`` (Vose's alias construction)."""
    scaled = np.asarray(areas, dtype=np.float64) * len(areas) / np.sum(areas)
    prob, alias = np.ones(len(areas)), np.arange(len(areas))
    small = [i for i in range(len(areas)) if scaled[i] < 1]
    large = [i for i in range(len(areas)) if scaled[i] >= 1]
    while small and large:
        less, more = small.pop(), large.pop()
        prob[less], alias[less] = scaled[less], more
        scaled[more] += scaled[less] - 1
        (small if scaled[more] < 1 else large).append(more)
    return FaceTable(normals[faces], vertices[faces], np.asarray(face_normals, dtype=np.float64), prob, alias)


def _mesh_points(domain, material, rng):
    """(n0, surface point) of each point: a pose of the pose set shared by :data:`GROUP`
    points, a face of the point's material drawn by area and redrawn until it faces the
    viewer under that pose (where a point's draws keep failing, one of the few faces toward the
    viewer, uniformly, or for a pose with none a new pose for its group), a uniform point of
    the face.  A region's patch of faces (:mod:`phongfx.scene.patches`) meets such poses often."""
    n0, point = np.empty((len(material), 3)), np.empty((len(material), 3))
    for m in np.unique(material):
        table = domain.surface.tables[m]
        mine = np.flatnonzero(material == m)
        groups = -(-len(mine) // GROUP)
        turned = _matrices(random_poses(domain, groups, rng))
        toward = np.ascontiguousarray(turned[:, 2, :])  # a face is drawn when its normal · this > 0
        local = table.draw(groups * GROUP, rng)
        ok = np.einsum("gkj,gj->gk", table.face_normals[local].reshape(groups, GROUP, 3), toward).ravel() > 0
        pending = np.flatnonzero(~ok)
        for round in range(1, _ROUNDS + 1):
            if not len(pending):
                break
            pick = table.draw(len(pending), rng)
            ok = _dot(toward[pending // GROUP], table.face_normals[pick]) > 0
            local[pending[ok]] = pick[ok]
            pending = pending[~ok]
            if round % 32 == 0 and len(pending):  # few faces face this pose: any of them, else a new pose
                pending = facing_draw(table.face_normals, toward, local, pending, GROUP, rng)
                stuck = np.unique(pending // GROUP)
                turned[stuck] = _matrices(random_poses(domain, len(stuck), rng))
                toward[stuck] = turned[stuck, 2, :]
                pending = np.flatnonzero(np.isin(np.arange(groups * GROUP) // GROUP, stuck))
        else:
            raise ValueError(f"no face of material {domain.materials[m][0]!r} faces the viewer under "
                             f"pose {domain.pose!r}; the domain is empty")
        r1, r2 = np.sqrt(rng.random(len(local))), rng.random(len(local))
        bary = np.stack([1 - r1, r1 * (1 - r2), r1 * r2], -1)[:, :, None]
        transposed = turned.transpose(0, 2, 1)
        normal = _unit(np.einsum("pkj,pkj->pj", bary, table.normals[local])).reshape(groups, GROUP, 3)
        where = np.einsum("pkj,pkj->pj", bary, table.vertices[local]).reshape(groups, GROUP, 3)
        n0[mine] = np.matmul(normal, transposed).reshape(-1, 3)[:len(mine)]
        point[mine] = np.matmul(where, transposed).reshape(-1, 3)[:len(mine)]
    return n0, point


def _lyon_points(domain, rng, count):
    """(sphere index, n0 uniform on the front hemisphere, surface point) of Lyon's spheres."""
    sphere = rng.integers(len(domain.surface.shininess), size=count)
    z = rng.random(count)
    phi = rng.uniform(0, 2 * np.pi, count)
    rho = np.sqrt(1 - z * z)
    n0 = np.stack([rho * np.cos(phi), rho * np.sin(phi), z], -1)
    return sphere, n0, n0 + np.stack([sphere + domain.surface.first, np.zeros(count), np.zeros(count)], -1)


def _toward(kind, vector, points):
    if kind in ("directional", "infinity"):
        return [np.broadcast_to(np.asarray(vector, dtype=np.float64), p.shape) for p in points]
    return [_unit(np.asarray(vector) - p) for p in points]


def _second_normal(domain, n0, a, views, rng):
    """``(n1, N)``: ``n1`` uniform in the cap of the span angle about ``n0``, redrawn while it
    or ``N = unit((1-a)n0 + a·n1)`` meets some viewer vector below ``view_cos_min``; after
    the last round the few left take ``n1 = n0`` (a one-normal span, in the domain)."""
    n1 = cap(n0, domain.max_span_angle_deg, rng)
    normal = _unit((1 - a)[:, None] * n0 + a[:, None] * n1)
    pending = np.flatnonzero(~_meets(domain, (n1, normal), views, None))
    n1[pending], normal[pending] = n0[pending], n0[pending]  # until a redraw meets the bound
    for _ in range(_ROUNDS):
        if not len(pending):
            break
        got = cap(n0[pending], domain.max_span_angle_deg, rng)
        t = a[pending, None]
        mixed = _unit((1 - t) * n0[pending] + t * got)
        ok = _meets(domain, (got, mixed), views, pending)
        n1[pending[ok]], normal[pending[ok]] = got[ok], mixed[ok]
        pending = pending[~ok]
    return n1, normal


def _meets(domain, normals, views, index):
    """(P,) whether every one of ``normals`` has N·V in [view_cos_min, view_cos_max] for every
    one of ``views`` (a fixed vector, or per point, taken at ``index`` unless None)."""
    ok = np.ones(len(normals[0]), dtype=bool)
    for v in views:
        v = v if v.ndim == 1 or index is None else v[index]
        for n in normals:
            cos = n @ v if v.ndim == 1 else _dot(n, v)
            ok &= (cos >= domain.view_cos_min) & (cos <= domain.view_cos_max)
    return ok


def sample_chunk(domain, count, rng):
    """``{name: array}`` of ``count`` domain points, the fields of a
    :class:`~phongfx.scene.geometry.FrameGeometry` that vary (``l0``, ``l1``, ``light`` are
    (lights, count, 3); fixed directions are read-only broadcasts)."""
    if domain.regions:
        return _by_region(domain, count, rng)
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
    end = rng.random(count)
    a = np.where(end < ENDS, 0.0, np.where(end >= 1 - ENDS, 1.0, rng.random(count)))
    band = band_points(domain, a, rng) if domain.surface.lyon and domain.region_name else None
    if band is not None:  # the surface point at the pixel's normal, as Lyon's image has it
        surface = surface - n0 + band[2]
    if domain.camera[0] == "point" or any(kind == "point" for kind, _, _ in domain.lights):
        x0 = surface
        inside = np.flatnonzero(rng.random(count) < 0.5)
        x0[inside] = in_ball(domain, rng, len(inside))
        x1 = span_end(domain, x0, rng)
        points = (x0, x1, (1 - a)[:, None] * x0 + a[:, None] * x1)
    else:  # no vector depends on where the surface is: the pixel is the surface point
        points = (surface, surface, surface)
    position = points[2]
    if domain.camera_path:
        path = np.asarray(domain.camera_path)
        views = _toward("point", path[rng.integers(len(path), size=count)], points)
    else:
        views = _toward(domain.camera[0], domain.camera[1], points)
    checks = [] if domain.view_cos_min <= -1 and domain.view_cos_max >= 1 else (
        [np.asarray(domain.camera[1], dtype=np.float64)] if views[0].strides[0] == 0 else views)
    if band is not None:
        n0, n1, normal = band
    else:
        n1, normal = _second_normal(domain, n0, a, checks, rng)
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


def _by_region(domain, count, rng):
    """:func:`sample_chunk` of a domain with regions: a uniform region per point (each region,
    narrow or wide, gets its share of the hard points at its own limits), then a point of it,
    the points of one region side by side; a region whose pose draws keep showing none of its
    faces hands its points to the others."""
    todo = list(zip(range(len(domain.regions)), np.bincount(rng.integers(len(domain.regions), size=count),
                                                           minlength=len(domain.regions)).tolist()))
    out, failed, start = None, set(), 0
    while todo:
        r, size = todo.pop(0)
        try:
            part = sample_chunk(domain.region(r), size, rng)
        except ValueError:
            failed.add(r)
            others = np.setdiff1d(np.arange(len(domain.regions)), sorted(failed))
            if not len(others):
                raise
            more = np.bincount(rng.integers(len(others), size=size), minlength=len(others))
            todo += [(int(o), int(m)) for o, m in zip(others, more) if m]
            continue
        out = _put(out, part, slice(start, start + size), count)
        start += size
    if out is None:  # no point: any region's empty chunk has the fields
        out = sample_chunk(domain.region(0), 0, rng)
    return out


def draw_chunks(domain, count, seed):
    """:class:`~phongfx.scene.geometry.FrameGeometry` pieces of :data:`CHUNK` domain points
    (the last shorter) whose concatenation is ``draw(domain, count, seed)``."""
    for _, part in _parts(domain, _count(count), seed):
        yield _geometry(domain, part)


def draw(domain, count, seed):
    """A :class:`~phongfx.scene.geometry.FrameGeometry` of ``count`` points of ``domain``
    (one pixel per span, ``span = arange(count)``, ``frame = -1``), deterministic for
    (domain, count, seed): the chunks of :func:`draw_chunks`, filled into arrays made once
    (no second copy of every array)."""
    count = _count(count)
    out = None
    for start, part in _parts(domain, count, seed, at_least_one=True):
        out = _put(out, part, slice(start, start + CHUNK), count)
    return _geometry(domain, out)


def _put(out, part, where, count):
    """``out`` (None: made, ``count`` long) with the arrays ``part`` written at ``where``."""
    if out is None:
        out = {key: _empty(value, count, 1 if key in _PER_LIGHT else 0) for key, value in part.items()}
    for key, value in part.items():
        axis = 1 if key in _PER_LIGHT else 0
        if out[key].strides[axis] != 0:
            np.moveaxis(out[key], axis, 0)[where] = np.moveaxis(value, axis, 0)
    return out


_PER_LIGHT = ("l0", "l1", "light")


def _parts(domain, count, seed, at_least_one=False):
    """``(start, arrays)`` of each chunk: chunk ``index`` drawn from its own generator,
    seeded by ``(seed, index)``."""
    for index, start in enumerate(range(0, max(count, 1) if at_least_one else count, CHUNK)):
        yield start, _part(domain, count, seed, index)


def _part(domain, count, seed, index):
    start = index * CHUNK
    return sample_chunk(domain, min(CHUNK, count - start), np.random.default_rng((int(seed), index)))


def draw_chunk(domain, count, seed, index):
    """Chunk ``index`` of :func:`draw_chunks` alone (each is drawn from its own generator:
    chunks can be drawn in any order, by any process)."""
    return _geometry(domain, _part(domain, _count(count), seed, index))


def _empty(value, count, axis):
    """An array like ``value`` with ``count`` along ``axis``: a broadcast of its one vector
    when ``value`` is one (stride 0 along ``axis``: a directional light, a camera at
    infinity), which stays a broadcast rather than gigabytes of copies."""
    shape = list(value.shape)
    shape[axis] = count
    if value.shape[axis] and value.strides[axis] == 0:
        return np.broadcast_to(np.take(value, [0], axis=axis), shape)
    return np.empty(shape, dtype=value.dtype)


def _geometry(domain, g):
    count = len(g["a"])
    zeros = np.zeros(count, dtype=np.int64)
    rgb = np.array([light[2] for light in domain.lights], dtype=np.float64).reshape(-1, 3)
    return FrameGeometry(0, 0, zeros, zeros.copy(), np.arange(count), g["a"], g["n0"], g["n1"],
                         g["normal"], g["position"], g["l0"], g["l1"], g["light"], g["v0"],
                         g["v1"], g["viewer"], rgb, g["n"], g["kd"], g["ks"], g["ka"], g["colour"],
                         g["material"], None, -1, domain.bits)


def _count(count):
    if isinstance(count, bool) or not isinstance(count, (int, np.integer)) or count < 0:
        raise ValueError(f"count must be a non-negative integer, not {count!r}")
    return int(count)
