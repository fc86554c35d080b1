"""Wavefront OBJ loader: corner forms, negative indices, fans, computed normals, errors."""

import numpy as np
import pytest

from phongfx.scene.mesh import rasterize, uv_sphere
from phongfx.scene.obj import ObjError, load_obj, parse_obj

# a unit square in z = 0 split unevenly, plus a tilted triangle sharing no vertex
SQUARE = """# square
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
f 1 2 3 4   # one quad, fanned into 2 triangles
"""


def test_quad_is_fanned_and_counted_once():
    mesh = parse_obj(SQUARE)
    assert mesh.polygons == 1 and mesh.faces.tolist() == [[0, 1, 2], [0, 2, 3]]
    assert np.allclose(mesh.normals, [0, 0, 1])


@pytest.mark.parametrize("face", ["f 1 2 3", "f 1/1 2/2 3/3", "f -3 -2 -1", "f -3/1 2/2 -1/3"])
def test_corner_forms_and_negative_indices(face):
    mesh = parse_obj("v 0 0 0\nv 2 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n" + face + "\n")
    assert mesh.faces.tolist() == [[0, 1, 2]]
    assert np.allclose(mesh.vertices, [[0, 0, 0], [2, 0, 0], [0, 1, 0]])


def test_given_normals_split_vertices_and_are_normalized():
    text = ("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 0 0 2\nvn 0 3 4\n"
            "f 1//1 2//1 3//1\nf 2//2 4//2 3//2\n")
    mesh = parse_obj(text)
    # vertices 2 and 3 carry two different normals, so they appear twice: 6 mesh vertices
    assert len(mesh.vertices) == 6 and mesh.polygons == 2
    corner_normals = mesh.normals[mesh.faces]
    assert np.allclose(corner_normals[0], [0, 0, 1]) and np.allclose(corner_normals[1], [0, 0.6, 0.8])
    assert np.allclose(mesh.vertices[mesh.faces[1]], [[1, 0, 0], [1, 1, 0], [0, 1, 0]])


def test_computed_normals_are_area_weighted():
    # vertex 1 is shared by a big triangle in z = 0 (area 2) and a small one in x = 0 (area 0.5)
    text = "v 0 0 0\nv 2 0 0\nv 0 2 0\nv 0 0 -1\nv 0 1 0\nf 1 2 3\nf 1 5 4\n"
    mesh = parse_obj(text)
    expected = np.array([-0.5, 0, 2.0]) / np.linalg.norm([-0.5, 0, 2.0])
    assert np.allclose(mesh.normals[0], expected)
    assert np.allclose(mesh.normals[1], [0, 0, 1]) and np.allclose(mesh.normals[3], [-1, 0, 0])


def test_unused_vertices_are_dropped():
    mesh = parse_obj("v 9 9 9\n" + SQUARE.replace("f 1 2 3 4", "f 2 3 4 5"))
    assert len(mesh.vertices) == 4 and np.max(np.abs(mesh.vertices)) == 1


def test_sphere_round_trip_rasterizes_like_the_original(tmp_path):
    sphere = uv_sphere(6, 10)
    lines = [f"v {x!r} {y!r} {z!r}" for x, y, z in sphere.vertices.tolist()]
    lines += [f"vn {x!r} {y!r} {z!r}" for x, y, z in sphere.normals.tolist()]
    lines += [f"f {a + 1}//{a + 1} {b + 1}//{b + 1} {c + 1}//{c + 1}" for a, b, c in sphere.faces]
    (tmp_path / "s.obj").write_text("\n".join(lines))
    mesh = load_obj(tmp_path / "s.obj")
    a, b = rasterize(sphere, np.eye(3), 40, 40), rasterize(mesh, np.eye(3), 40, 40)
    assert b.length.sum() == a.length.sum() > 0 and np.array_equal(a.y, b.y)
    assert np.allclose(a.na, b.na)


BAD = [
    ("v 0 0 0\nv 1 0 0\nf 1 2 3\n", r"^m\.obj:3: face index 3 out of range 1\.\.2$"),
    ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n", r"^m\.obj:4: face index -4 out of range 1\.\.3$"),
    ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", r"^m\.obj:4: face index 0 out of range 1\.\.3$"),
    ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", r"^m\.obj:4: face needs at least 3 corners, not 2$"),
    ("v 0 0\n", r"^m\.obj:1: needs 3 numbers, not 2$"),
    ("v 0 zero 0\n", r"^m\.obj:1: numbers expected, not '0 zero 0'$"),
    ("v 0 0 nan\n", r"^m\.obj:1: numbers must be finite, not '0 0 nan'$"),
    ("vn 0 0 0\n", r"^m\.obj:1: normal must be nonzero, not \[0\.0, 0\.0, 0\.0\]$"),
    ("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//2\n", r"^m\.obj:5: normal index 2 out of range 1\.\.1$"),
    ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/2/3/4 2 3\n",
     r"^m\.obj:4: face corner must be v, v/vt, v//vn or v/vt/vn, not '1/2/3/4'$"),
    ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf a 2 3\n", r"^m\.obj:4: face index must be an integer, not 'a'$"),
    ("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\nf 1 2 3\n",
     r"^m\.obj:6: faces mix corners with and without normals \(vn\)$"),
    ("v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n",
     r"^m\.obj: vertex 1 has no normal \(its faces have zero total area\); give vn records$"),
    ("curv 0 1\n", r"^m\.obj:1: unknown record 'curv'; records: v, vn, f, vt, vp, o, g, s, usemtl, "
                   r"mtllib, l, p$"),
    ("# nothing\nv 0 0 0\n", r"^m\.obj: no faces$"),
]


@pytest.mark.parametrize("text, message", BAD)
def test_errors_name_file_and_line(text, message):
    with pytest.raises(ObjError, match=message):
        parse_obj(text, "m.obj")


def test_missing_file(tmp_path):
    with pytest.raises(ObjError, match=r"^none\.obj: cannot read: No such file or directory$"):
        load_obj(tmp_path / "none.obj")
