import numpy as np
import pytest

from phongfx.golden.adaptive import adaptive_test, edge_maximum, highlight_test, levels, specular_euler
from phongfx.golden.euler_setup import (curves_at, euler_curve, gouraud_curve, random_spans, span_setup,
                                        span_setups)


def random_setups(count, max_angle, lengths, seed):
    g = np.random.default_rng(seed)
    na, nb, light = random_spans(count, max_angle, g)
    length = g.integers(*lengths, size=count)
    return span_setups(na, nb, light, length), length


def pixels(length):
    span = np.repeat(np.arange(len(length)), length)
    return span, np.arange(length.sum()) - np.repeat(np.cumsum(length) - length, length)


def per_span_all(span, equal, count):
    return np.bincount(span, weights=~equal, minlength=count) == 0


def test_delta_is_zero_when_euler_is_linear():
    # na == nb: k = 0, ds = 0, Euler is the chord; the ds = 0 guard gives δ = 0
    g = np.random.default_rng(1)
    na, _, light = random_spans(50, 1.0, g)
    length = g.integers(1, 300, size=50)
    result = adaptive_test(span_setups(na, na, light, length))
    assert np.all(result["delta"] == 0) and np.all(result["gouraud"]) and np.all(result["step"] == 0)


def test_delta_is_the_largest_difference_along_the_span():
    # brute force over every pixel with the scalar curves, and the closed form
    # δ = m(n - m)/2·ds at m = trunc((n - 1)/2) + 1 (corrected Euler ends at p_b)
    g = np.random.default_rng(2)
    for na, nb, light in zip(*random_spans(40, np.radians(40), g)):
        length = int(g.integers(2, 200))
        setup = span_setup(na, nb, light, length)
        many = {key: np.array([value]) for key, value in setup.items()}
        result = adaptive_test(many)
        diff = gouraud_curve(setup) - euler_curve(setup)
        assert abs(result["delta"][0]) == pytest.approx(np.max(np.abs(diff)), rel=1e-9, abs=1e-15)
        n, m = length - 1, (length - 2) // 2 + 1
        # for odd n, (n - 1)/2 is an integer where δ(m - 1) = δ(m): rounding may pick either
        assert result["step"][0] == m or (n % 2 and result["step"][0] == m - 1)
        assert result["delta"][0] == pytest.approx(m * (n - m) / 2 * setup["ds"], rel=1e-9, abs=1e-15)


def test_agrees_with_per_pixel_brute_force():
    # seeded random spans up to 20° and 64 pixels, half of them lit
    setups, length = random_setups(4000, np.radians(20), (1, 65), seed=3)
    span, x = pixels(length)
    curves = curves_at(setups, span, x)
    decision = adaptive_test(setups)["gouraud"]
    # what δ estimates: every pixel's float difference below one level
    close = per_span_all(span, np.abs(255 * (curves["gouraud"] - curves["corrected"])) < 1, len(length))
    assert np.mean(decision == close) >= 0.99
    # against truncated levels: equal levels mean a difference below one level, so a lit
    # span the test sends to Euler never had equal levels (no false negatives)...
    equal = per_span_all(span, levels(curves["gouraud"]) == levels(curves["corrected"]), len(length))
    lit = per_span_all(span, (curves["corrected"] > 0) & (curves["gouraud"] > 0)
                       & (curves["corrected"] < 1), len(length))
    false_neg = ~decision & equal
    assert not np.any(lit & false_neg) and np.mean(false_neg) > 0.05  # the rest are dark spans
    # ...but below one level is not equal levels: with these spans (not the small ones of a
    # torus) about half the lit spans sent to Gouraud differ somewhere by a level (27% of
    # all spans), and the test agrees with the truncated truth on only ~62% of spans
    false_pos = decision & ~equal
    assert 0.2 < np.mean(false_pos) < 0.35 and 0.4 < np.mean(false_pos[lit]) < 0.65
    assert 0.5 < np.mean(decision == equal) < 0.75


def test_kd_scales_the_threshold():
    setups, _ = random_setups(500, np.radians(30), (2, 65), seed=4)
    delta = adaptive_test(setups)["delta"]
    np.testing.assert_array_equal(adaptive_test(setups, kd=0.5)["gouraud"], np.abs(delta) * 127.5 < 1)
    with pytest.raises(ValueError, match=r"^kd must be a finite number >= 0, not -1$"):
        adaptive_test(setups, kd=-1)


