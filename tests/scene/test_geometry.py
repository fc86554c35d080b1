"""Per-frame geometry of scene files: the vectors every datapath of a scene is fed."""

import os

import numpy as np
import pytest

from phongfx.scene.file import SceneError, load_scene, parse_scene
from phongfx.scene.geometry import error_levels, frames, levels, rotation, scene_mesh, shade
from phongfx.scene.lyon import Scene, pixels
from phongfx.scene.mesh import fit_scale, rasterize, torus

SCENES = os.path.join(os.path.dirname(__file__), "..", "..", "scenes")


def _spec(lights=({"direction": [1, 2, 2]},), camera=None, objects=None, frames_=None, size=32, materials=None):
    data = {"lights": list(lights), "output": {"width": size, "height": size},
            "materials": materials or {"a": {"kd": 0.5, "ks": 0.25, "n": 8}, "b": {"kd": 0.9, "ks": 0.1, "n": [4, 40]}},
            "objects": objects or [{"type": "sphere", "material": "a", "stacks": 8, "slices": 12}]}
    if camera:
        data["camera"] = camera
    if frames_:
        data["frames"] = frames_
    return parse_scene(data, name="t")


def _unit(v):
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def test_rotation_about_an_axis():
    assert np.allclose(rotation((0, 0, 2), 90), [[0, -1, 0], [1, 0, 0], [0, 0, 1]])
    r = rotation((1, 1, 1), 120)  # a third of a turn about the diagonal cycles the axes
    assert np.allclose(r @ [1, 0, 0], [0, 1, 0])


def test_directional_light_and_viewer_at_infinity_are_constant():
    (g,) = frames(_spec())
    expected = np.array([1, 2, 2]) / 3
    for vectors in (g.l0[0], g.l1[0], g.light[0]):
        assert np.array_equal(vectors, np.broadcast_to(expected, vectors.shape))
    assert np.all(g.viewer == [0, 0, 1]) and np.all(g.v0 == [0, 0, 1]) and np.all(g.v1 == [0, 0, 1])
    assert g.light.shape == (1, len(g), 3) and np.array_equal(g.rgb, [[1.0, 1.0, 1.0]])


def test_point_light_and_local_viewer_point_from_the_surface():
    light, eye = np.array([2.0, 1.0, 3.0]), np.array([0.0, 0.0, 4.0])
    (g,) = frames(_spec(lights=[{"position": light.tolist()}], camera={"position": eye.tolist()}))
    for vectors in (g.l0[0], g.l1[0], g.light[0], g.v0, g.v1, g.viewer):
        assert np.allclose(np.linalg.norm(vectors, axis=1), 1)
    assert np.allclose(g.light[0], _unit(light - g.position))
    assert np.allclose(g.viewer, _unit(eye - g.position))
    first = g.a == 0  # at a span's first pixel the pixel's vector is the span-start one
    assert np.allclose(g.l0[0][first], g.light[0][first]) and np.allclose(g.v0[first], g.viewer[first])
    last = g.a == 1
    assert last.any() and np.allclose(g.l1[0][last], g.light[0][last])
    assert not np.allclose(g.light[0], g.light[0][0])  # it does vary


def test_positions_project_to_the_pixel_centres_and_lie_on_the_faces():
    spec = _spec(frames_={"count": 3, "axis": [1, 0, 1], "degrees": 90})
    mesh, _ = scene_mesh(spec)
    scale = fit_scale(mesh, 32, 32)
    for g in frames(spec):
        assert np.allclose(16 + scale * g.position[:, 0], g.col + 0.5)
        assert np.allclose(16 - scale * g.position[:, 1], g.row + 0.5)
        r = rotation(spec.frames.axis, g.frame * 30)
        tri = mesh.vertices[mesh.faces[g.spans.face[g.span]]] @ r.T
        facet = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
        assert np.allclose(np.einsum("ij,ij->i", g.position - tri[:, 0], _unit(facet)), 0, atol=1e-12)


