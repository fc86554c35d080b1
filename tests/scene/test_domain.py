"""A scene's input domain holds every pixel the scene's frames feed, under other motions too;
its samples lie in it; the [domain] table's errors name file, field, value and range."""

import copy
import dataclasses
import json
import math
import os

import numpy as np
import pytest

from phongfx.scene import sampling
from phongfx.scene.domain import Options, domain
from phongfx.scene.file import Frames, SceneError, load_scene, parse_scene
from phongfx.scene.geometry import frames
from phongfx.scene.lyon import Scene, pixels

SCENES = os.path.join(os.path.dirname(__file__), "..", "..", "scenes")
TOL = 1e-9


def _scene(name):
    return load_scene(os.path.join(SCENES, f"{name}.toml"))


def _angle(u, w):
    return np.degrees(np.arccos(np.clip(np.sum(u * w, -1), -1.0, 1.0)))


def _ends(spec, g):
    """(x0, x1) the span end points of each pixel of frame ``g``."""
    if g.spans is not None:
        return g.spans.pa[g.span], g.spans.pb[g.span]
    p = spec.objects[0].params
    px = pixels(Scene(p["radius"], p["shininess"], span=p["span"]))
    centre = np.stack([px.sphere, np.zeros(len(px)), np.zeros(len(px))], -1)
    return px.n0 + centre, px.n1 + centre


def assert_inside(d, g, ends=None):
    """Every pixel of ``g`` lies in the domain ``d`` (the bounds the module docstring derives)."""
    for n in (g.n0, g.n1, g.normal):
        for v in (g.v0, g.v1, g.viewer):
            assert np.min(np.sum(n * v, -1)) >= d.view_cos_min - TOL
    assert np.max(_angle(g.n0, g.n1)) <= d.max_span_angle_deg + 1e-6
    assert np.min(np.linalg.norm(g.interpolated, axis=-1)) >= d.min_normal_length - TOL
    assert np.all((g.a >= 0) & (g.a <= 1))
    centre, radius = np.asarray(d.ball[0]), d.ball[1]
    x0, x1 = ends if ends is not None else (g.position, g.position)
    for x in (g.position, x0, x1):
        assert np.max(np.linalg.norm(x - centre, axis=-1)) <= radius * (1 + TOL)
    assert np.max(np.linalg.norm(x1 - x0, axis=-1), initial=0) <= d.max_span_length * (1 + TOL)
    for i, cone in enumerate(d.light_cones):  # toward a point light: within its cone
        if cone is not None:
            for vectors in (g.l0[i], g.l1[i], g.light[i]):
                assert np.min(vectors @ np.asarray(cone[0])) >= math.cos(math.radians(cone[1])) - TOL
    for vectors in (g.v0, g.v1, g.viewer) if d.viewer_cones else ():  # within a camera position's cone
        inside = [vectors @ np.asarray(axis) >= math.cos(math.radians(half)) - TOL for axis, half in d.viewer_cones]
        assert np.all(np.any(inside, axis=0))
    for m, (name, values) in enumerate(d.materials):
        mine = g.material == m
        assert np.all(np.isin(g.n[mine], values)), name


@pytest.mark.parametrize("name", ["torus", "local-mesh", "lyon-balls"])
def test_every_pixel_of_every_frame_lies_in_the_domain(name):
    spec = _scene(name)
    geometries = frames(spec)
    d = domain(spec, geometries)
    for g in geometries:
        assert_inside(d, g, _ends(spec, g))
    # the bounds are not vacuous: the frames themselves come close to them
    assert max(np.max(_angle(g.n0, g.n1)) for g in geometries) >= 0.75 * d.max_span_angle_deg
    if d.view_cos_min < 0:
        assert min(np.min(np.sum(g.normal * g.viewer, -1)) for g in geometries) <= 0.6 * d.view_cos_min


def test_a_narrower_claim_than_the_rasterizer_is_caught():
    spec = dataclasses.replace(_scene("torus"), domain=Options(max_span_angle_deg=10.0))
    g = frames(spec)[0]
    with pytest.raises(AssertionError):
        assert_inside(domain(spec), g, _ends(spec, g))


