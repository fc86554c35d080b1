import numpy as np
import pytest

from phongfx.config import NormalizeConfig
from phongfx.core.registry import get_block
from phongfx.golden.fixed import Fixed
from phongfx.golden.normalize import normalize
from phongfx.sim.stimulus import rng, unit_vectors

ROUNDINGS = ["truncate", "round_half_up", "round_half_even"]


def run(n, config=NormalizeConfig()):
    return normalize(config, Fixed.from_float(n, config.vec))["n"]


def lengths(n, order):
    return np.linalg.norm(run(n, NormalizeConfig(order=order)).to_float(), axis=-1)


@pytest.mark.parametrize("order", [1, 2])
@pytest.mark.parametrize("rounding", ROUNDINGS)
def test_unit_axes_are_unchanged_and_zero_stays_zero(order, rounding):
    n = np.concatenate([np.eye(3), -np.eye(3), np.zeros((1, 3))])
    out = run(n, NormalizeConfig(order=order, rounding=rounding))
    np.testing.assert_equal(out.to_float(), n)


@pytest.mark.parametrize("rounding", ROUNDINGS)
def test_tiny_vectors_are_doubled(rounding):
    # |N'| < 2**-6.5 rounds to z = 0, where g2 = 2 saturates to 2 - 2**-12: rounding to
    # nearest still gives exactly 2N'; truncation floors positive components one LSB lower
    s = np.arange(-11, 12)
    n = Fixed(np.stack([s, -s, np.zeros_like(s)], axis=-1), "S1.10")
    out = normalize(NormalizeConfig(rounding=rounding), n)["n"]
    low = (n.raw > 0) if rounding == "truncate" else 0
    np.testing.assert_equal(out.raw, 2 * n.raw - low)


def test_half_length_squared_gives_lyons_numbers():
    # the midpoint of a 90° span: z = 1/2, y = 1/2; Lyon: g2 = 1.375 (~3 % short), g1 = 1.25 (~12 %)
    n = [[0.5, 0.5, 0], [0, -0.5, 0.5]]
    np.testing.assert_equal(run(n, NormalizeConfig(order=2)).to_float(), np.multiply(n, 1.375))
    np.testing.assert_equal(run(n, NormalizeConfig(order=1)).to_float(), np.multiply(n, 1.25))
    assert np.allclose(lengths(n, 2), 0.9723, atol=1e-4)  # 2.8 % short
    assert np.allclose(lengths(n, 1), 0.8839, atol=1e-4)  # 11.6 % short


def test_g2_is_within_half_percent_from_length_0_8_to_1_figure_4():
    u = unit_vectors(200, rng(9))
    n = (u[None] * np.linspace(0.8, 1.0, 101)[:, None, None]).reshape(-1, 3)
    assert np.max(np.abs(lengths(n, 2) - 1)) < 0.005
    # g1 is "reasonable only over a more limited range": over 5 % short at 0.8
    assert np.max(lengths(u * 0.8, 1)) < 0.95


def test_g2_over_corrects_near_0_9_to_about_1_002():
    u = unit_vectors(400, rng(4))
    sizes = np.linspace(0.8, 1.0, 21)
    mean = np.array([np.mean(lengths(u * s, 2)) for s in sizes])
    assert 0.88 <= sizes[np.argmax(mean)] <= 0.91
    assert abs(mean.max() - 1.002) < 0.0005


@pytest.mark.parametrize("order", [1, 2])
@pytest.mark.parametrize("rounding", ROUNDINGS)
def test_matches_float_g_within_stated_lsbs(order, rounding):
    # Each rounding (z, y², g) errs by half a 1.12 LSB (a whole one truncating); through
    # |dg/dy|·|N'| <= 0.71 and |N'| <= 1 that is <= 0.28 output LSB, plus N's own rounding
    block = get_block("normalize", order=order, rounding=rounding)
    raw = block.stimulus(count=1000, seed=3)
    n = raw["n"] * 2.0 ** -10
    out = block.golden(raw)["n"] * 2.0 ** -10
    z = np.sum(n * n, axis=-1)
    y = 1 - z
    g = 1 + y / 2 if order == 1 else 1 + (y + y * y) / 2
    inside = z <= 1.01  # up to a hair over unit length; beyond is junk that saturates
    err = np.abs(out - n * g[:, None])[inside] / 2.0 ** -10
    assert np.count_nonzero(inside) > 6000
    assert err.max() <= (1.56 if rounding == "truncate" else 0.78)


def test_y2_overflow_is_declared_only_where_impossible():
    assert NormalizeConfig().y2_overflow == "error"
    wide = NormalizeConfig(z="2.12")
    assert wide.y2_overflow == "saturate"
    # junk z = 12 and 3.25 keep y = -3 and -2.25 in a 2.12 z: y² = 9 and 5.06 overflow 1.12
    # and saturate to 2 - 2**-12, so g2 = 1 + (y + y²)/2 is 0.5 and 0.875 (to within 2**-13)
    out = run([[-2.0, -2.0, -2.0], [1.5, 1.0, 0]], wide)
    np.testing.assert_equal(out.to_float(), [[-1.0, -1.0, -1.0], [1.3125, 0.875, 0]])


def test_vectors_are_seeded_and_start_with_extremes():
    block = get_block("normalize")
    a, b, c = (block.stimulus(count=50, seed=s)["n"] for s in (1, 1, 2))
    np.testing.assert_equal(a, b)
    assert not np.array_equal(a, c)
    np.testing.assert_equal(a[:7], np.concatenate([np.eye(3), -np.eye(3), np.zeros((1, 3))]) * 1024)
    assert set(range(-2048, 2048)) <= set(a[:, 0].tolist())


def test_config_errors_name_the_field():
    with pytest.raises(ValueError, match=r"^order must be an integer in 1\.\.2, not 3$"):
        NormalizeConfig(order=3)
    with pytest.raises(ValueError, match=r"^order must be an integer in 1\.\.2, not True$"):
        NormalizeConfig(order=True)
    with pytest.raises(ValueError, match=r"^z must be an unsigned format \(n\.m\), not S1\.12$"):
        NormalizeConfig(z="S1.12")
    with pytest.raises(ValueError, match=r"^g must hold exactly 1\.0 \(at least 1 integer bit\), not 0\.12$"):
        NormalizeConfig(g="0.12")
    with pytest.raises(ValueError, match=r"^out must be a signed format \(Sn\.m\), not 1\.10$"):
        NormalizeConfig(out="1.10")
    with pytest.raises(ValueError, match=r"^rounding must be one of truncate, round_half_up, "
                                         r"round_half_even, not 'nearest'$"):
        NormalizeConfig(rounding="nearest")
