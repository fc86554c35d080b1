import numpy as np
import pytest

from phongfx.config import ReflectConfig
from phongfx.core.registry import get_block
from phongfx.golden.fixed import Fixed
from phongfx.golden.reflect import reflect
from phongfx.sim.stimulus import codes, rng, unit_vectors

LSB = 2.0 ** -10
AXES = np.concatenate([np.eye(3), -np.eye(3)])


def run(n, v, config=ReflectConfig()):
    return reflect(config, Fixed.from_float(n, config.vec), Fixed.from_float(v, config.vec))["r"]


def exact(raw, config):
    """float64 reflection of the same (already quantized) inputs."""
    n, v = raw["n"] * config.fmt("vec").lsb, raw["v"] * config.fmt("vec").lsb
    return 2 * np.sum(n * v, axis=-1, keepdims=True) * n - v


def test_axis_normal_equal_to_view_reflects_to_itself():
    # N·V = 1 exactly, and N = -V gives N·V = -1: R = V both ways
    np.testing.assert_equal(run(AXES, AXES).to_float(), AXES)
    np.testing.assert_equal(run(-AXES, AXES).to_float(), AXES)


def test_grazing_reflects_to_minus_v():
    # N = (a, b, c), V = (b, -a, 0): N·V = 0 exactly for any codes, so R = -V exactly
    config = ReflectConfig()
    n = codes(unit_vectors(200, rng(5)), config.fmt("vec"))
    v = np.stack([n[:, 1], -n[:, 0], np.zeros(len(n), dtype=np.int64)], axis=-1)
    r = reflect(config, Fixed(n, config.vec), Fixed(v, config.vec))["r"]
    np.testing.assert_equal(r.raw, -v)


def test_45_degree_normal_turns_the_view_by_90():
    # N = (1,1,0)/√2 quantized to 724/1024 leaves R = (-0.22, 1023.78, 0) LSB: rounds to y
    r = run([[0.5 ** 0.5, 0.5 ** 0.5, 0]], [[1.0, 0, 0]])
    np.testing.assert_equal(r.raw, [[0, 1024, 0]])


@pytest.mark.parametrize("rounding, bound", [("round_half_up", 0.75), ("round_half_even", 0.75),
                                             ("truncate", 1.5)])
def test_unit_inputs_match_float_within_bound(rounding, bound):
    # N·V rounded to S1.12 costs at most 2·|N_i|·(dot error) = 1/4 LSB (1/2 truncated),
    # the final rounding 1/2 LSB (1 truncated)
    block = get_block("reflect", rounding=rounding)
    raw = block.stimulus(count=2000, seed=3)
    unit = slice(0, len(raw["n"]) - 2000)  # the full-range codes come last
    raw = {name: column[unit] for name, column in raw.items()}
    err = np.abs(block.golden(raw)["r"] * LSB - exact(raw, block.config))
    assert np.max(err) <= bound * LSB


def test_full_range_codes_match_float_where_unsaturated():
    # |N_i| up to 2 doubles the cost of the dot rounding: 1/2 + 1/2 LSB
    block = get_block("reflect")
    raw = block.stimulus(count=2000, seed=4)
    want = exact(raw, block.config)
    dot = np.sum(raw["n"] * raw["v"], axis=-1) * LSB * LSB
    fine = (np.abs(dot) < 1.99)[:, None] & (np.abs(want) < 1.99)
    err = np.abs(block.golden(raw)["r"] * LSB - want)
    assert np.max(err[fine]) <= LSB


def test_length_stays_near_one_for_unit_inputs():
    # |R|² = |V|² + 4(N·V)²(|N|²-1), and quantized unit vectors are within √3/2 LSB of
    # unit length: about 3.5 LSB of growth, 1.3 LSB of rounding, under 2^-7 = 8 LSB
    g = rng(6)
    n, v = unit_vectors(3000, g), unit_vectors(3000, g)
    length = np.linalg.norm(run(n, v).to_float(), axis=-1)
    assert np.max(length) <= 1 + 2.0 ** -7
    assert np.min(length) >= 1 - 2.0 ** -7


def test_junk_codes_saturate_instead_of_wrapping():
    # N = V = (1.5, 1.5, 1.5): N·V = 6.75 saturates to ~2, R = 2·2·1.5 - 1.5 saturates to ~2
    r = run([[1.5, 1.5, 1.5]], [[1.5, 1.5, 1.5]])
    np.testing.assert_equal(r.raw, [[2047, 2047, 2047]])
    r = run([[1.5, 1.5, 1.5]], [[-1.5, -1.5, -1.5]])
    np.testing.assert_equal(r.raw, [[-2048, -2048, -2048]])


@pytest.mark.parametrize("rounding, r", [("round_half_up", [-8, 0, 1]), ("truncate", [-8, 0, 0])])
def test_dot_is_rounded_before_scaling(rounding, r):
    # raw N = (16, 0, 1024), V = (8, 0, 0): N·V = 2^-13, half an LSB of dot.  Rounded up to
    # 2^-12 it makes R_z = 2^-11, half an LSB of R, so 1 (exact R_z = 2^-12 would give 0);
    # truncated, N·V is 0 and R = -V exactly
    config = ReflectConfig(rounding=rounding)
    out = reflect(config, Fixed([[16, 0, 1024]], config.vec), Fixed([[8, 0, 0]], config.vec))["r"]
    np.testing.assert_equal(out.raw, [r])


def test_config_errors_name_the_field():
    with pytest.raises(ValueError, match=r"^dot must hold exactly 1\.0 \(at least 1 integer bit\), not S0\.12$"):
        ReflectConfig(dot="S0.12")
    with pytest.raises(ValueError, match=r"^vec must be a signed format \(Sn\.m\), not 1\.10$"):
        ReflectConfig(vec="1.10")
    with pytest.raises(ValueError, match=r"^rounding must be one of truncate, round_half_up, round_half_even, not 'nearest'$"):
        ReflectConfig(rounding="nearest")
