import time

import numpy as np
import pytest

from phongfx.scene.mesh import Mesh, fit_scale, image, rasterize, rasterize_screen, rotation, torus, uv_sphere

UP = np.array([0.0, 0.0, 1.0])


def _quad(corners, z=0.0, normals=None):
    """Two triangles (0,1,2), (0,2,3) in screen space sharing the diagonal 0–2."""
    screen = np.column_stack([np.asarray(corners, dtype=np.float64), np.full(4, z)])
    normals = np.tile(UP, (4, 1)) if normals is None else np.asarray(normals, np.float64)
    return screen, normals, np.array([[0, 1, 2], [0, 2, 3]])


def _inside(corners, width, height):
    """Independent coverage: pixel centres strictly inside a convex polygon."""
    x, y = np.meshgrid(np.arange(width) + 0.5, np.arange(height) + 0.5)
    c = np.asarray(corners, dtype=np.float64)
    sides = []
    for (ax, ay), (bx, by) in zip(c, np.roll(c, -1, axis=0)):
        sides.append((bx - ax) * (y - ay) - (by - ay) * (x - ax))
    sides = np.stack(sides)
    return np.all(sides > 0, axis=0) | np.all(sides < 0, axis=0)


def _coverage(spans):
    xy = spans.pixel_xy()
    return xy, np.unique(xy[:, 1] * spans.width + xy[:, 0]).size


def test_pixel_aligned_square_covers_its_area_once():
    spans = rasterize_screen(*_quad([(2, 3), (12, 3), (12, 9), (2, 9)]), 16, 16)
    xy, unique = _coverage(spans)
    assert len(xy) == unique == 10 * 6  # the shared diagonal is not drawn twice
    assert set(map(tuple, xy)) == {(x, y) for x in range(2, 12) for y in range(3, 9)}
    assert set(spans.face) == {0, 1}


@pytest.mark.parametrize("corners", [
    [(3.3, 1.7), (27.1, 6.2), (21.6, 28.4), (1.9, 19.3)],
    [(15.2, 0.6), (30.7, 15.1), (16.1, 30.2), (0.8, 14.9)],
])
def test_generic_quad_matches_point_in_polygon_without_double_cover(corners):
    spans = rasterize_screen(*_quad(corners), 32, 32)
    xy, unique = _coverage(spans)
    want = _inside(corners, 32, 32)
    assert len(xy) == unique == want.sum()
    assert want[xy[:, 1], xy[:, 0]].all()


def test_fan_of_triangles_covers_each_pixel_once():
    # 7 triangles around a non-integer centre: every interior edge is shared
    angles = 2 * np.pi * np.arange(7) / 7 + 0.3
    ring = np.column_stack([20.3 + 15 * np.cos(angles), 19.6 + 15 * np.sin(angles)])
    screen = np.column_stack([np.vstack([[20.3, 19.6], ring]), np.zeros(8)])
    faces = np.array([[0, 1 + i, 1 + (i + 1) % 7] for i in range(7)])
    spans = rasterize_screen(screen, np.tile(UP, (8, 1)), faces, 40, 40)
    xy, unique = _coverage(spans)
    assert len(xy) == unique == _inside(ring, 40, 40).sum()
    assert spans.visible.all()


def test_spans_are_sorted_and_inside_the_frame():
    spans = rasterize(torus(288), rotation(37), 64, 48)
    assert np.all(spans.length >= 1)
    key = spans.y * 1000 + spans.x0
    assert np.all(np.diff(key) >= 0)
    xy = spans.pixel_xy()
    assert xy[:, 0].min() >= 0 and xy[:, 0].max() < 64
    assert xy[:, 1].min() >= 0 and xy[:, 1].max() < 48
    assert len(spans.visible) == spans.length.sum()


