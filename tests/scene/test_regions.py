"""A domain's regions hold every input of the scene's frames, are tighter than the whole domain,
and the sampler draws only inside them."""

import dataclasses
import json
import math
import os

import numpy as np
import pytest

from phongfx.explore.compile.climb import inside, points, state_of
from phongfx.scene.domain import Options, domain
from phongfx.scene.file import load_scene
from phongfx.scene.geometry import frames
from phongfx.scene.regions import holds

SCENES = os.path.join(os.path.dirname(__file__), "..", "..", "scenes")


def _scene(name):
    return load_scene(os.path.join(SCENES, f"{name}.toml"))


def _angle(u, w):
    return np.degrees(np.arccos(np.clip(np.sum(u * w, -1), -1.0, 1.0)))


def _points(g):
    """The pixels' surface points and, on a mesh, their spans' end points (Lyon's span ends are
    on the same sphere as the pixel's point, and no vector depends on them)."""
    return (g.position,) if g.spans is None else (g.position, g.spans.pa[g.span], g.spans.pb[g.span])


def _holds(d, g, points=None):
    return holds(d.regions, g.n0, g.n1, g.normal, (g.v0, g.v1, g.viewer), g.material, g.n, points or (g.position,))


@pytest.mark.parametrize("name", ["lyon-balls", "torus", "two-lights", "local-mesh"])
def test_every_pixel_of_every_frame_lies_in_a_region(name):
    spec = _scene(name)
    geometries = frames(spec)
    d = domain(spec, geometries)
    assert len(d.regions) >= 9
    for g in geometries:
        assert np.all(_holds(d, g, _points(g)))
    # and the test has teeth: a frame's pixel moved past its region's limits falls out
    g = geometries[0]
    turned = dataclasses.replace(g, n1=-g.n1)
    assert not np.any(_holds(d, turned))


def test_lyon_regions_are_tighter_than_the_whole_image():
    spec = _scene("lyon-balls")
    d = domain(spec)
    assert len(d.regions) == 20 and d.max_span_angle_deg == pytest.approx(38.96, abs=0.01)
    for k, n in enumerate((1, 4, 16, 64, 256)):
        mine = [r for r in d.regions if r.where["sphere"] == k]
        assert all(r.materials == (("ball", (n,)),) for r in mine)  # one n per sphere
        assert sum(r.where["pixels"] for r in mine) == (3228 if k == 0 else 1964)  # every pixel, once
        # the bands cover θ from the sphere's centre to its limb, in order
        theta = [(math.degrees(math.acos(r.view_cos_max)), math.degrees(math.acos(r.view_cos_min))) for r in mine]
        assert theta[0][0] < 1.4 and theta[-1][1] == pytest.approx(87.82, abs=0.02)
        assert all(a[1] <= b[0] + 0.2 for a, b in zip(theta, theta[1:]))
        # near the centre the spans are far narrower than the image's widest
        assert mine[0].max_span_angle_deg < 16.6 < 0.45 * d.max_span_angle_deg
        assert mine[0].min_normal_length > 0.989 > d.min_normal_length
    widest = max(r.max_span_angle_deg for r in d.regions)
    assert d.max_span_angle_deg < widest <= d.max_span_angle_deg + 0.011  # the margin, no more


def test_mesh_patches_have_their_own_limits():
    d = domain(_scene("torus"))
    faces = sum(r.where["faces"] for r in d.regions)
    assert faces <= 576 and len(d.regions) == 11  # one of the twelve directions never faces the viewer
    assert all(d.view_cos_min - 1e-12 <= r.view_cos_min <= r.view_cos_max <= 1.0 for r in d.regions)
    assert min(r.view_cos_max for r in d.regions) < 0.6  # a patch that never faces the viewer squarely
    assert max(r.view_cos_min for r in d.regions) > -0.2  # ... and one that never reaches the silhouette
    assert min(r.max_span_angle_deg for r in d.regions) == pytest.approx(31.65, abs=0.01)
    assert d.max_span_angle_deg == pytest.approx(33.23, abs=0.01)
    for r in d.regions:  # each patch's ball lies in the domain's
        assert np.linalg.norm(np.subtract(r.ball[0], d.ball[0])) + r.ball[1] <= d.ball[1] + 1e-12


