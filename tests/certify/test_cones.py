"""Cones of point lights and a local viewer: every widening holds on sampled geometry."""

from dataclasses import replace

import numpy as np

from phongfx.certify.bound import shader_config
from phongfx.certify.cones import Direction, Directions, directions
from phongfx.certify.datapath import interpolated
from phongfx.certify.figures import FIG7_BOUND
from phongfx.certify.outputs import box_errors
from phongfx.certify.sphere import cover, frame
from phongfx.golden.fixed import Fixed
from phongfx.golden.lirp import lirp
from phongfx.golden.normalize import normalize
from phongfx.scene.domain import domain
from phongfx.scene.file import load_scene


def _unit(v):
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def _in_cone(axis, half, count, g):
    """``count`` unit vectors within ``half`` (radians) of ``axis``, the rim included."""
    a, e1, e2 = frame(axis)
    t = half * np.sqrt(g.uniform(0, 1, count))
    t[: count // 10] = half
    p = g.uniform(0, 2 * np.pi, count)
    return (np.cos(t)[:, None] * a + np.sin(t)[:, None] * (np.cos(p)[:, None] * e1 + np.sin(p)[:, None] * e2))


def test_projections_widen_over_the_cones():
    """N̂·V, N̂·L and R̂·L at random points of random boxes, V and L anywhere in their cones,
    lie in the ranges the boxes get; so do R's components."""
    g = np.random.default_rng(3)
    view = Direction(tuple(_unit(np.array([0.1, -0.2, 1.0]))), np.radians(15), True)
    light = Direction(tuple(_unit(np.array([1.0, 1.0, 1.5]))), np.radians(20), True)
    cones = Directions(view, [light], -1.0, np.pi)
    boxes = cover(-1.0, 1.0, [(1, 0)], 6, 12)
    pick = g.integers(0, len(boxes), 4000)
    box = boxes.take(pick)
    theta = g.uniform(box.theta[:, 0], box.theta[:, 1])
    phi = g.uniform(box.phi[:, 0], box.phi[:, 1])
    v0, e1, e2 = cones.basis
    n = (np.cos(theta)[:, None] * v0 + np.sin(theta)[:, None] * (np.cos(phi)[:, None] * e1
                                                                + np.sin(phi)[:, None] * e2))
    v = _in_cone(view.axis, view.half, len(n), g)
    l = _in_cone(light.axis, light.half, len(n), g)
    p, q = np.sum(n * v, -1), np.sum(n * l, -1)
    r = 2 * p[:, None] * n - v
    for value, (lo, hi) in ((p, cones.p(box)), (q, cones.q(box, 0)), (np.sum(r * l, -1), cones.c(box, 0))):
        assert np.all((lo <= value) & (value <= hi))
        assert np.max(hi - lo) > 0.5  # the cones do widen them
    lo, hi = cones.reflected(box, (np.ones(len(n)), np.ones(len(n))), 2)
    assert np.all((lo <= r + 1e-12) & (r <= hi + 1e-12))


def _spans(dom, position, count, g, span=None):
    """Span ends ``x0``, ``x1`` in the ball at most ``span`` apart, ``a``, and the unit vectors
    toward ``position`` from both ends and from the pixel ``(1-a)x0 + a·x1``."""
    centre, radius = np.asarray(dom.ball[0]), dom.ball[1]
    span = dom.max_span_length if span is None else span
    x0 = centre + _unit(g.normal(size=(count, 3))) * radius * g.uniform(0, 1, (count, 1)) ** (1 / 3)
    x1 = x0 + _unit(g.normal(size=(count, 3))) * span * g.uniform(0.5, 1, (count, 1))
    keep = np.linalg.norm(x1 - centre, axis=-1) <= radius
    x0, x1 = x0[keep], x1[keep]
    a = g.uniform(0, 1, len(x0))
    x = (1 - a)[:, None] * x0 + a[:, None] * x1
    return a, _unit(position - x0), _unit(position - x1), _unit(position - x)


def test_span_ends_lie_within_the_chord_and_the_bend():
    """On local-mesh's light and a light near the ball: ``|l1 - l0| <= chord`` and the
    interpolated direction within ``bend`` of the pixel's, both reached to within a factor."""
    spec = load_scene("scenes/local-mesh.toml")
    dom = domain(spec)
    g = np.random.default_rng(5)
    near = replace(dom, lights=(("point", (0.0, 1.9, 0.8), (1.0, 1.0, 1.0)),), max_span_length=0.8)
    for case in (dom, near):
        position = np.asarray(case.lights[0][1])
        light = directions(case).lights[0]
        a, l0, l1, ref = _spans(case, position, 200_000, g)
        chord = np.linalg.norm(l1 - l0, axis=-1)
        bend = np.linalg.norm(_unit((1 - a)[:, None] * l0 + a[:, None] * l1) - ref, axis=-1)
        assert chord.max() <= light.chord and bend.max() <= light.bend
        assert chord.max() > 0.3 * light.chord and bend.max() > 0.1 * light.bend
        axis = np.asarray(light.axis)
        assert np.degrees(np.arccos(np.min(ref @ axis))) <= np.degrees(light.half)


def test_the_hardware_direction_is_within_its_interval():
    """The golden LIRP and normalizer on encoded span ends: inside the Interval's range and
    within its deviation of the ideal ``g(|L'|²)·L'``."""
    spec = load_scene("scenes/local-mesh.toml")
    dom = domain(spec)
    g = np.random.default_rng(7)
    for params in ({}, {"vec_frac": 8, "order": 1}):
        unit = shader_config("fig7", params, spec).units[0]
        light = directions(dom).lights[0]
        got = interpolated(unit, light, 1)
        a, l0, l1, _ = _spans(dom, np.asarray(dom.lights[0][1]), 20_000, g)
        end, af = unit.lirp.fmt("vec"), unit.lirp.fmt("a")
        codes = [Fixed.from_float(v, end, "round_half_up", "saturate") for v in (l0, l1)]
        a_code = Fixed.from_float(a, af, "round_half_up", "saturate")
        out = normalize(unit.direction_normalize, lirp(unit.lirp, *codes, a_code)["n"])["n"].to_float()
        exact = (1 - a)[:, None] * l0 + a[:, None] * l1
        z = np.sum(exact * exact, -1)[:, None]
        y = 1 - z
        ideal = exact * (1 + y / 2 if unit.direction_normalize.order == 1 else 1 + (y + y * y) / 2)
        assert np.all((got.lo[0] <= out) & (out <= got.hi[0]))
        assert np.max(np.abs(out - ideal)) <= got.dev[0, 0]
        assert np.max(np.abs(out - ideal)) > 0.3 * got.dev[0, 0]


def test_directional_scenes_take_the_old_geometry():
    """The torus (lights and viewer at infinity): its Directions are the old constants, and the
    box errors with them are those of the old call, exactly."""
    spec = load_scene("scenes/torus.toml")
    dom = domain(spec)
    cones = directions(dom)
    assert not cones.local and cones.view.half == 0 and all(light.half == 0 for light in cones.lights)
    shader = shader_config("fig7", {}, spec)
    boxes = cover(dom.view_cos_min, dom.min_normal_length, [(16, 0), (40, 0)], 6, 12)
    lights = [np.asarray(v) for _, v, _ in dom.lights]
    old = box_errors(shader, FIG7_BOUND, "phong", boxes, frame(dom.camera[1]), lights, dom.min_normal_length)
    new = box_errors(shader, FIG7_BOUND, "phong", boxes, cones.basis, None, dom.min_normal_length, cones)
    for a, b in zip(old[:2] + old[3:], new[:2] + new[3:]):
        assert np.array_equal(a, b)


def test_a_camera_path_gets_one_cone_holding_every_position():
    spec = load_scene("scenes/local-mesh.toml")
    dom = domain(spec)
    path = ((0.0, 0.0, 4.0), (2.0, 0.0, 3.5), (-1.0, 1.5, 4.5))
    moving = replace(dom, camera_path=path)
    view, still = directions(moving).view, directions(dom).view
    assert view.local and view.half > still.half
    g = np.random.default_rng(9)
    axis = np.asarray(view.axis)
    for position in path:
        _, v0, _, ref = _spans(moving, np.asarray(position), 20_000, g)
        assert np.min(np.concatenate([v0, ref]) @ axis) >= np.cos(view.half)


def test_a_light_inside_the_ball_or_a_constant_input_says_why_not():
    spec = load_scene("scenes/local-mesh.toml")
    dom = domain(spec)
    shader = shader_config("fig7", {}, spec)
    assert FIG7_BOUND.why_not(shader, dom) is None
    inside = replace(dom, lights=(("point", (0.0, 0.0, 0.5), (1.0, 1.0, 1.0)),))
    assert FIG7_BOUND.why_not(shader, inside).startswith("the point light 0 lies inside the objects' bounding ball")
    constant = replace(shader, units=(shader.units[0].replace(local_lights=False),))
    assert FIG7_BOUND.why_not(constant, dom) == "light 0 is a point light but the datapath takes it as a constant"
