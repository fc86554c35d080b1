"""Cells of surface points: the cone of a cell holds every direction from the ball's points in it,
a cell is halved along its longest edge when it is a box's widest side, and on the local mesh
cells bring the conventional unit's bound down and certify a narrower design."""

from dataclasses import replace

import numpy as np
import pytest

from phongfx.certify import certify
from phongfx.certify.bound import shader_config
from phongfx.certify.branch import bound_boxes, cases
from phongfx.certify.cells import meets, positions, root, scale, toward
from phongfx.certify.cones import directions
from phongfx.certify.sphere import Boxes, cover
from phongfx.certify.table_units import CONVENTIONAL_BOUND
from phongfx.scene.domain import domain
from phongfx.scene.file import load_scene


def _local_mesh():
    spec = load_scene("scenes/local-mesh.toml")
    return spec, domain(spec)


def _points_in(cell, centre, radius, count, rng):
    """``count`` points of the ball in the axis-aligned ``cell`` (rejection from the cell)."""
    x = rng.uniform(cell[0], cell[1], (count * 8, 3))
    x = x[np.linalg.norm(x - centre, axis=-1) <= radius]
    return x[:count]


def test_a_cells_cone_holds_every_direction_from_its_points():
    spec, dom = _local_mesh()
    centre, radius = np.asarray(dom.ball[0]), dom.ball[1]
    rng = np.random.default_rng(3)
    lo = rng.uniform(-radius, radius * 0.6, (200, 3))
    cells = np.stack([lo, lo + rng.uniform(0.05, 0.8, (200, 3))], axis=1)
    cells = np.concatenate([root(dom, 1), cells])
    lights, camera = positions(dom)
    assert len(lights) == 1 and len(lights[0]) == 1 and len(camera) == 1
    for where in (lights[0], camera):
        axis, half = toward(dom, cells, where)
        checked = 0
        for cell, a, h, inside in zip(cells, axis, half, meets(dom, cells)):
            x = _points_in(cell, centre, radius, 500, rng)
            assert inside == (len(x) > 0) or not inside  # no point of the ball outside a cell that misses it
            if not len(x):
                continue
            d = where[0] - x
            d /= np.linalg.norm(d, axis=-1, keepdims=True)
            assert np.max(np.arccos(np.clip(d @ a, -1, 1))) <= h
            checked += 1
        assert checked > 100
    # the root cell holds the ball: its cone is the whole domain's (Domain.cone)
    axis, half = toward(dom, root(dom, 1), lights[0])
    want_axis, want_half = dom.cone(lights[0][0])
    assert np.allclose(axis[0], want_axis) and half[0] == pytest.approx(np.radians(want_half), rel=1e-9)


def test_a_cell_misses_the_ball_only_when_no_point_of_it_is_inside():
    spec, dom = _local_mesh()
    radius = dom.ball[1]
    far = np.array([[[radius * 0.8, radius * 0.8, radius * 0.8], [radius, radius, radius]]])
    near = np.array([[[radius * 0.5, radius * 0.5, radius * 0.5], [radius, radius, radius]]])
    assert list(meets(dom, np.concatenate([far, near, root(dom, 1)]))) == [False, True, True]


def test_a_cell_is_halved_along_its_longest_edge_when_it_is_the_widest_side():
    cells = np.array([[[0.0, 0.0, 0.0], [0.4, 1.0, 0.2]], [[0.0, 0.0, 0.0], [0.01, 0.01, 0.01]]])
    boxes = Boxes(np.array([[0.1, 0.2], [0.1, 0.2]]), np.array([[0.0, 0.1], [0.0, 0.1]]),
                  np.array([[0.99, 1.0], [0.99, 1.0]]), np.array([16, 16]), np.array([0, 0]), cells, (0.5, 10.0))
    widths = boxes.widths()
    assert widths.shape == (2, 4) and np.argmax(widths[0]) == 3 and np.argmax(widths[1]) == 0
    halves = boxes.split()
    assert np.allclose(halves.cells[0], [[0.0, 0.0, 0.0], [0.4, 0.5, 0.2]])
    assert np.allclose(halves.cells[2], [[0.0, 0.5, 0.0], [0.4, 1.0, 0.2]])
    assert np.allclose(halves.theta[:, 0], [0.1, 0.1, 0.1, 0.15])  # the second box halved along θ
    assert np.all(halves.cells[[1, 3]] == cells[1])
    assert scale(_local_mesh()[1]) > 0


def test_cells_narrow_the_local_meshs_bound():
    """The whole domain's bound of the conventional design at 15-bit vectors falls by a tenth with
    cells (1.18 levels without, 1.07 with, at 150,000 boxes): a cell narrows the light's and the
    viewer's cones together."""
    spec, dom = _local_mesh()
    whole = replace(dom, regions=())
    params = {"vec_frac": 15, "rsqrt_addr": 9, "table_addr": 5, "coef": 1}
    shader = shader_config("conventional", params, spec)
    method = CONVENTIONAL_BOUND
    with_cells, parts = method.bound(shader, spec, whole, max_boxes=150_000)
    cones = directions(whole)
    plain = cover(cones.cover_cos_min, whole.min_normal_length, cases(whole))
    without, _ = bound_boxes(lambda boxes, floor: method.errors(shader, spec.requirement.against, boxes, cones, floor,
                                                                whole), whole, max_boxes=150_000, boxes=plain)
    assert "cell" in parts["where"]
    assert with_cells < 1.1 and without > 1.15 and with_cells < without - 0.1
    assert certify("conventional", params, spec, whole, shader=shader, max_boxes=150_000).certified