def test_normals_spans_and_pixel_order():
    (g,) = frames(_spec())
    assert np.allclose(np.linalg.norm(g.normal, axis=1), 1)
    assert np.allclose(np.linalg.norm(g.n0, axis=1), 1) and np.allclose(np.linalg.norm(g.n1, axis=1), 1)
    assert np.array_equal(g.n0, g.spans.na[g.span]) and np.array_equal(g.n1, g.spans.nb[g.span])
    steps = g.spans.pixel_step()[g.spans.visible]
    assert np.all(g.a[steps == 0] == 0) and np.all((g.a > 0)[steps > 0])
    key = g.row * 32 + g.col
    assert np.all(np.diff(key) > 0)  # scanline order, each pixel once
    interpolated = g.n0 + g.a[:, None] * (g.n1 - g.n0)
    assert np.allclose(g.normal, _unit(interpolated))


def test_torus_frames_match_mesh_rasterize():
    spec = load_scene(os.path.join(SCENES, "torus.toml"))
    geometries = frames(spec)
    assert [g.frame for g in geometries] == [0, 1, 2, 3]
    mesh = torus(288)
    for g in geometries:
        spans = rasterize(mesh, rotation((1, 1, 0), 22.5 * g.frame), 96, 96)
        assert len(g) == spans.visible.sum() > 1000
        assert np.all(g.n == 16) and np.all(g.kd == 0.6) and np.all(g.ks == 0.4)
    assert len(geometries[0]) != len(geometries[2])  # the rotation changes the image


def test_objects_concatenate_with_their_materials():
    objects = [{"type": "sphere", "material": "a", "offset": [-1.5, 0, 0]},
               {"type": "torus", "material": "b", "polygons": 32, "scale": 0.8, "offset": [1.5, 0, 0]}]
    (g,) = frames(_spec(objects=objects))
    left = g.col < 16
    assert np.all(g.material[left] == 0) and np.all(g.material[~left] == 1)
    assert np.all(g.kd[left] == 0.5) and np.all(g.kd[~left] == 0.9)
    assert np.all(g.n[left] == 8) and np.all(g.n[~left] == 4)  # a range gives its n_lo


def test_lyon_spheres_follow_phongfx_scene():
    spec = load_scene(os.path.join(SCENES, "lyon-balls.toml"))
    (g,) = frames(spec)
    px = pixels(Scene(32, (1, 4, 16, 64, 256), span=8))
    assert np.array_equal(g.row, px.row) and np.array_equal(g.col, px.col)
    assert np.array_equal(g.n, px.n) and g.spans is None
    assert np.allclose(np.linalg.norm(g.position - [[s, 0, 0] for s in px.sphere], axis=1), 1)
    starts = np.flatnonzero(np.diff(g.span)) + 1
    assert np.all(g.a[starts] == 0) and np.all(np.diff(g.span) >= 0)
    assert np.allclose(g.light[1], np.array([1, -1, 1]) / np.sqrt(3))
    # Phong's normal: the span's interpolated normal, normalized; not the sphere's inside a span
    lerp = (1 - g.a[:, None]) * px.n0 + g.a[:, None] * px.n1
    assert np.allclose(g.normal, lerp / np.linalg.norm(lerp, axis=1, keepdims=True))
    inside = (g.a > 0) & (g.a < 1)
    assert np.abs(g.normal[inside] - px.normal[inside]).max() > 1e-3


def test_point_light_on_the_surface_is_refused():
    with pytest.raises(ValueError, match=r"^lights\[0\]\.position lies on the surface in frame 0, "
                                         r"not in front of it$"):
        frames(_spec(lights=[{"position": frames(_spec())[0].position[40].tolist()}]))


