"""A point light's or local viewer's vector as the conventional unit normalizes it: the hull and
the distance bound hold on the golden normalizer, and the geometry's bound on Phong's R·V holds."""

import numpy as np
import pytest

from phongfx.certify.cones import Direction
from phongfx.certify.local_vectors import geometry_error, local_vector
from phongfx.config import ConventionalConfig
from phongfx.golden.conventional import unit_length
from phongfx.golden.fixed import Fixed


def _in_cone(axis, half, count, rng):
    """``count`` unit vectors within ``half`` radians of the unit ``axis``, their angles spread up to it."""
    axis = np.asarray(axis, dtype=np.float64)
    other = np.cross(axis, [1.0, 0.0, 0.0] if abs(axis[0]) < 0.9 else [0.0, 1.0, 0.0])
    e1 = other / np.linalg.norm(other)
    e2 = np.cross(axis, e1)
    theta = half * np.sqrt(rng.random(count))
    theta[:8] = half  # the rim, where a hull is tightest
    phi = rng.uniform(0.0, 2 * np.pi, count)
    return (np.cos(theta)[:, None] * axis
            + np.sin(theta)[:, None] * (np.cos(phi)[:, None] * e1 + np.sin(phi)[:, None] * e2))


@pytest.mark.parametrize("vec_frac, axis, half_deg", [
    (12, (0.485, 0.485, 0.728), 18.55), (15, (0.0, 0.0, 1.0), 19.15), (9, (0.6, -0.8, 0.0), 30.0),
])
def test_the_hull_and_the_distance_hold_on_the_golden_normalizer(vec_frac, axis, half_deg):
    """The unit fed a direction of the cone rounded by the host (to nearest) gives a vector
    inside the hull, at most ``delta`` from the exact one; and the bound is not slack by much."""
    config = ConventionalConfig(local_light=True).replace(vec=f"S1.{vec_frac}")
    axis = np.asarray(axis) / np.linalg.norm(axis)
    cone = Direction(tuple(axis), np.radians(half_deg), True)
    hull, delta = local_vector(config, cone, 1, 5)
    exact = _in_cone(axis, cone.half, 50_000, np.random.default_rng(vec_frac))
    code = Fixed.from_float(exact, config.fmt("vec"), rounding="round_half_up", overflow="saturate")
    hardware = unit_length(config, code).to_float()
    assert np.all(hardware >= hull.lo[0] - 1e-15) and np.all(hardware <= hull.hi[0] + 1e-15)
    distance = np.linalg.norm(hardware - exact, axis=-1)
    assert distance.max() <= delta < 4 * distance.max()
    assert hull.dev.max() == 0.0  # exact over its hull: the distance is bounded apart


def test_the_geometry_bound_holds_on_phongs_reflection():
    """``|G(L̂, V̂) - G(L, V)| <= geometry_error(|δL|, |δV|)``, ``G(X, Y) = 2(N·X)(N·Y) - X·Y``, for
    unit ``N``, ``L``, ``V`` and any small ``δL``, ``δV``; reached within 10% (δ along ``R``)."""
    rng = np.random.default_rng(5)
    count = 200_000

    def units():
        v = rng.normal(size=(count, 3))
        return v / np.linalg.norm(v, axis=-1, keepdims=True)

    def g(n, x, y):
        return 2 * np.sum(n * x, -1) * np.sum(n * y, -1) - np.sum(x * y, -1)

    n, light, view = units(), units(), units()
    e_light, e_view = 3e-3, 2e-3
    d_light = units() * e_light * rng.random((count, 1)) ** 0.1
    d_view = units() * e_view * rng.random((count, 1)) ** 0.1
    # the worst direction: along V and L reflected about N
    d_light[:1000] = e_light * (2 * np.sum(n * view, -1, keepdims=True) * n - view)[:1000]
    d_view[:1000] = e_view * (2 * np.sum(n * light, -1, keepdims=True) * n - light)[:1000]
    moved = np.abs(g(n, light + d_light, view + d_view) - g(n, light, view))
    bound = geometry_error(e_light, e_view)
    assert moved.max() <= bound < 1.1 * moved.max()
