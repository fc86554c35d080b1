import numpy as np
import pytest

from phongfx.config import DiffuseConfig
from phongfx.core.registry import get_block
from phongfx.golden.diffuse import diffuse
from phongfx.golden.fixed import Fixed

LSB = 2.0 ** -10
AXES = np.concatenate([np.eye(3), -np.eye(3)])


def run(n, l, config=DiffuseConfig()):
    return diffuse(config, Fixed.from_float(n, config.vec), Fixed.from_float(l, config.vec))["diff"]


def raw_run(n, l, config=DiffuseConfig()):
    return diffuse(config, Fixed(n, config.vec), Fixed(l, config.vec))["diff"].raw


def test_light_along_the_normal_is_exactly_one():
    np.testing.assert_equal(run(AXES, AXES).to_float(), np.ones(6))


def test_backside_and_perpendicular_lights_are_zero():
    np.testing.assert_equal(run(AXES, -AXES).raw, np.zeros(6))
    np.testing.assert_equal(run(AXES, np.roll(AXES, 1, axis=1)).raw, np.zeros(6))


@pytest.mark.parametrize("rounding, half", [("round_half_up", 1), ("truncate", 0),
                                            ("round_half_even", 0)])
def test_grazing_lights_round_once_and_clamp_below(rounding, half):
    # raw N = (1024, 0, 512): N·L = ±1, ±1/2 LSB with L = (±1, 0, 0), (0, 0, ±1)
    config = DiffuseConfig(rounding=rounding)
    n = [[1024, 0, 512]] * 4
    out = raw_run(n, [[1, 0, 0], [0, 0, 1], [-1, 0, 0], [0, 0, -1]], config)
    np.testing.assert_equal(out, [1, half, 0, 0])


@pytest.mark.parametrize("rounding, bound", [("round_half_up", 0.5), ("round_half_even", 0.5),
                                             ("truncate", 1 - LSB)])
def test_matches_float_within_bound(rounding, bound):
    # the only inexact step is one rounding of the exact N·L (20 fraction bits, so
    # truncation loses at most 1 - 2^-10 LSB); full-range codes saturate at the top
    block = get_block("diffuse", rounding=rounding)
    raw = block.stimulus(count=2000, seed=3)
    dot = np.sum(raw["n"] * raw["l"], axis=-1) * LSB * LSB
    want = np.clip(dot, 0, 2 - LSB)
    err = np.abs(block.golden(raw)["diff"] * LSB - want)
    assert np.max(err) <= bound * LSB


def test_every_backside_light_gives_zero():
    block = get_block("diffuse")
    raw = block.stimulus(count=2000, seed=4)
    back = np.sum(raw["n"] * raw["l"], axis=-1) < 0
    assert np.count_nonzero(back) > 1000
    np.testing.assert_equal(block.golden(raw)["diff"][back], 0)


def test_junk_codes_saturate_instead_of_wrapping():
    # N = L = (1.5, 1.5, 1.5): N·L = 6.75 saturates to the top of 1.10
    np.testing.assert_equal(run([[1.5, 1.5, 1.5]], [[1.5, 1.5, 1.5]]).raw, [2047])


def test_config_errors_name_the_field():
    with pytest.raises(ValueError, match=r"^out must be an unsigned format \(n\.m\), not S1\.10$"):
        DiffuseConfig(out="S1.10")
    with pytest.raises(ValueError, match=r"^out must hold exactly 1\.0 \(at least 1 integer bit\), not 0\.10$"):
        DiffuseConfig(out="0.10")
    with pytest.raises(ValueError, match=r"^vec must be a signed format \(Sn\.m\), not 1\.10$"):
        DiffuseConfig(vec="1.10")
