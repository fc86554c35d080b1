import numpy as np
import pytest

from phongfx.config import DifferenceConfig, ShapeConfig
from phongfx.config.shape import K_MAX
from phongfx.core.registry import get_block
from phongfx.golden.fixed import Fixed
from phongfx.golden.shape import shape
from phongfx.sim.stimulus.shape import nonzero_codes, threshold


def run(raw, config=ShapeConfig()):
    return shape(config, Fixed(raw, config.x2))["spec"]


def f_k(x, k):
    """Lyon's shape function in floating point, 0 from ``x/2^k = 1`` on."""
    v = np.minimum(x / 2.0 ** k, 1.0)
    return (1.0 - v) ** (2 ** k)


def bound(config):
    """LSB bound of the module docstring: ``2^k·e0 + (2^k - 1)·r``, ``r`` the rounding error."""
    r = 1.0 if config.rounding == "truncate" else 0.5
    e0 = r if config.fmt("x2").frac_bits + config.k + 1 > config.fmt("t").frac_bits else 0.0
    return 2 ** config.k * e0 + (2 ** config.k - 1) * r


def sweep(config):
    # every code to the threshold (not strided), and a margin past it
    raw = np.arange(threshold(config) + 64)
    return raw, run(raw, config)


@pytest.mark.parametrize("rounding", ["round_half_up", "round_half_even", "truncate"])
@pytest.mark.parametrize("k", [*range(5), 7, K_MAX])
def test_matches_float_within_bound(k, rounding):
    config = ShapeConfig(k=k, rounding=rounding)
    raw, spec = sweep(config)
    error = np.abs(spec.to_float() - f_k(raw * 2.0 ** -13, k)) * 2.0 ** 15
    assert np.max(error) <= bound(config)


def test_measured_error_with_default_rounding():
    # what the bound leaves unused (max |error| in LSB of 1.15, k = 0..4)
    measured = [np.max(np.abs(s.to_float() - f_k(r * 2.0 ** -13, k))) * 2.0 ** 15
                for k in range(5) for r, s in [sweep(ShapeConfig(k=k))]]
    np.testing.assert_allclose(measured, [0, 0.5, 1.4153, 6.6211, 12.4463], atol=1e-4)


@pytest.mark.parametrize("k", range(5))
def test_peak_is_exactly_one(k):
    assert run([0], ShapeConfig(k=k)).to_float().tolist() == [1.0]


@pytest.mark.parametrize("k", range(5))
def test_zero_from_threshold_on(k):
    config = ShapeConfig(k=k)
    top = threshold(config)
    above = np.concatenate([np.arange(top, top + 4096), 1 << np.arange(k + 13, 25), [2 ** 25 - 1]])
    assert not np.any(run(above, config).raw)
    # just below, 1 - x/2^k is 2^-(13+k): 4 LSB of t for k = 0, squared away for k >= 1
    assert run([top - 1], config).raw[0] == (4 if k == 0 else 0)


@pytest.mark.parametrize("k", range(5))
def test_monotone_over_exhaustive_sweep(k):
    config = ShapeConfig(k=k)
    spec = run(get_block("shape", k=k).stimulus(count=0)["x2"][:len(nonzero_codes(config))], config)
    assert np.all(np.diff(spec.raw) <= 0)
    assert spec.raw[0] == 1 << 15


def test_exhaustive_set_sizes():
    assert len(nonzero_codes(ShapeConfig(k=2))) == 8 * 2 ** 12
    assert [len(nonzero_codes(ShapeConfig(k=k))) for k in range(5)] == [
        2 ** 13, 2 ** 14, 2 ** 15, 2 ** 16, 2 ** 16]


def test_difference_then_shape_follows_the_float_chain():
    # Figure 7c then 7d on unit vectors near the peak: against float f_2(n/2·|R-L|²) on the
    # same codes; 2x is within 2^-13, so x within 2^-14, which moves f_2 by at most
    # max |f_2'|·2^-14 = 2^-14, 2 LSB of 1.15: the 12 fraction bits of 2x cost more than t
    block = get_block("difference")
    raw = block.stimulus(count=500, seed=5)
    x2 = block.golden(raw)["x2"]
    d = (raw["r"] - raw["l"]) * 2.0 ** -10
    x = raw["n"] / 2 * np.sum(d * d, axis=-1)
    keep = (x < 4) & (np.max(np.abs(d), axis=-1) < 2) & (np.sum(d * d, axis=-1) < 4)  # unsaturated
    spec = run(x2[keep]).to_float()
    assert np.count_nonzero(keep) > 100
    assert np.max(np.abs(spec - f_k(x[keep], 2))) * 2.0 ** 15 <= bound(ShapeConfig()) + 2


def test_config_errors_name_the_field():
    with pytest.raises(ValueError, match=r"^k must be an integer in 0\.\.10, not 11$"):
        ShapeConfig(k=11)
    with pytest.raises(ValueError, match=r"^x2 must have at least k\+2 = 5 integer bits so that "
                                         r"x/2\^k reaches 1, not 4\.12$"):
        ShapeConfig(x2="4.12", k=3)
    with pytest.raises(ValueError, match=r"^t must hold exactly 1\.0 \(at least 1 integer bit\), "
                                         r"not 0\.16$"):
        ShapeConfig(t="0.16")
    with pytest.raises(ValueError, match=r"^rounding must be one of truncate, round_half_up, "
                                         r"round_half_even, not 'nearest'$"):
        ShapeConfig(rounding="nearest")
    assert DifferenceConfig().x2 == ShapeConfig().x2  # Figure 7c feeds 7d
