import numpy as np
import pytest

from phongfx.config import LirpConfig
from phongfx.core.registry import get_block
from phongfx.golden.fixed import Fixed
from phongfx.golden.lirp import lirp


def run(n0, n1, a, config=LirpConfig()):
    return lirp(config, Fixed.from_float(n0, config.vec), Fixed.from_float(n1, config.vec),
                Fixed.from_float(a, config.a))["n"]


def test_ends_are_exact():
    n0 = [[1.0, 0, 0], [0.625, -0.75, 0]]
    n1 = [[0, -1.0, 0], [0, 0, 1.0]]
    np.testing.assert_equal(run(n0, n1, [0, 0]).to_float(), n0)
    np.testing.assert_equal(run(n0, n1, [1, 1]).to_float(), n1)


def test_midpoint_of_opposite_vectors_is_zero():
    out = run([[1.0, -1.0, 0.5]], [[-1.0, 1.0, -0.5]], [0.5])
    np.testing.assert_equal(out.raw, [[0, 0, 0]])


def test_rounds_half_up_once():
    # (1-a)·0 + a·1LSB with a = 1/2 is half an LSB: rounds up to 1 LSB, truncate gives 0
    lsb = 2.0 ** -10
    assert run([[0, 0, 0]], [[lsb, 0, 0]], [0.5]).raw[0, 0] == 1
    assert run([[0, 0, 0]], [[lsb, 0, 0]], [0.5], LirpConfig(rounding="truncate")).raw[0, 0] == 0


def test_matches_float_within_half_lsb():
    block = get_block("lirp")
    raw = block.stimulus(count=500, seed=3)
    out = block.golden(raw)["n"] * 2.0 ** -10
    n0, n1 = raw["n0"] * 2.0 ** -10, raw["n1"] * 2.0 ** -10
    a = raw["a"][:, None] * 2.0 ** -10
    exact = (1 - a) * n0 + a * n1
    assert np.max(np.abs(out - exact)) <= 2.0 ** -11


def test_a_above_one_is_refused():
    with pytest.raises(ValueError, match=r"^a must be in 0\.\.1; 1 value\(s\) are not, first 1\.5 "):
        run([[1.0, 0, 0]], [[0, 1.0, 0]], [1.5])


def test_config_errors_name_the_field():
    with pytest.raises(ValueError, match=r"^a must be an unsigned format \(n\.m\), not S1\.10$"):
        LirpConfig(a="S1.10")
    with pytest.raises(ValueError, match=r"^a must hold exactly 1\.0 \(at least 1 integer bit\), not 0\.10$"):
        LirpConfig(a="0.10")
    with pytest.raises(ValueError, match=r"^vec: format must look like 'n\.m' \(unsigned\) or 'Sn\.m' \(signed\), not 'S1,10'$"):
        LirpConfig(vec="S1,10")