def test_derived_values_of_the_example_scenes():
    torus = domain(_scene("torus"))
    assert (torus.pose, torus.degrees, torus.axis) == ("motion", (0.0, 90.0), pytest.approx((0.5 ** 0.5,) * 2 + (0,)))
    assert torus.ball == ((0.0, 0.0, 0.0), pytest.approx(1.4))  # major + minor radius
    assert torus.face_cap_deg == pytest.approx(16.62, abs=0.01) and torus.view_tilt_deg == 0.0
    assert torus.view_cos_min == pytest.approx(-math.sin(math.radians(torus.face_cap_deg)))
    assert torus.max_span_angle_deg == pytest.approx(33.23, abs=0.01)
    assert torus.min_normal_length == pytest.approx(math.cos(math.radians(33.226 / 2)), abs=1e-4)
    assert torus.materials == (("shiny", (16,)),) and torus.lights[0][0] == "directional"
    local = domain(_scene("local-mesh"))
    # a viewer at (0, 0, 4) seen from a ball of radius 1.312: within asin(1.312/4) of the axis
    assert local.view_tilt_deg == pytest.approx(math.degrees(math.asin(local.ball[1] / 4)))
    assert local.materials == (("clay", tuple(range(16, 33))),) and local.camera == ("point", (0.0, 0.0, 4.0))
    lyon = domain(_scene("lyon-balls"))
    assert (lyon.pose, lyon.view_cos_min, lyon.ball) == ("still", 0.0, ((2.0, 0.0, 0.0), 3.0))
    assert lyon.max_span_angle_deg == pytest.approx(38.96, abs=0.01)  # 8-pixel spans on radius 32
    assert lyon.materials == (("ball", (1, 4, 16, 64, 256)),)


@pytest.mark.parametrize("axis", [(1.0, 0.0, 0.0), (0.0, 0.0, 1.0), (0.0, 1.0, 0.0)])
def test_the_torus_turned_about_other_axes_stays_in_the_domain(axis):
    spec = _scene("torus")
    other = dataclasses.replace(spec, frames=Frames(32, axis, 360.0), domain=Options(pose="any"))
    d = domain(other)
    assert d.pose == "any" and d.view_cos_min == domain(spec).view_cos_min  # pose-independent bounds
    for g in frames(other):
        assert_inside(d, g, _ends(other, g))


def test_two_objects_a_camera_path_and_a_point_light():
    data = copy.deepcopy(BASE)
    data["materials"]["m"]["n"] = [3, 5]
    data["objects"].append({"type": "torus", "material": "spare", "polygons": 32, "scale": 0.5,
                            "offset": [1.5, 0, 0]})
    data["lights"].append({"position": [0, 3, 3]})
    data["camera"] = {"position": [0, 0, 6]}
    data["frames"] = {"count": 3, "axis": [0, 0, 1], "degrees": 120, "camera_path": [[0, 0, 6], [1, 0, 5], [0, 2, 6]]}
    data["output"] = {"width": 48, "height": 48}
    spec = parse_scene(data, name="t")
    d = domain(spec)
    assert d.ball[1] == pytest.approx(1.5 + 0.5 * 1.4) and len(d.camera_path) == 3
    assert d.materials == (("m", (3, 4, 5)), ("spare", (2,)))
    for g in frames(spec):
        assert set(g.material) == {0, 1}
        assert_inside(d, g, _ends(spec, g))
    g = d.sample(4000, 2)
    assert_inside(d, g)
    assert set(g.n[g.material == 0]) == {3.0, 4.0, 5.0} and set(g.n[g.material == 1]) == {2.0}
    cameras = np.asarray(spec.frames.camera_path)
    toward = (cameras[None] - g.position[:, None]) / np.linalg.norm(cameras[None] - g.position[:, None], axis=-1,
                                                                     keepdims=True)
    assert np.all(np.min(np.linalg.norm(toward - g.viewer[:, None], axis=-1), axis=1) < 1e-9)  # toward a path point


def test_a_mesh_wound_inside_out_widens_the_bounds_to_everything():
    spec = _scene("torus")
    obj = spec.objects[0]
    mesh = obj.params["mesh"]
    flipped = dataclasses.replace(mesh, faces=mesh.faces[:, ::-1].copy())
    spec = dataclasses.replace(spec, objects=(dataclasses.replace(obj, params={**obj.params, "mesh": flipped}),))
    d = domain(spec)
    assert d.face_cap_deg > 90 and d.view_cos_min == -1.0
    for g in frames(spec):  # the rasterizer now draws the far side: normals facing away
        assert np.min(np.sum(g.normal * g.viewer, -1)) < -0.9
        assert_inside(d, g, _ends(spec, g))


