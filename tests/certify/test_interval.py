"""Interval values: the golden blocks run on them, and their bounds hold for real codes."""

import numpy as np
import pytest

from phongfx.certify.interval import Interval, rounding_error
from phongfx.config import NormalizeConfig, ReflectConfig
from phongfx.core.format import Format
from phongfx.golden.diffuse import diffuse
from phongfx.golden.fixed import Fixed
from phongfx.golden.normalize import normalize
from phongfx.golden.reflect import reflect
from phongfx.config import DiffuseConfig


def _codes(values, fmt):
    return Fixed.from_float(values, fmt, rounding="round_half_up", overflow="saturate")


def _near_unit(count, seed, shrink=0.95):
    g = np.random.default_rng(seed)
    v = g.normal(size=(count, 3))
    return v / np.linalg.norm(v, axis=-1, keepdims=True) * g.uniform(shrink, 1.0, (count, 1))


def _around(values, fmt, err):
    """An Interval of tight boxes about float ``values``: the hardware's codes within ``err``,
    the ideal the values themselves (one shared symbol per component)."""
    lo, hi = values - err, values + err
    terms = np.broadcast_to(err * np.eye(3), values.shape + (3,))
    return Interval(lo, hi, 0.0, fmt, terms=terms)


def test_rounding_error_of_each_mode():
    frm, to = Format.parse("S3.20"), Format.parse("S1.10")
    assert rounding_error(frm, to, "round_half_up") == 2.0 ** -11
    assert rounding_error(frm, to, "truncate") == 2.0 ** -10 - 2.0 ** -20
    assert rounding_error(to, frm, "truncate") == 0.0


def test_normalize_and_reflect_hold_the_golden_codes_and_their_error():
    """Run the golden normalize → reflect and diffuse on real codes and on Intervals around the
    exact floats: each code lies in its interval and within ``dev`` of the float ideal."""
    ncfg, rcfg, dcfg = NormalizeConfig(), ReflectConfig(), DiffuseConfig()
    vec = Format.parse(ncfg.vec)
    exact = _near_unit(4000, 3)
    codes = _codes(exact, vec)
    view = np.array([0.0, 0.0, 1.0])
    light = np.array([1.0, 1.0, 1.0]) / np.sqrt(3)
    hw_n = normalize(ncfg, codes)["n"]
    hw_r = reflect(rcfg, hw_n, _codes(np.broadcast_to(view, exact.shape), vec))["r"]
    hw_d = diffuse(dcfg, hw_n, _codes(np.broadcast_to(light, exact.shape), vec))["diff"]

    box = _around(exact, vec, vec.lsb / 2)
    v_int = Interval.exact(np.broadcast_to(view, exact.shape), vec)
    l_code = _codes(light, vec).to_float()
    l_int = Interval(np.broadcast_to(l_code, exact.shape), np.broadcast_to(l_code, exact.shape),
                     np.broadcast_to(np.abs(l_code - light), exact.shape), vec)
    n_int = normalize(ncfg, box)["n"]
    r_int = reflect(rcfg, n_int, v_int)["r"]
    d_int = diffuse(dcfg, n_int, l_int)["diff"]

    z = np.sum(exact * exact, -1, keepdims=True)
    y = 1 - z
    ideal_n = exact * (1 + (y + y * y) / 2)
    ideal_r = 2 * np.sum(ideal_n * view, -1, keepdims=True) * ideal_n - view
    ideal_d = np.maximum(ideal_n @ light, 0.0)
    for hw, box_out, ideal in ((hw_n, n_int, ideal_n), (hw_r, r_int, ideal_r), (hw_d, d_int, ideal_d)):
        value = hw.to_float()
        assert np.all(value >= box_out.lo) and np.all(value <= box_out.hi)
        assert np.all(np.abs(value - ideal) <= box_out.dev)
        # the bound has teeth: it is not wildly above what these codes reach
        assert np.max(box_out.dev) < 20 * max(np.max(np.abs(value - ideal)), hw.fmt.lsb)


def test_affine_terms_cancel_in_the_normalizer():
    """An error along N' is what the normalizer takes out: with shared symbols N's bound is
    below the per-component one (Lyon's Figure 7a)."""
    cfg = NormalizeConfig()
    exact = np.array([[0.0, 0.6, 0.78]])
    err = 2.0 ** -11
    shared = normalize(cfg, _around(exact, cfg.vec, err))["n"]
    alone = normalize(cfg, Interval(exact - err, exact + err, err, cfg.vec))["n"]
    assert np.all(shared.dev < alone.dev)
    assert shared.dev[0, 2] < 0.75 * alone.dev[0, 2]


def test_saturation_adds_the_distance_past_the_format():
    x = Interval(np.array([1.5]), np.array([2.5]), 0.25, "S3.6")
    q = x.quantize("S1.4", "round_half_up", "saturate")
    top = 2 - 2.0 ** -4
    assert q.hi[0] == top
    assert q.dev[0] == pytest.approx(0.25 + 2.0 ** -5 + (2.5 + 0.25 - top), rel=1e-9)


def test_wrap_or_error_where_the_range_leaves_the_format_gives_no_bound():
    x = Interval(np.array([0.5, 1.5]), np.array([0.75, 2.5]), 0.0, "S3.4")
    q = x.quantize("S1.4", "round_half_up", "error", op="test quantize")
    assert np.isfinite(q.dev[0]) and np.isinf(q.dev[1])
    assert q.faults == {"test quantize"}


def test_a_clamp_keeps_its_input_error_and_a_step_pays_the_jump():
    v = Interval(np.array([-0.1, 0.2]), np.array([0.1, 0.3]), 0.01, "S1.10")
    zero = Fixed.const(0, "S1.10")
    relu = v.where(v >= 0, zero)
    assert np.allclose(relu.dev, 0.01 * (1 + 1e-12))
    assert relu.lo[0] == 0 and relu.hi[0] == pytest.approx(0.1)
    one = Interval.exact(np.ones(2), "S1.10")
    step = one.where(v >= 0, Interval.exact(np.zeros(2), "S1.10"))
    assert step.dev[0] >= 1.0     # either side of 0: a jump of 1
    assert step.dev[1] == 0.0     # 0.2 - 0.01 > 0: both sides take 1


def test_an_interval_has_no_raw_codes():
    with pytest.raises(TypeError, match="ranges, not raw codes"):
        Interval.exact([1.0], "S1.10").raw
