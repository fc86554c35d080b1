"""Polygon meshes and a vectorized scanline rasterizer producing Phong spans.

The test objects of the papers: Hast, Barrera & Bengtsson (§5, §6, Tables 1–2) render
tori of 288, 512, 800 and 1152 polygons "in 200 frames rotated in the x, y and z
directions"; Szirmay-Kalos (§6, Figures 14–15) renders coarsely tessellated spheres.
:func:`rasterize` does what their scanline hardware is fed by (Szirmay-Kalos §5,
Figure 13): edge walking per triangle, one span per triangle per scanline, with the
vertex normals interpolated along the edges and then to the first and last pixel
centres of the span, normalized there (Hast §3 needs unit end normals).

Screen space: orthographic projection along -z (viewer at infinity, ``V = (0, 0, 1)``
in eye space); x right, y down (row index); pixel centres at ``(x + 0.5, y + 0.5)``.
The top-left fill rule (centre on a top or left edge: in; bottom or right: out) makes
triangles that share an edge cover each pixel of it exactly once.
"""

from dataclasses import dataclass

import numpy as np

__all__ = ["unit", "Mesh", "uv_sphere", "torus", "rotation", "Spans", "fit_scale", "project",
           "rasterize", "rasterize_screen", "image", "FILL"]

FILL = 0.95  # the object's bounding sphere spans this fraction of min(width, height)


def _positive_int(name, value, minimum=1):
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < minimum:
        raise ValueError(f"{name} must be an integer >= {minimum}, not {value!r}")
    return int(value)


@dataclass(frozen=True)
class Mesh:
    """Triangle mesh with unit vertex normals; ``polygons`` counts a quad as one polygon
    (as the papers count them)."""
    vertices: np.ndarray
    normals: np.ndarray
    faces: np.ndarray
    polygons: int


def unit(v):
    """Each row of ``v`` scaled to length 1 (a zero row stays 0)."""
    return v / np.maximum(np.linalg.norm(v, axis=-1, keepdims=True), 1e-300)


def _quads(index, rows, cols, wrap_rows):
    """Two counter-clockwise (seen from outside) triangles per quad of a grid of vertex
    ``index[row, col]``, columns wrapping around."""
    r = np.arange(rows if wrap_rows else rows - 1)
    c = np.arange(cols)
    r, c = np.meshgrid(r, c, indexing="ij")
    r1, c1 = (r + 1) % rows, (c + 1) % cols
    a, b, d, e = index[r, c], index[r, c1], index[r1, c1], index[r1, c]
    return np.concatenate([np.stack([a, e, d], -1).reshape(-1, 3),
                           np.stack([a, d, b], -1).reshape(-1, 3)])


def uv_sphere(stacks, slices):
    """Unit UV sphere: ``stacks`` bands of latitude, ``slices`` of longitude; the two
    polar bands are triangle fans, the others quads, so ``polygons = stacks·slices``."""
    stacks = _positive_int("stacks", stacks, 2)
    slices = _positive_int("slices", slices, 3)
    theta = np.pi * np.arange(1, stacks) / stacks  # polar angle of the inner rings
    phi = 2 * np.pi * np.arange(slices) / slices
    theta, phi = np.meshgrid(theta, phi, indexing="ij")
    ring = np.stack([np.sin(theta) * np.cos(phi), np.cos(theta),
                     -np.sin(theta) * np.sin(phi)], -1).reshape(-1, 3)
    vertices = np.concatenate([ring, [[0.0, 1.0, 0.0], [0.0, -1.0, 0.0]]])
    north, south = len(ring), len(ring) + 1
    index = np.arange(len(ring)).reshape(stacks - 1, slices)
    c, c1 = np.arange(slices), (np.arange(slices) + 1) % slices
    top = np.stack([np.full(slices, north), index[0, c], index[0, c1]], -1)
    bottom = np.stack([np.full(slices, south), index[-1, c1], index[-1, c]], -1)
    faces = np.concatenate([top, _quads(index, stacks - 1, slices, False), bottom])
    return Mesh(vertices, vertices.copy(), faces.astype(np.int64), stacks * slices)


def torus(polygons, major=1.0, minor=0.4):
    """Torus of ``polygons = 2k²`` quads: ``2k`` around the ring by ``k`` around the tube
    (288, 512, 800, 1152 → 24×12, 32×16, 40×20, 48×24, Hast Tables 1–2)."""
    k = int(round(np.sqrt(polygons / 2))) if isinstance(polygons, (int, np.integer)) and polygons > 0 else 0
    if isinstance(polygons, bool) or k < 3 or 2 * k * k != polygons:
        raise ValueError(f"polygons must be 2·k² for an integer k >= 3 (18, 32, ..., 288, 512, "
                         f"800, 1152), not {polygons!r}")
    if not 0 < minor < major:
        raise ValueError(f"radii must satisfy 0 < minor < major, not minor={minor!r}, "
                         f"major={major!r}")
    u = 2 * np.pi * np.arange(2 * k) / (2 * k)  # around the ring (z axis)
    v = 2 * np.pi * np.arange(k) / k  # around the tube
    u, v = np.meshgrid(u, v, indexing="ij")
    normals = np.stack([np.cos(v) * np.cos(u), np.cos(v) * np.sin(u), np.sin(v)], -1)
    centre = np.stack([major * np.cos(u), major * np.sin(u), np.zeros_like(u)], -1)
    vertices = (centre + minor * normals).reshape(-1, 3)
    index = np.arange(2 * k * k).reshape(2 * k, k)
    faces = _quads(index, 2 * k, k, True)
    return Mesh(vertices, normals.reshape(-1, 3), faces.astype(np.int64), polygons)