def test_sphere_silhouette_area_is_pi_r_squared():
    sphere = uv_sphere(48, 96)
    radius = fit_scale(sphere, 256, 256)  # unit sphere: pixels per unit = radius in pixels
    spans = rasterize(sphere, rotation(13), 256, 256)
    _, unique = _coverage(spans)
    assert unique == spans.visible.sum() == spans.length.sum()  # convex: nothing hidden
    # an inscribed 96-gon loses 1 - sin(2π/96)·96/(2π) = 0.07 % of the disc; sampling
    # a 121-pixel radius disc on the pixel grid is within a few tenths of a percent
    assert unique == pytest.approx(np.pi * radius ** 2, rel=0.01)


def test_end_normals_are_unit_and_interpolation_hits_them():
    spans = rasterize(torus(512), rotation(11), 96, 96)
    np.testing.assert_allclose(np.linalg.norm(spans.na, axis=1), 1, atol=1e-12)
    np.testing.assert_allclose(np.linalg.norm(spans.nb, axis=1), 1, atol=1e-12)
    normals, step, span = spans.interpolated_normals(), spans.pixel_step(), spans.pixel_span()
    first, last = step == 0, step == spans.length[span] - 1
    np.testing.assert_allclose(normals[first], spans.na[span[first]], atol=1e-14)
    np.testing.assert_allclose(normals[last], spans.nb[span[last]], atol=1e-14)
    single = spans.length == 1
    np.testing.assert_array_equal(spans.na[single], spans.nb[single])
    assert np.all(spans.pixel_t()[first] == 0)


def test_flat_shaded_plane_has_constant_normals():
    corners = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (1.0, 1.0, 0.0), (0.0, 1.0, 0.0)]
    plane = Mesh(np.array(corners) - 0.5, np.tile(UP, (4, 1)), np.array([[0, 1, 2], [0, 2, 3]]), 1)
    turn = rotation(7)
    spans = rasterize(plane, turn, 64, 64)
    assert spans.length.sum() > 500
    np.testing.assert_allclose(spans.interpolated_normals(), np.tile(turn @ UP, (spans.length.sum(), 1)),
                               atol=1e-14)


def test_nearer_surface_is_visible():
    back = _quad([(2, 2), (20, 2), (20, 20), (2, 20)], z=-1.0)
    front = _quad([(10, 10), (30, 10), (30, 30), (10, 30)], z=1.0)
    screen, normals = np.vstack([back[0], front[0]]), np.vstack([back[1], front[1]])
    faces = np.vstack([back[2], front[2] + 4])
    spans = rasterize_screen(screen, normals, faces, 32, 32)
    xy, span = spans.pixel_xy(), spans.pixel_span()
    overlap = (xy[:, 0] >= 10) & (xy[:, 0] < 20) & (xy[:, 1] >= 10) & (xy[:, 1] < 20)
    assert overlap.sum() == 2 * 100
    front_pixel = spans.face[span] >= 2
    np.testing.assert_array_equal(spans.visible, ~overlap | front_pixel)


def test_torus_hides_its_back_but_never_doubles_a_visible_pixel():
    spans = rasterize(torus(800), rotation(37), 128, 128)
    xy, unique = _coverage(spans)
    assert spans.visible.sum() == unique < len(xy)  # something is occluded


def test_image_places_visible_values_on_background():
    spans = rasterize(uv_sphere(6, 12), rotation(0), 40, 30)
    values = np.arange(spans.length.sum(), dtype=np.float64) + 1
    picture = image(spans, values, background=-1.0)
    assert picture.shape == (30, 40)
    xy = spans.pixel_xy()
    np.testing.assert_array_equal(picture[xy[:, 1], xy[:, 0]], values)
    assert (picture == -1).sum() == 40 * 30 - spans.length.sum()
    with pytest.raises(ValueError, match=r"^values must have one row per pixel \(\d+\), not shape \(3,\)$"):
        image(spans, np.zeros(3))


@pytest.mark.parametrize("polygons, ring, tube", [(288, 24, 12), (512, 32, 16), (800, 40, 20),
                                                   (1152, 48, 24), (18, 6, 3)])
