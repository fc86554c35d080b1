"""A point light's or local viewer's vector as the conventional unit normalizes it: the hull and
the distance bound hold on the golden normalizer, and the geometry's bound on Phong's R·V holds."""

import numpy as np
import pytest

from phongfx.certify.cones import Direction
from phongfx.certify.local_vectors import Deviation, along_by_length, geometry_error, local_vector
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
    hull, deviation = local_vector(config, cone, 1, 5)
    exact = _in_cone(axis, cone.half, 50_000, np.random.default_rng(vec_frac))
    code = Fixed.from_float(exact, config.fmt("vec"), rounding="round_half_up", overflow="saturate")
    hardware = unit_length(config, code).to_float()
    assert np.all(hardware >= hull.lo[0] - 1e-15) and np.all(hardware <= hull.hi[0] + 1e-15)
    distance = np.linalg.norm(hardware - exact, axis=-1)
    assert distance.max() <= deviation.whole < 4 * distance.max()
    along = np.abs(np.sum((hardware - exact) * exact, axis=-1))
    assert along.max() <= deviation.along < 4 * along.max()
    assert deviation.along < deviation.whole  # the normalizer takes the host's rounding out along L
    assert hull.dev.max() == 0.0  # exact over its hull: the distance is bounded apart


def test_the_geometry_bound_holds_on_phongs_reflection():
    """``|G(L̂, V̂) - G(L, V)| <= geometry_error(δL, δV)``, ``G(X, Y) = 2(N·X)(N·Y) - X·Y``, for
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
    bound = geometry_error(Deviation(e_light, e_light), Deviation(e_view, e_view))
    assert moved.max() <= bound < 1.1 * moved.max()


def test_near_the_highlight_only_the_part_along_each_vector_counts():
    """With ``|δL·L| <= a_L`` (and ``V``'s), where Phong's ``t = R·V`` is in a band ``[t0, t1]``
    (``0 <= t0``) the geometry moves ``G`` by at most ``geometry_error(δL, δV, t1, √(1 - t0²))``:
    at ``t`` near 1, about ``a_L + a_V`` however large the parts across; reached within 10%."""
    rng = np.random.default_rng(6)
    count = 400_000

    def units(k=count):
        v = rng.normal(size=(k, 3))
        return v / np.linalg.norm(v, axis=-1, keepdims=True)

    def g(n, x, y):
        return 2 * np.sum(n * x, -1) * np.sum(n * y, -1) - np.sum(x * y, -1)

    def across(x, v):  # a vector of length ``v`` perpendicular to each row of ``x``
        w = units(len(x))
        w -= np.sum(w * x, -1, keepdims=True) * x
        return v * w / np.linalg.norm(w, axis=-1, keepdims=True)

    light, view = units(), units()
    # normals near the highlight: N = unit(L + V) turned a little, so that t is near 1
    n = light + view + units() * rng.random((count, 1)) * 0.2
    n /= np.linalg.norm(n, axis=-1, keepdims=True)
    whole, along = (3e-3, 1e-3), (1e-3, 4e-4)
    moved = []
    for x, w, a in ((light, whole[0], along[0]), (view, whole[1], along[1])):
        part = a * rng.uniform(-1, 1, (count, 1)) * x
        side = np.sqrt(w ** 2 - np.sum(part ** 2, -1, keepdims=True))
        moved.append(part + across(x, side[:, 0:1] * rng.random((count, 1)) ** 0.1))
    t = g(n, light, view)
    change = np.abs(g(n, light + moved[0], view + moved[1]) - t)
    d_light, d_view = Deviation(whole[0], along[0]), Deviation(whole[1], along[1])
    for t0, t1 in ((0.0, 0.5), (0.5, 0.9), (0.99, 0.999), (0.999, 1.0)):
        pick = (t >= t0) & (t <= t1)
        bound = geometry_error(d_light, d_view, t1, np.sqrt(1 - t0 ** 2))
        assert np.count_nonzero(pick) > 100
        assert change[pick].max() <= bound
    near = (t >= 0.999)
    assert geometry_error(d_light, d_view, 1.0, np.sqrt(1 - 0.999 ** 2)) < 1.1 * change[near].max()
    assert geometry_error(d_light, d_view, 1.0, np.sqrt(1 - 0.999 ** 2)) < 0.5 * geometry_error(d_light, d_view)


@pytest.mark.parametrize("vec_frac, rsqrt_addr, axis, half_deg", [
    (8, 5, (0.485, 0.485, 0.728), 18.55), (10, 9, (0.0, 0.0, 1.0), 19.15), (14, 9, (0.485, 0.485, 0.728), 18.55),
    (14, 9, (0.0, 0.0, 1.0), 19.15), (12, 7, (0.6, -0.8, 0.0), 30.0),
])
def test_the_along_bound_by_length_holds_and_is_the_tighter(vec_frac, rsqrt_addr, axis, half_deg):
    """Tied to the host's squared length, the part of ``δL`` along ``L`` holds on 400,000 golden
    normalizations (the axis's component near 1 clamps), within 1.7 times their largest, and it
    is what the deviation keeps where it is below the interval bound (local mesh's light cone
    at 14 bits: 7.14e-5 where the intervals give 8.22e-5)."""
    config = ConventionalConfig(local_light=True).replace(vec=f"S1.{vec_frac}", rsqrt_addr=rsqrt_addr)
    axis = np.asarray(axis) / np.linalg.norm(axis)
    cone = Direction(tuple(axis), np.radians(half_deg), True)
    exact = _in_cone(axis, cone.half, 400_000, np.random.default_rng(vec_frac + rsqrt_addr))
    code = Fixed.from_float(exact, config.fmt("vec"), rounding="round_half_up", overflow="saturate")
    along = np.abs(np.sum((unit_length(config, code).to_float() - exact) * exact, axis=-1)).max()
    bound = along_by_length(config, cone)
    assert along <= bound < 1.7 * along
    assert local_vector(config, cone, 1, 5)[1].along <= bound * (1 + 1e-12)


def test_no_along_bound_by_length_where_the_shift_drops_bits():
    """With ``dot`` narrower than the shifted codes, the unit rounds twice, its step is no longer
    monotone in a component, and the bound by length is not given (the interval one stands)."""
    config = ConventionalConfig(local_light=True).replace(vec="S1.14", dot="S1.12")
    cone = Direction((0.0, 0.0, 1.0), np.radians(19.15), True)
    assert along_by_length(config, cone) is None
