import numpy as np
import pytest

from phongfx.config import EulerConfig
from phongfx.golden.euler import euler
from phongfx.golden.euler_setup import (curves_at, duff_curve, euler_curve, gouraud_curve, min_frac_bits,
                                        normalized_curve, quantize_setup, random_spans, span_setup,
                                        span_setups, stability)
from phongfx.golden.fixed import Fixed, FixedOverflowError
from phongfx.sim.stimulus.euler import span

LENGTHS = (2, 3, 16, 257, 2048)


def spans(count=20, max_angle=np.pi / 3, seed=0):
    return list(zip(*random_spans(count, max_angle, np.random.default_rng(seed))))


@pytest.mark.parametrize("length", LENGTHS)
def test_duff_matches_direct_normalization(length):
    for na, nb, light in spans():
        exact = normalized_curve(na, nb, light, length)
        np.testing.assert_allclose(duff_curve(span_setup(na, nb, light, length)), exact, atol=1e-12)


@pytest.mark.parametrize("length", LENGTHS)
def test_dq_b_is_minus_dq_a(length):
    # equation 22 against the definition dq_b = 2nC + D
    for setup in (span_setup(*s, length) for s in spans()):
        assert setup["dq_b"] == pytest.approx(2 * setup["n"] * setup["C"] + setup["D"], abs=1e-12)


@pytest.mark.parametrize("length", LENGTHS)
def test_corrected_euler_ends_exactly_at_p_b(length):
    for setup in (span_setup(*s, length) for s in spans()):
        curve = euler_curve(setup)
        assert curve[0] == setup["p_a"]
        assert curve[-1] == pytest.approx(setup["p_b"], abs=1e-12)


def test_uncorrected_euler_drifts_by_epsilon():
    # equations 14-15: the uncorrected end is off by ε, which the correction removes;
    # for normals 60° apart it is visible in 8 bits on most spans
    setups = [span_setup(*s, 64) for s in spans(50)]
    drift = np.array([euler_curve(s, corrected=False)[-1] - s["p_b"] for s in setups])
    np.testing.assert_allclose(drift, [s["eps"] for s in setups], atol=1e-12)
    assert np.median(np.abs(drift)) * 256 > 1
    worse = [np.max(np.abs(euler_curve(s, corrected=False) - duff_curve(s))) >
             np.max(np.abs(euler_curve(s) - duff_curve(s))) for s in setups]
    assert np.mean(worse) > 0.9


def test_short_spans_use_the_end_values():
    # one pixel is p_a; two pixels step straight to p_b (t0 = p_b - p_a, the paper's §3.2)
    for na, nb, light in spans():
        one, two = span_setup(na, nb, light, 1), span_setup(na, nb, light, 2)
        assert euler_curve(one).tolist() == [one["p_a"]] and one["t0"] == one["ds"] == 0
        assert two["t0"] == pytest.approx(two["p_b"] - two["p_a"], abs=1e-15)
        np.testing.assert_allclose(gouraud_curve(two), euler_curve(two), atol=1e-15)


def test_corrected_euler_is_close_to_phong_for_small_angles():
    # Hast's Table 2: within about one 8-bit level once the polygons are small (here 10°)
    error = max(np.max(np.abs(euler_curve(s) - duff_curve(s))) * 256
                for s in (span_setup(*x, 64) for x in spans(50, np.radians(10))))
    assert error < 1


@pytest.mark.parametrize("compensate", [False, True])
def test_fixed_point_end_within_rounding(compensate):
    # with compensation the end is off by at most n/2 LSB of t plus the rounding of p_b
    config = EulerConfig()
    for na, nb, light in spans(5):
        setup = span_setup(na, nb, light, 2048)
        raw = span(config, 2048, np.random.default_rng(0), **quantize_setup(config, setup, compensate))
        p = euler(config, *(Fixed(raw[name], fmt) for name, fmt in
                            (("init", "1.0"), ("p0", config.p), ("t0", config.t), ("ds", config.ds))))["p"]
        error = abs(p.to_float()[-1] - setup["p_b"]) * 2.0 ** 30
        assert error <= (2047 / 2 + 0.5 if compensate else 2047 * 2046 / 4 + 2047 / 2 + 0.5)


def test_quantize_setup_refuses_overflow():
    setup = span_setup([0, 0, 1], [0, 0, 1], [0, 0, 1], 4)  # p = 1.0 all along
    with pytest.raises(FixedOverflowError, match=r"^from_float: 4 value\(s\) overflow format S0\.10 "):
        quantize_setup(EulerConfig(p="S0.10", t="S3.10", ds="S3.10"), setup)


def test_span_setup_wants_a_length():
    with pytest.raises(ValueError, match=r"^length must be a positive integer, not 0$"):
        span_setup([0, 0, 1], [0, 0, 1], [0, 0, 1], 0)


def test_stability_smoke():
    # default formats (30 fraction bits) keep a 2048-pixel span's end within one level
    assert stability(30, 2048, spans=4)["level"] <= 1
    assert min_frac_bits(2048, widths=range(26, 31), spans=8)[0] == 28


@pytest.mark.slow
def test_stability_sweep():
    # fraction bits F of p, t, ds for 60° spans: the paper's setup rounded (ds error grows
    # like n²/2) against the compensated t0 (only n/2 LSB of t remain)
    table = {}
    for compensate in (False, True):
        for length in (2, 16, 256, 2048):
            table[compensate, length] = min_frac_bits(length, compensate=compensate)[0]
    assert table == {(False, 2): 8, (False, 16): 14, (False, 256): 22, (False, 2048): 28,
                     (True, 2): 8, (True, 16): 11, (True, 256): 15, (True, 2048): 18}


def test_span_setups_vectorized_curves():
    # every span of mixed lengths (1 included) against the scalar curves and direct normalization
    g = np.random.default_rng(7)
    na, nb, light = random_spans(60, np.pi / 3, g)
    length = g.integers(1, 40, size=60)
    setups = span_setups(na, nb, light, length)
    span = np.repeat(np.arange(60), length)
    x = np.arange(length.sum()) - np.repeat(np.cumsum(length) - length, length)
    curves = curves_at(setups, span, x)
    for i in range(60):
        one = span_setup(na[i], nb[i], light[i], int(length[i]))
        mine = span == i
        exact = normalized_curve(na[i], nb[i], light[i], int(length[i]))
        np.testing.assert_allclose(curves["phong"][mine], exact, atol=1e-12)
        np.testing.assert_allclose(curves["corrected"][mine], euler_curve(one), atol=1e-12)
        np.testing.assert_allclose(curves["euler"][mine], euler_curve(one, corrected=False), atol=1e-12)
        np.testing.assert_allclose(curves["gouraud"][mine], gouraud_curve(one), atol=1e-12)
    assert np.all(setups["t0"][length == 1] == 0) and np.all(setups["ds"][length == 1] == 0)


def test_span_setups_wants_lengths():
    with pytest.raises(ValueError, match=r"^length must be a positive integer, not 0$"):
        span_setups([[0, 0, 1]] * 2, [[0, 0, 1]] * 2, [0, 0, 1], [3, 0])
    with pytest.raises(ValueError, match=r"^length must be integers, not dtype float64$"):
        span_setups([[0, 0, 1]], [[0, 0, 1]], [0, 0, 1], [2.5])