def rotation(frame, frames=200):
    """Rotation of ``frame`` of an animation of ``frames``: ``frame/frames`` of a full turn
    about x, then y, then z (Hast §5: "rotated in the x, y and z directions")."""
    frames = _positive_int("frames", frames)
    if isinstance(frame, bool) or not isinstance(frame, (int, np.integer)):
        raise ValueError(f"frame must be an integer, not {frame!r}")
    angle = 2 * np.pi * (frame % frames) / frames
    c, s = np.cos(angle), np.sin(angle)
    rx = np.array([[1, 0, 0], [0, c, -s], [0, s, c]])
    ry = np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])
    rz = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
    return rz @ ry @ rx


@dataclass(frozen=True)
class Spans:
    """One row per span (a triangle's run of pixels on one scanline), sorted by (y, x0);
    per-pixel arrays are in pixel order: spans in row order, pixels left to right.
    ``pa``/``pb`` (optional) are the eye-space surface points at the span's first and
    last pixel centres, for local lights and a local viewer (Lyon's "local viewer")."""
    width: int
    height: int
    y: np.ndarray
    x0: np.ndarray
    length: np.ndarray
    na: np.ndarray
    nb: np.ndarray
    face: np.ndarray
    visible: np.ndarray
    pa: np.ndarray = None
    pb: np.ndarray = None

    def pixel_span(self):
        """(P,) index of each pixel's span."""
        return np.repeat(np.arange(len(self.length)), self.length)

    def pixel_step(self):
        """(P,) step ``k = 0..length-1`` of each pixel within its span."""
        starts = np.cumsum(self.length) - self.length
        return np.arange(int(self.length.sum())) - np.repeat(starts, self.length)

    def pixel_t(self):
        """(P,) ``k/(length-1)``, 0 for one-pixel spans."""
        steps = np.repeat(np.maximum(self.length - 1, 1), self.length)
        return self.pixel_step() / steps

    def pixel_xy(self):
        """(P, 2) pixel coordinates ``(x, y)``."""
        span = self.pixel_span()
        return np.stack([self.x0[span] + self.pixel_step(), self.y[span]], -1)

    def interpolated_normals(self):
        """(P, 3) ``na + t·(nb - na)``, not normalized (Phong normalizes it per pixel)."""
        span, t = self.pixel_span(), self.pixel_t()[:, None]
        return self.na[span] + t * (self.nb[span] - self.na[span])

    def interpolated_positions(self):
        """(P, 3) ``pa + t·(pb - pa)``: exact surface points, since the projection is
        orthographic and each span lies on one plane."""
        if self.pa is None:
            raise ValueError("spans carry no positions; rasterize_screen(..., positions=...) adds them")
        span, t = self.pixel_span(), self.pixel_t()[:, None]
        return self.pa[span] + t * (self.pb[span] - self.pa[span])


def _check_size(width, height):
    return _positive_int("width", width), _positive_int("height", height)


def fit_scale(mesh, width, height):
    """Pixels per object unit: the bounding sphere (about the origin) spans ``FILL`` of
    the smaller side, whatever the rotation."""
    width, height = _check_size(width, height)
    return FILL * min(width, height) / (2 * np.max(np.linalg.norm(mesh.vertices, axis=1)))


def project(mesh, rotation, width, height):
    """Eye-space vertices and normals and screen ``(x, y, z)`` of the rotated mesh."""
    rotation = np.asarray(rotation, dtype=np.float64)
    if rotation.shape != (3, 3):
        raise ValueError(f"rotation must be a 3×3 matrix, not shape {rotation.shape}")
    scale = fit_scale(mesh, width, height)
    eye, normals = mesh.vertices @ rotation.T, mesh.normals @ rotation.T
    screen = np.stack([width / 2 + scale * eye[:, 0], height / 2 - scale * eye[:, 1],
                       eye[:, 2]], -1)
    return eye, normals, screen


def rasterize(mesh, rotation, width, height):
    """Spans of ``mesh`` rotated by ``rotation`` (module docstring): back faces culled
    (eye-space facet normal ``z <= 0``), nearest surface marked ``visible``."""
    width, height = _check_size(width, height)
    eye, normals, screen = project(mesh, rotation, width, height)
    tri = eye[mesh.faces]
    facing = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])[:, 2] > 0
    faces = np.flatnonzero(facing)
    return rasterize_screen(screen, normals, mesh.faces[faces], width, height, faces, eye)


