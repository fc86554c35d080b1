"""The ideal datapath's distance from the reference: each bound holds at random points."""

import numpy as np
import pytest

from phongfx.certify.approximation import (CELLS, diffuse_shift, form_distance, form_table, scale_range,
                                           shape_shift)
from phongfx.certify.sphere import cover, frame, projection
from phongfx.golden.reference import specular


def _shape(x, k):
    t = np.maximum(0.0, 1 - x / 2.0 ** k)
    for _ in range(k):
        t = t * t
    return t


def test_scale_range_holds_lyons_g1_and_g2():
    z = np.array([[0.8, 0.85], [0.95, 1.0]])
    for order in (1, 2):
        lo, hi = scale_range(z, order)
        for row in range(2):
            zz = np.linspace(*z[row], 101)
            y = 1 - zz
            g = 1 + y / 2 if order == 1 else 1 + (y + y * y) / 2
            s = g * np.sqrt(zz)
            assert lo[row] <= s.min() and s.max() <= hi[row]
    # Lyon: g1 leaves a 0.9-long vector short, g2 slightly over-corrects it
    assert scale_range(np.array([[0.81, 0.81]]), 1)[1][0] < 0.99
    assert scale_range(np.array([[0.81, 0.81]]), 2)[1][0] > 1.0


@pytest.mark.parametrize("n, k, light", [(16, 2, (1, 1, 1)), (16, 4, (1, 1, 1)), (64, 2, (1, -1, 1)),
                                         (1, 2, (1, 1, -1))])
def test_shape_and_diffuse_shifts_hold_at_random_points(n, k, light):
    view = np.array([0.0, 0.0, 1.0])
    light = np.asarray(light, dtype=np.float64) / np.linalg.norm(light)
    basis = frame(view)
    v, e1, e2 = basis
    boxes = cover(-0.3, 0.9, [(n, 0)], 16, 32, 2).split()
    g = np.random.default_rng(n + k)
    index = g.integers(0, len(boxes), 40000)
    theta = g.uniform(boxes.theta[index, 0], boxes.theta[index, 1])
    phi = g.uniform(boxes.phi[index, 0], boxes.phi[index, 1])
    z = g.uniform(boxes.z[index, 0], boxes.z[index, 1])
    unit = (np.cos(theta)[:, None] * v + np.sin(theta)[:, None] * (np.cos(phi)[:, None] * e1
                                                                    + np.sin(phi)[:, None] * e2))
    y = 1 - z
    s = (1 + (y + y * y) / 2) * np.sqrt(z)
    normal = s[:, None] * unit
    r = 2 * (normal @ view)[:, None] * normal - view
    ideal = _shape(n / 2 * np.sum((r - light) ** 2, -1), k)
    at_one = specular(f"lyon-k{k}", unit, light, view, np.full(len(unit), float(n)))
    phong = specular("phong", unit, light, view, np.full(len(unit), float(n)))
    sr = scale_range(boxes.z, 2)
    p, q = projection(boxes, basis, view), projection(boxes, basis, light)
    c = projection(boxes, basis, light, reflected=True)
    shift = shape_shift(sr, p, q, c, np.full(len(boxes), float(n)), k)
    assert np.all(np.abs(ideal - at_one) <= shift[index] + 1e-12)
    form = form_distance(n, n, k, c)
    assert np.all(np.abs(at_one - phong) <= form[index])
    cosine = unit @ light
    assert np.all(np.abs(np.maximum(s * cosine, 0) - np.maximum(cosine, 0)) <= diffuse_shift(sr, q)[index] + 1e-15)


def test_form_table_is_zero_where_the_form_is_phong_and_not_elsewhere():
    """``2^k = n`` makes ``f_k(n(1 - c)) = c^n`` (Lyon's shape at ``k = log2 n`` is Phong's
    power), so the table holds only the cells' own slope; ``k = 2`` against ``n = 16`` does not."""
    assert form_table(16, 16, 4).max() < 16 * 2.0 / CELLS * 2
    c = np.linspace(-1, 1, 2001)
    true = np.max(np.abs(_shape(16 * (1 - c), 2) - np.maximum(c, 0) ** 16))
    assert true <= form_table(16, 16, 2).max() <= true + 1e-3


def test_form_distance_over_any_range_holds_the_cells_in_it():
    table = form_table(64, 64, 2)
    g = np.random.default_rng(4)
    lo = g.uniform(-1, 1, 300)
    hi = np.minimum(lo + g.uniform(0, 0.5, 300), 1)
    got = form_distance(64, 64, 2, (lo, hi))
    for a, b, bound in zip(lo, hi, got):
        first, last = int((a + 1) / 2 * CELLS), min(int((b + 1) / 2 * CELLS), CELLS - 1)
        assert bound >= table[first:last + 1].max()