def test_shade_levels_and_errors():
    (g,) = frames(_spec(lights=[{"direction": [0, 0, 1], "intensity": 0.5}, {"direction": [1, 0, 0]}]))
    p = len(g)
    diff = np.stack([np.full(p, 0.4), np.full(p, 0.2)])
    spec = np.stack([np.full(p, 0.8), np.full(p, 0.4)])
    # 0.5 * (0.5*0.4 + 0.25*0.8) + 1 * (0.5*0.2 + 0.25*0.4) = 0.2 + 0.2, in every channel
    assert shade(g, diff, spec).shape == (p, 3) and np.allclose(shade(g, diff, spec), 0.4)
    assert np.all(shade(g, diff * 10, spec) == 1.0) and np.all(shade(g, -diff, -spec) == 0.0)
    # the backside test: no specular where the light is behind the surface (diff = 0)
    assert np.allclose(shade(g, np.zeros_like(diff), spec), 0.0)
    assert levels([0.0, 0.4, 0.5 / 255, 0.49 / 255, 1.0], 8).tolist() == [0, 102, 1, 0, 255]
    assert error_levels([0.5, 0.0], [0.25, 1.0], 2).tolist() == [0.75, 3.0]
    with pytest.raises(ValueError, match=r"^diff and spec must have shape \(lights, pixels\) = "
                                         rf"\(2, {p}\), not \(1, {p}\) and \(2, {p}\)$"):
        shade(g, diff[:1], spec)


def test_shade_colours_and_ambient():
    (g,) = frames(_spec(lights=[{"direction": [0, 0, 1], "colour": [1.0, 0.5, 0.0]}],
                        materials={"a": {"kd": 0.5, "ks": 0.25, "n": 16, "ka": 0.1, "colour": [1, 0.8, 0.5]}}))
    p = len(g)
    diff, spec = np.full((1, p), 0.4), np.full((1, p), 0.8)
    # M_c·(ka + L_c·(kd·diff + ks·spec)) = M_c·(0.1 + L_c·0.4)
    assert np.allclose(shade(g, diff, spec), [1.0 * 0.5, 0.8 * 0.3, 0.5 * 0.1])


def test_a_camera_path_moves_the_local_viewer_frame_by_frame():
    path = [[0, 0, 4], [3, 0, 3]]
    moving = frames(_spec(camera={"position": [0, 0, 4]}, frames_={"count": 2, "camera_path": path}))
    still = frames(_spec(camera={"position": [0, 0, 4]}, frames_={"count": 2}))
    for g, position in zip(moving, path):
        assert np.allclose(g.viewer, _unit(np.asarray(position, float) - g.position))
    assert np.allclose(moving[0].viewer, still[0].viewer)
    assert not np.allclose(moving[1].viewer, still[1].viewer)


@pytest.mark.parametrize("camera, frames_, message", [
    (None, {"count": 1, "camera_path": [[0, 0, 4]]},
     r"^t: frames\.camera_path moves a local camera: give camera\.position, not a camera at infinity$"),
    ({"position": [0, 0, 4]}, {"count": 2, "camera_path": [[0, 0, 4]]},
     r"^t: frames\.camera_path must be an array of frames\.count = 2 positions, not \[\[0, 0, 4\]\]$"),
    ({"position": [0, 0, 4]}, {"count": 1, "camera_path": [[0, 4]]},
     r"^t: frames\.camera_path\[0\] must be 3 numbers, not \[0, 4\]$"),
])
def test_bad_camera_paths(camera, frames_, message):
    with pytest.raises(SceneError, match=message):
        _spec(camera=camera, frames_=frames_)


def test_pixel_error_and_the_terminator_band():
    from phongfx.scene.geometry import pixel_error, terminator_lit
    assert pixel_error([[10, 0, 255]], [[10.4 / 255, 0.6 / 255, 1.0]], 8).tolist() == [[0, 1, 0]]
    cosine = np.array([-0.5, -0.002, 0.0, 0.003, 0.5])
    shader = np.array([True, True, False, False, False])
    # within 1/255 of N·L = 0 the shader's own test decides; outside it, the exact one
    assert terminator_lit(cosine, shader, 8).tolist() == [False, True, False, False, True]
    assert terminator_lit(cosine, None, 8).tolist() == [False, False, False, True, True]