@pytest.mark.parametrize("name,options", [
    ("torus", Options()), ("torus", Options(pose="any")), ("torus", Options(pose="still", wobble_degrees=20)),
    ("local-mesh", Options()), ("lyon-balls", Options())])
def test_samples_lie_in_the_domain(name, options):
    spec = dataclasses.replace(_scene(name), domain=options)
    d = domain(spec)
    g = d.sample(20000, 5)
    assert len(g) == 20000 and g.frame == -1 and g.spans is None and list(g.span) == list(range(20000))
    assert g.l0.shape == (len(spec.lights), 20000, 3) and g.bits == spec.output.bits
    assert_inside(d, g)  # the span ends are not kept: span_end is checked on its own below
    assert np.allclose(g.normal, g.interpolated / np.linalg.norm(g.interpolated, axis=-1, keepdims=True))
    assert 0.01 < np.mean(g.a == 0) < 0.03 and 0.01 < np.mean(g.a == 1) < 0.03
    for i, light in enumerate(spec.lights):
        want = (np.asarray(light.vector) - g.position) if light.kind == "point" else np.asarray(light.vector)
        assert np.allclose(g.light[i], want / np.linalg.norm(want, axis=-1, keepdims=True))
    if spec.camera.kind == "point":
        want = np.asarray(spec.camera.vector) - g.position
        assert np.allclose(g.viewer, want / np.linalg.norm(want, axis=-1, keepdims=True))
    material = spec.materials[d.materials[0][0]]
    assert np.all(g.kd == material.kd) and np.all(g.ks == material.ks) and np.all(g.colour == material.colour)
    # the sample reaches toward the bounds, not only the middle of the domain
    assert np.max(_angle(g.n0, g.n1)) > 0.9 * d.max_span_angle_deg
    assert len(np.unique(g.n)) == len(d.materials[0][1])


def test_sampling_is_deterministic_and_chunked(monkeypatch):
    d = domain(_scene("local-mesh"))
    one, again, other = d.sample(3000, 7), d.sample(3000, 7), d.sample(3000, 8)
    assert np.array_equal(one.n0, again.n0) and np.array_equal(one.light, again.light)
    assert not np.array_equal(one.n0, other.n0)
    monkeypatch.setattr(sampling, "CHUNK", 1000)
    whole = d.sample(2500, 3)
    parts = list(d.chunks(2500, 3))
    assert [len(p) for p in parts] == [1000, 1000, 500]
    for key in ("n0", "n1", "a", "position", "viewer", "n", "material"):
        assert np.array_equal(getattr(whole, key), np.concatenate([getattr(p, key) for p in parts]))
    assert len(d.sample(0, 1)) == 0
    with pytest.raises(ValueError, match=r"^count must be a non-negative integer, not -1$"):
        d.sample(-1, 1)


def test_fixed_directions_stay_broadcasts():
    g = domain(_scene("torus")).sample(200000, 1)
    assert g.light.strides[1] == 0 and g.viewer.strides[0] == 0  # not 200000 copies of one vector
    assert np.allclose(g.light[0, -1], 3 ** -0.5)


def test_user_span_angle_is_a_claim():
    spec = dataclasses.replace(_scene("torus"), domain=Options(max_span_angle_deg=10.0))
    d = domain(spec)
    assert d.max_span_angle_deg == 10.0 and d.user_span_angle
    assert d.derived_span_angle_deg == pytest.approx(33.23, abs=0.01)
    assert d.min_normal_length == pytest.approx(math.cos(math.radians(5)))
    out = json.loads(json.dumps(d.as_dict()))
    assert out["max_span_angle_source"].startswith("user claim") and out["derived_max_span_angle_deg"] > 33
    assert "the [domain] table's claim (derived: 33.23°)" in d.describe()
    assert np.max(_angle(*(lambda g: (g.n0, g.n1))(d.sample(5000, 1)))) <= 10 + 1e-9