def _unit(v):
    v = np.asarray(v, dtype=np.float64)
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def _polar(theta_deg, phi_deg):
    t, p = np.radians(theta_deg), np.radians(phi_deg)
    return np.array([np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)])


H = np.array([0.0, 0.0, 1.0])


def test_edge_maximum_closed_form():
    # normals 10° and -50° from H in one plane: the edge passes through H where its
    # x component vanishes, s = sin 10°/(sin 10° + sin 50°), with N̂·H = 1
    a, b = _polar(10, 0), _polar(50, 180)
    e = edge_maximum(a[None], b[None], H)
    s = np.sin(np.radians(10)) / (np.sin(np.radians(10)) + np.sin(np.radians(50)))
    assert e["s"][0] == pytest.approx(s, abs=1e-12) and e["interior"][0]
    assert e["value"][0] == pytest.approx(1.0, abs=1e-12)


def test_edge_maximum_matches_dense_sampling():
    g = np.random.default_rng(5)
    a, b, h = random_spans(200, np.radians(90), g)
    for i in range(len(a)):
        s = np.linspace(0, 1, 20001)[:, None]
        n = a[i] + s * (b[i] - a[i])
        sampled = np.max(n @ h[i] / np.linalg.norm(n, axis=1))
        value = edge_maximum(a[i:i + 1], b[i:i + 1], h[i])["value"][0]
        assert sampled - 1e-12 <= value <= sampled + 1e-6


def test_highlight_on_an_edge_with_every_vertex_below_threshold():
    # vertices 40° off H (N·H = 0.766) but the first edge passes through H
    tri = np.array([[_polar(40, 0), _polar(40, 180), _polar(60, 90)]])
    t = highlight_test(tri, H, 0.9)
    assert not t["vertex"][0] and t["edge"][0] and t["highlight"][0] and t["exact"][0]


def test_highlight_inside_only():
    # vertices 40° off H at azimuths 0, 120, 240: edge maxima at their midpoints,
    # N̂·H = cos 40°/√(cos²40° + sin²40°·cos²60°) ≈ 0.922; the peak 1 is inside
    tri = np.array([[_polar(40, 0), _polar(40, 120), _polar(40, 240)]])
    mid = np.cos(np.radians(40)) / np.hypot(np.cos(np.radians(40)), np.sin(np.radians(40)) / 2)
    e = edge_maximum(tri[:, 0], tri[:, 1], H)
    assert e["s"][0] == pytest.approx(0.5) and e["value"][0] == pytest.approx(mid, abs=1e-12)
    t = highlight_test(tri, H, 0.95)
    assert not t["vertex"][0] and not t["edge"][0]
    assert t["extremum"][0] and t["highlight"][0] and t["exact"][0]
    below = highlight_test(tri, H, 0.9)  # the edges reach 0.922
    assert below["edge"][0]


def test_no_highlight_facing_away():
    tri = -np.array([[_polar(40, 0), _polar(40, 120), _polar(40, 240)],
                     [_polar(10, 0), _polar(5, 100), _polar(20, 250)]])
    t = highlight_test(tri, H, 0.1)
    for key in ("vertex", "edge", "extremum", "highlight", "exact"):
        assert not np.any(t[key]), key
    with pytest.raises(ValueError, match=r"^threshold must be in -1\.\.1, not 2$"):
        highlight_test(tri, H, 2)


def test_specular_euler():
    setups, length = random_setups(300, np.radians(10), (1, 40), seed=6)
    span, x = pixels(length)
    curves = curves_at(setups, span, x)
    ours, phong = specular_euler(setups, span, x, 1)
    np.testing.assert_array_equal(ours, np.clip(curves["corrected"], 0, 1))
    np.testing.assert_array_equal(phong, np.clip(curves["phong"], 0, 1))
    ours, phong = specular_euler(setups, span, x, 50)
    np.testing.assert_allclose(phong, np.clip(curves["phong"], 0, 1) ** 50, rtol=1e-12)
    # the power amplifies the Euler error by about n·e^(n-1), still far below a level here
    assert np.max(np.abs(ours - phong)) < 2e-3
    with pytest.raises(ValueError, match=r"^shininess must be a number >= 1, not 0$"):
        specular_euler(setups, span, x, 0)


def test_levels_truncate_255():
    assert levels(np.array([-0.5, 0.0, 0.5, 1 / 255 - 1e-12, 1.0, 1.5])).tolist() == [0, 0, 127, 0, 255, 255]
