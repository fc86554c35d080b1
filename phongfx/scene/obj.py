"""Wavefront OBJ triangle meshes for scene files.

Reads ``v`` and ``vn`` records and ``f`` faces in all four corner forms (``v``,
``v/vt``, ``v//vn``, ``v/vt/vn``), with negative (relative) indices; a polygon of more
than three corners is fan-triangulated from its first corner and counts as one polygon
(as :class:`phongfx.scene.mesh.Mesh` counts them).  Without ``vn`` the vertex normals are the
area-weighted averages of the adjacent face normals (the cross product's length is
twice the area, so summing unnormalized cross products weights by area).  Texture
coordinates, groups, smoothing and materials are read past.  Vertices no face uses are
dropped, so they cannot change :func:`phongfx.scene.mesh.fit_scale`.
"""

import os

import numpy as np

from .mesh import Mesh

__all__ = ["ObjError", "load_obj", "parse_obj"]

#: Records that carry nothing the shader needs.
_IGNORED = ("vt", "vp", "o", "g", "s", "usemtl", "mtllib", "l", "p")


class ObjError(ValueError):
    """A malformed OBJ file; the message is ``file:line: what is wrong``."""


def load_obj(path):
    """The :class:`~phongfx.scene.mesh.Mesh` of the OBJ file ``path`` (:func:`parse_obj`)."""
    name = os.path.basename(os.fspath(path))
    try:
        with open(path, encoding="utf-8", errors="replace") as file:
            text = file.read()
    except OSError as error:
        raise ObjError(f"{name}: cannot read: {error.strerror}") from None
    return parse_obj(text, name)


def _numbers(fields, where, count):
    if len(fields) < count:
        raise ObjError(f"{where}: needs {count} numbers, not {len(fields)}")
    try:
        values = [float(f) for f in fields[:count]]
    except ValueError:
        raise ObjError(f"{where}: numbers expected, not {' '.join(fields)!r}") from None
    if not all(np.isfinite(values)):
        raise ObjError(f"{where}: numbers must be finite, not {' '.join(fields)!r}")
    return values


def _index(text, count, where, what):
    try:
        raw = int(text)
    except ValueError:
        raise ObjError(f"{where}: {what} index must be an integer, not {text!r}") from None
    index = raw - 1 if raw > 0 else count + raw
    if raw == 0 or not 0 <= index < count:
        raise ObjError(f"{where}: {what} index {raw} out of range 1..{count}")
    return index


def parse_obj(text, name="<obj>"):
    """The :class:`~phongfx.scene.mesh.Mesh` of OBJ ``text`` (module docstring).

    Raises
    ------
    ObjError
        One line ``name:line: ...`` for a bad record, an index out of range, a face
        of fewer than 3 corners, faces that mix corners with and without normals, or a
        file without faces.
    """
    vertices, normals, corners, polygons = [], [], [], 0
    for number, line in enumerate(text.splitlines(), 1):
        fields = line.split("#", 1)[0].split()
        if not fields:
            continue
        where, key = f"{name}:{number}", fields[0]
        if key == "v":
            vertices.append(_numbers(fields[1:], where, 3))
        elif key == "vn":
            normal = _numbers(fields[1:], where, 3)
            if np.linalg.norm(normal) == 0:
                raise ObjError(f"{where}: normal must be nonzero, not {normal}")
            normals.append(normal)
        elif key == "f":
            if len(fields) < 4:
                raise ObjError(f"{where}: face needs at least 3 corners, not {len(fields) - 1}")
            face = []
            for corner in fields[1:]:
                parts = corner.split("/")
                if len(parts) > 3:
                    raise ObjError(f"{where}: face corner must be v, v/vt, v//vn or v/vt/vn, "
                                   f"not {corner!r}")
                v = _index(parts[0], len(vertices), where, "face")
                vn = (_index(parts[2], len(normals), where, "normal")
                      if len(parts) == 3 and parts[2] else -1)
                face.append((v, vn, number))
            # fan from the first corner: convex polygons stay counter-clockwise
            corners += [c for i in range(1, len(face) - 1) for c in (face[0], face[i], face[i + 1])]
            polygons += 1
        elif key not in _IGNORED:
            raise ObjError(f"{where}: unknown record {key!r}; records: v, vn, f, "
                           f"{', '.join(_IGNORED)}")
    if not corners:
        raise ObjError(f"{name}: no faces")
    corners = np.array(corners, dtype=np.int64)
    has_normal = corners[:, 1] >= 0
    if has_normal.any() and not has_normal.all():
        line = corners[np.argmax(has_normal != has_normal[0]), 2]
        raise ObjError(f"{name}:{line}: faces mix corners with and without normals (vn)")
    vertices = np.array(vertices, dtype=np.float64)
    if has_normal.all():
        # one mesh vertex per distinct (v, vn) pair: Mesh keeps one normal per vertex
        pairs, index = np.unique(corners[:, :2], axis=0, return_inverse=True)
        normals = np.array(normals, dtype=np.float64)[pairs[:, 1]]
        return Mesh(vertices[pairs[:, 0]], normals / np.linalg.norm(normals, axis=1, keepdims=True),
                    index.reshape(-1, 3).astype(np.int64), polygons)
    used, index = np.unique(corners[:, 0], return_inverse=True)
    points, faces = vertices[used], index.reshape(-1, 3).astype(np.int64)
    tri = points[faces]
    area2 = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    summed = np.zeros_like(points)
    for k in range(3):
        np.add.at(summed, faces[:, k], area2)
    length = np.linalg.norm(summed, axis=1)
    if np.any(length == 0):
        bad = int(used[np.argmin(length)]) + 1
        raise ObjError(f"{name}: vertex {bad} has no normal (its faces have zero total area); "
                       f"give vn records")
    return Mesh(points, summed / length[:, None], faces, polygons)