def _edge(top, bottom, yc):
    """Point of each edge ``top→bottom`` (top has the smaller y) at row centre ``yc``.
    Computed from the edge alone, so both triangles sharing it get identical bits."""
    dy = bottom[:, 1] - top[:, 1]
    f = (yc - top[:, 1]) / np.where(dy == 0, 1.0, dy)
    return top + f[:, None] * (bottom - top)


def rasterize_screen(screen, normals, faces, width, height, face_ids=None, positions=None):
    """Scan-convert triangles given in screen coordinates (module docstring).

    ``screen`` (V, 3) is ``(x, y, z)`` with larger ``z`` nearer, ``normals`` (V, 3) the
    vertex normals, ``faces`` (F, 3); every face is drawn whatever its winding.
    ``face_ids`` (F,) names the faces in :attr:`Spans.face` (default ``0..F-1``).
    ``positions`` (V, 3), optional: per-vertex points interpolated like the normals into
    :attr:`Spans.pa` and :attr:`Spans.pb` (not normalized).
    """
    width, height = _check_size(width, height)
    faces = np.asarray(faces, dtype=np.int64).reshape(-1, 3)
    face_ids = np.arange(len(faces)) if face_ids is None else np.asarray(face_ids, np.int64)
    # per vertex: x, y, z, nx, ny, nz, sorted by y within each triangle
    extra = [] if positions is None else [np.asarray(positions, dtype=np.float64)]
    attrs = np.concatenate([screen, normals] + extra, axis=1)[faces]
    attrs = np.take_along_axis(attrs, np.argsort(attrs[:, :, 1], axis=1, kind="stable")[:, :, None], 1)
    # rows whose centre lies in [y_top, y_bottom): top edges in, bottom edges out
    first = np.clip(np.ceil(attrs[:, 0, 1] - 0.5), 0, height).astype(np.int64)
    stop = np.clip(np.ceil(attrs[:, 2, 1] - 0.5), 0, height).astype(np.int64)
    rows = np.maximum(stop - first, 0)
    tri = np.repeat(np.arange(len(faces)), rows)
    y = np.arange(int(rows.sum())) - np.repeat(np.cumsum(rows) - rows, rows) + first[tri]
    yc = y + 0.5
    v0, v1, v2 = attrs[tri, 0], attrs[tri, 1], attrs[tri, 2]
    long = _edge(v0, v2, yc)
    upper = yc < v1[:, 1]
    short = np.where(upper[:, None], _edge(v0, v1, yc), _edge(v1, v2, yc))
    swap = (short[:, 0] < long[:, 0])[:, None]
    left, right = np.where(swap, short, long), np.where(swap, long, short)
    # pixels whose centre lies in [x_left, x_right): left edges in, right edges out
    x0 = np.clip(np.ceil(left[:, 0] - 0.5), 0, width).astype(np.int64)
    x1 = np.clip(np.ceil(right[:, 0] - 0.5), 0, width).astype(np.int64)
    keep = x1 > x0
    tri, y, x0, left, right = tri[keep], y[keep], x0[keep], left[keep], right[keep]
    length = (x1[keep] - x0).astype(np.int64)
    span_dx = np.where(right[:, 0] > left[:, 0], right[:, 0] - left[:, 0], 1.0)

    def at(x):  # attributes linearly interpolated between the edges at pixel centre x
        f = ((x + 0.5 - left[:, 0]) / span_dx)[:, None]
        return left + f * (right - left)

    a, b = at(x0), at(x0 + length - 1)
    order = np.lexsort((x0, y))
    tri, y, x0, length, a, b = tri[order], y[order], x0[order], length[order], a[order], b[order]
    na, nb = unit(a[:, 3:6]), unit(b[:, 3:6])
    pa, pb = (None, None) if positions is None else (a[:, 6:9], b[:, 6:9])
    # z-buffer: per pixel the nearest span wins (ties: the first in pixel order)
    starts = np.cumsum(length) - length
    step = np.arange(int(length.sum())) - np.repeat(starts, length)
    t = step / np.repeat(np.maximum(length - 1, 1), length)
    z = np.repeat(a[:, 2], length) + t * np.repeat(b[:, 2] - a[:, 2], length)
    pixel = np.repeat(y * width + x0, length) + step
    visible = np.zeros(len(pixel), dtype=bool)
    if len(pixel):
        ranked = np.lexsort((np.arange(len(pixel)), -z, pixel))
        head = np.ones(len(ranked), dtype=bool)
        head[1:] = pixel[ranked[1:]] != pixel[ranked[:-1]]
        visible[ranked[head]] = True
    return Spans(width, height, y, x0, length, na, nb, face_ids[tri], visible, pa, pb)


def image(spans, values, background=0.0):
    """(height, width[, ...]) float image of per-pixel ``values`` (P[, ...]) at the
    visible pixels, ``background`` elsewhere."""
    values = np.asarray(values, dtype=np.float64)
    count = int(spans.length.sum())
    if values.shape[:1] != (count,):
        raise ValueError(f"values must have one row per pixel ({count}), not shape {values.shape}")
    out = np.full((spans.height, spans.width) + values.shape[1:], float(background))
    xy = spans.pixel_xy()[spans.visible]
    out[xy[:, 1], xy[:, 0]] = values[spans.visible]
    return out