def test_as_dict_and_describe():
    d = domain(_scene("local-mesh"))
    out = json.loads(json.dumps(d.as_dict()))
    light = np.array([2.0, 2.0, 3.0])
    assert out["lights"][0]["cone"]["axis"] == pytest.approx(list(light / np.linalg.norm(light)))
    assert out["lights"][0]["cone"]["half_angle_deg"] == pytest.approx(math.degrees(math.asin(d.ball[1] / 17 ** 0.5)))
    assert out["camera"]["cones"] == [{"axis": [0.0, 0.0, 1.0], "half_angle_deg": pytest.approx(d.view_tilt_deg)}]
    assert domain(_scene("torus")).as_dict()["lights"][0]["cone"] is None
    assert out["pose"] == "motion" and out["materials"] == [{"name": "clay", "n": {"range": [16, 32]}}]
    assert out["ball"]["radius"] == d.ball[1] and out["samples"] == 1_000_000 and out["final_samples"] == 2_000_000
    assert out["description"] == d.describe()
    assert d.describe().startswith("Poses: the continuous rotation about (0, 1, 0) over [0°, 30°]")
    assert "still" in domain(_scene("lyon-balls")).pose


BASE = {
    "lights": [{"direction": [1, 1, 1]}],
    "materials": {"m": {"kd": 0.5, "ks": 0.5, "n": 16}, "spare": {"kd": 0.1, "ks": 0.1, "n": 2}},
    "objects": [{"type": "sphere", "material": "m"}],
    "output": {"width": 16, "height": 16},
}


def _parse(table, frames_table=None):
    data = copy.deepcopy(BASE)
    data["domain"] = table
    if frames_table:
        data["frames"] = frames_table
    return parse_scene(data, name="t")


def test_domain_table_is_read():
    spec = _parse({"pose": "still", "wobble_degrees": 12.5, "samples": 10, "final_samples": 20, "seed": 4})
    assert spec.domain == Options("still", 12.5, None, 10, 20, 4)
    d = domain(spec)
    assert (d.pose, d.wobble_degrees, d.samples, d.final_samples, d.seed) == ("still", 12.5, 10, 20, 4)
    assert d.materials == (("m", (16,)), ("spare", ()))  # an unused material admits no n
    assert set(d.sample(1000, 1).material) == {0}
    assert domain(_parse({}, {"count": 3, "degrees": 60})).pose == "motion"
    assert domain(_parse({})).pose == "still" and parse_scene(copy.deepcopy(BASE), name="t").domain == Options()


@pytest.mark.parametrize("table,frames_table,message", [
    ({"pose": "spin"}, None, r"^t: domain\.pose must be one of motion, any, still, not 'spin'$"),
    ({"wobble_degrees": 200}, None, r"^t: domain\.wobble_degrees must be a number in \[0, 180\], not 200$"),
    ({"wobble_degrees": 2}, {"count": 4, "degrees": 90},
     r"^t: domain\.wobble_degrees applies only to pose \"still\", not to pose 'motion' "
     r"\(the default for frames\.count = 4\)$"),
    ({"pose": "any", "wobble_degrees": 2}, None,
     r"^t: domain\.wobble_degrees applies only to pose \"still\", not to pose 'any'$"),
    ({"max_span_angle_deg": -1}, None, r"^t: domain\.max_span_angle_deg must be a number in \[0, 180\], not -1$"),
    ({"samples": 0}, None, r"^t: domain\.samples must be an integer in 1\.\.10000000000, not 0$"),
    ({"final_samples": 1.5}, None, r"^t: domain\.final_samples must be an integer in 1\.\.10000000000, not 1\.5$"),
    ({"seed": "x"}, None, r"^t: domain\.seed must be an integer in 0\.\.9223372036854775807, not 'x'$"),
    ({"size": 3}, None, r"^t: domain: unknown key 'size'; allowed: pose, wobble_degrees, max_span_angle_deg, "
                        r"samples, final_samples, seed$"),
    (3, None, r"^t: domain must be a table, not 3$"),
])
def test_domain_table_errors(table, frames_table, message):
    with pytest.raises(SceneError, match=message):
        _parse(table, frames_table)


def test_the_scene_page_gives_the_derived_values():
    with open(os.path.join(SCENES, "..", "docs", "scenes.rst"), encoding="utf-8") as file:
        page = file.read()
    rows = {name: page[page.index(f"| {name} "):].split("\n+")[0] for name in ("torus", "local-mesh", "lyon-balls")}
    for name, row in rows.items():
        d = domain(_scene(name))
        cos = "0" if d.view_cos_min == 0 else f"−{-d.view_cos_min:.3f}"
        assert cos in row and f"{d.max_span_angle_deg:.1f}°" in row and f"{d.ball[1]:.3g}" in row, name
