"""Boxes of normals: they cover the domain's normals, and their projections hold the exact ones."""

import numpy as np

from phongfx.certify.sphere import cos_range, cover, frame, projection


def _points(boxes, count, seed):
    """``count`` random points (box index, N̂, z) inside random boxes."""
    g = np.random.default_rng(seed)
    index = g.integers(0, len(boxes), count)
    theta = g.uniform(boxes.theta[index, 0], boxes.theta[index, 1])
    phi = g.uniform(boxes.phi[index, 0], boxes.phi[index, 1])
    z = g.uniform(boxes.z[index, 0], boxes.z[index, 1])
    return index, theta, phi, z


def test_cos_range_holds_the_extrema_inside():
    lo, hi = cos_range(np.array([-0.5, 3.0, 0.2]), np.array([0.5, 3.5, 0.4]))
    assert hi[0] == 1.0 and lo[1] == -1.0
    assert lo[2] < np.cos(0.4) < np.cos(0.2) < hi[2]


def test_the_boxes_cover_every_normal_facing_the_viewer_enough():
    view = np.array([0.2, -0.3, 0.9])
    basis = frame(view)
    boxes = cover(-0.3, 0.95, [(16, 0)], 6, 8, 2)
    v, e1, e2 = basis
    g = np.random.default_rng(5)
    n = g.normal(size=(20000, 3))
    n /= np.linalg.norm(n, axis=-1, keepdims=True)
    n = n[n @ v >= -0.3]
    theta = np.arccos(np.clip(n @ v, -1, 1))
    phi = np.mod(np.arctan2(n @ e2, n @ e1), 2 * np.pi)
    inside = ((theta[:, None] >= boxes.theta[:, 0]) & (theta[:, None] <= boxes.theta[:, 1])
              & (phi[:, None] >= boxes.phi[:, 0]) & (phi[:, None] <= boxes.phi[:, 1]))
    assert np.all(inside.any(axis=1))
    assert boxes.z.min() == 0.95 ** 2 and boxes.z.max() == 1.0


def test_projections_hold_the_exact_cosines():
    view = np.array([0.0, 0.0, 1.0])
    basis = frame(view)
    v, e1, e2 = basis
    boxes = cover(-0.2, 0.9, [(4, 0)], 10, 20, 1).split().split()
    light = np.array([1.0, 1.0, -1.0]) / np.sqrt(3)
    index, theta, phi, _ = _points(boxes, 20000, 9)
    normal = (np.cos(theta)[:, None] * v + np.sin(theta)[:, None] * (np.cos(phi)[:, None] * e1
                                                                      + np.sin(phi)[:, None] * e2))
    q = projection(boxes, basis, light)
    c = projection(boxes, basis, light, reflected=True)
    exact_q = normal @ light
    exact_c = (2 * (normal @ v)[:, None] * normal - v) @ light
    assert np.all((q[0][index] <= exact_q) & (exact_q <= q[1][index]))
    assert np.all((c[0][index] <= exact_c) & (exact_c <= c[1][index]))
    # tight for small boxes: the width is that of the box, not of the sphere
    assert np.median(q[1] - q[0]) < 0.2


def test_split_halves_the_widest_side():
    boxes = cover(0.0, 1.0, [(1, 0)], 1, 1, 1)
    halves = boxes.split()
    assert len(halves) == 2
    assert np.allclose(halves.phi[:, 1] - halves.phi[:, 0], np.pi)


def test_a_box_set_keeps_its_polar_ranges_for_every_projection_and_its_halves_their_own():
    # every projection of one box set shares the cos and sin ranges of θ (or 2θ, reflected):
    # computed once per scale, the same floats as computed afresh, and a split's are its own
    boxes = cover(-0.2, 0.9, [(4, 0)], 10, 20, 1).split()
    once, again = boxes.polar(1.0), boxes.polar(1.0)
    assert once is again and boxes.polar(2.0) is not once
    fresh = cos_range(2 * boxes.theta[:, 0] - np.pi / 2, 2 * boxes.theta[:, 1] - np.pi / 2)
    assert all(np.array_equal(a, b) for a, b in zip(boxes.polar(2.0)[1], fresh))
    halves = boxes.split()
    assert np.array_equal(halves.polar(1.0)[0][0], cos_range(halves.theta[:, 0], halves.theta[:, 1])[0])
    light = np.array([0.3, -0.5, 0.8])
    first = projection(boxes, frame([0.0, 0.0, 1.0]), light)
    assert all(np.array_equal(a, b) for a, b in zip(first, projection(boxes, frame([0.0, 0.0, 1.0]), light)))


def test_the_corners_least_and_most_are_numpys_reductions():
    from phongfx.certify.interval import least, most

    g = np.random.default_rng(3)
    corners = [g.normal(size=50) for _ in range(4)]
    corners[2][7] = -np.inf
    assert np.array_equal(least(corners), np.minimum.reduce(corners))
    assert np.array_equal(most(corners), np.maximum.reduce(corners))