def test_torus_polygon_counts(polygons, ring, tube):
    mesh = torus(polygons, major=1.0, minor=0.4)
    assert mesh.polygons == polygons == ring * tube
    assert mesh.faces.shape == (2 * polygons, 3) and len(mesh.vertices) == polygons
    np.testing.assert_allclose(np.linalg.norm(mesh.normals, axis=1), 1, atol=1e-12)
    assert len(np.unique(np.round(np.arctan2(mesh.vertices[:, 1], mesh.vertices[:, 0]), 9))) == ring
    distance = np.hypot(np.linalg.norm(mesh.vertices[:, :2], axis=1) - 1.0, mesh.vertices[:, 2])
    np.testing.assert_allclose(distance, 0.4, atol=1e-12)


def test_sphere_counts_and_outward_winding():
    for mesh in (uv_sphere(2, 3), uv_sphere(8, 16), torus(288)):
        tri = mesh.vertices[mesh.faces]
        facet = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
        assert np.all(np.einsum("ij,ij->i", facet, mesh.normals[mesh.faces].mean(1)) > 0)
    sphere = uv_sphere(8, 16)
    assert sphere.polygons == 128 and len(sphere.faces) == 2 * 16 + 2 * 6 * 16
    np.testing.assert_allclose(np.linalg.norm(sphere.vertices, axis=1), 1, atol=1e-12)


def test_rotation_is_orthonormal_and_turns_about_all_axes():
    np.testing.assert_array_equal(rotation(0), np.eye(3))
    for frame in (1, 37, 150, 199):
        r = rotation(frame)
        np.testing.assert_allclose(r @ r.T, np.eye(3), atol=1e-14)
        assert np.linalg.det(r) == pytest.approx(1)
    # half a turn about each axis: diag(1,-1,-1)·diag(-1,1,-1)·diag(-1,-1,1) = I
    np.testing.assert_allclose(rotation(100), np.eye(3), atol=1e-14)
    np.testing.assert_allclose(rotation(200), np.eye(3), atol=1e-14)
    # one small step: the generator is the sum of the three axes' generators
    angle = 2 * np.pi / 2000
    skew = (rotation(1, frames=2000) - rotation(1, frames=2000).T) / 2 / angle
    np.testing.assert_allclose(skew, [[0, -1, 1], [1, 0, -1], [-1, 1, 0]], atol=1e-2)


def test_rasterize_1152_torus_is_fast():
    mesh = torus(1152)
    start = time.perf_counter()
    for frame in (0, 33, 66):
        rasterize(mesh, rotation(frame), 256, 256)
    assert (time.perf_counter() - start) / 3 < 0.5


@pytest.mark.parametrize("call, message", [
    (lambda: torus(300), r"^polygons must be 2·k² for an integer k >= 3 \(.*\), not 300$"),
    (lambda: torus(8), r"^polygons must be 2·k² for an integer k >= 3 \(.*\), not 8$"),
    (lambda: torus(288.0), r"^polygons must be 2·k² for an integer k >= 3 \(.*\), not 288.0$"),
    (lambda: torus(288, major=1.0, minor=1.0),
     r"^radii must satisfy 0 < minor < major, not minor=1.0, major=1.0$"),
    (lambda: uv_sphere(1, 8), r"^stacks must be an integer >= 2, not 1$"),
    (lambda: uv_sphere(4, 2), r"^slices must be an integer >= 3, not 2$"),
    (lambda: rotation(1, frames=0), r"^frames must be an integer >= 1, not 0$"),
    (lambda: rotation(0.5), r"^frame must be an integer, not 0.5$"),
    (lambda: rasterize(torus(18), np.eye(3), 0, 8), r"^width must be an integer >= 1, not 0$"),
    (lambda: rasterize(torus(18), np.eye(3), 8, -2), r"^height must be an integer >= 1, not -2$"),
    (lambda: rasterize(torus(18), np.eye(2), 8, 8), r"^rotation must be a 3×3 matrix, not shape \(2, 2\)$"),
])
def test_bad_inputs_raise(call, message):
    with pytest.raises(ValueError, match=message):
        call()