@pytest.mark.parametrize("name,options", [("lyon-balls", Options()), ("torus", Options()),
                                          ("local-mesh", Options()), ("torus", Options(pose="still"))])
def test_samples_lie_in_the_regions(name, options):
    spec = dataclasses.replace(_scene(name), domain=options)
    d = domain(spec)
    g = d.sample(30000, 4)
    assert np.all(_holds(d, g))
    # every region gets its share, and each region's own samples reach its span angle
    for index in range(len(d.regions)):
        sub = d.region(index)
        assert sub.regions == () and sub.region_name == d.regions[index].name
        part = sub.sample(2000, index)
        assert np.all(holds(d.regions[index:index + 1], part.n0, part.n1, part.normal,
                            (part.v0, part.v1, part.viewer), part.material, part.n, (part.position,)))
        assert np.max(_angle(part.n0, part.n1)) > 0.85 * sub.max_span_angle_deg
        assert np.allclose(part.normal, part.interpolated / np.linalg.norm(part.interpolated, axis=-1)[:, None])


def test_a_lyon_sample_is_on_its_sphere_with_its_n():
    d = domain(_scene("lyon-balls"))
    g = d.sample(20000, 9)
    sphere = np.round(g.position[:, 0] - g.normal[:, 0]).astype(int)
    assert np.allclose(g.position - np.stack([sphere, 0 * sphere, 0 * sphere], -1), g.normal)
    assert np.array_equal(g.n, np.array([1, 4, 16, 64, 256])[sphere])
    # far more wide spans where the image has them, none where it has not
    theta = np.degrees(np.arccos(g.normal[:, 2]))
    wide = _angle(g.n0, g.n1) > 20
    assert not np.any(wide & (theta < 29.9)) and np.mean(wide[theta > 50.1]) > 0.3


def test_as_dict_shows_the_regions():
    d = domain(_scene("lyon-balls"))
    out = json.loads(json.dumps(d.as_dict()))
    assert out["regions"]["count"] == 20 and len(out["regions"]["each"]) == 20
    first = out["regions"]["each"][0]
    assert first["n"] == {"ball": [1]} and first["sphere"] == 0 and first["max_span_angle_deg"] < 16.6
    assert first["theta_deg"][1] == pytest.approx(30.0, abs=0.05)
    assert "20 regions, span angles 15.69°..38.97°" in d.describe()
    assert domain(_scene("torus")).as_dict()["regions"]["count"] == 11


def test_the_local_search_keeps_to_the_regions():
    """A span as wide as the image's widest, at a sphere's centre, lies in the whole domain but
    in no region: the worst-input search rejects it (its witness would exceed a sound bound)."""
    d = domain(_scene("lyon-balls"))
    g = d.sample(256, 2)
    s = state_of(g, d)
    assert inside(s, points(s, d, g.rgb, g.bits), d).all()
    tilt = math.radians(d.max_span_angle_deg - 0.5)
    s.n0[:] = (-math.sin(tilt / 2), 0.0, math.cos(tilt / 2))
    s.n1[:] = (math.sin(tilt / 2), 0.0, math.cos(tilt / 2))
    moved = points(s, d, g.rgb, g.bits)
    whole = dataclasses.replace(d, regions=())
    assert inside(s, moved, whole).all() and not inside(s, moved, d).any()


def test_a_domain_with_regions_stays_hashable_and_comparable():
    d, again = domain(_scene("lyon-balls")), domain(_scene("lyon-balls"))
    assert d == again and hash(d) == hash(again) and hash(d.region(3)) == hash(again.region(3))
    assert d.region(3) != d.region(4)
