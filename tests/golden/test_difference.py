import numpy as np
import pytest

from phongfx.config import DifferenceConfig
from phongfx.core.registry import get_block
from phongfx.golden.difference import difference
from phongfx.golden.fixed import Fixed


def run(r, l, n, config=DifferenceConfig()):
    return difference(config, Fixed.from_float(r, config.vec), Fixed.from_float(l, config.vec),
                      Fixed.from_float(n, config.n))["x2"]


def test_equal_vectors_give_zero():
    v = [[1.0, 0, 0], [0.6, -0.8, 0], [-0.5, 0.5, -0.70703125]]
    assert run(v, v, [8000, 1, 77]).raw.tolist() == [0, 0, 0]


def test_one_lsb_apart_at_n_max():
    # D = 1 LSB: D·D = 2^-20 exactly, 2x = 8000·2^-20 = 0.00763 rounds to 31 LSB of 13.12
    lsb = 2.0 ** -10
    assert run([[1.0, 0, 0]], [[1.0 - lsb, 0, 0]], [8000]).raw[0] == round(8000 * 2.0 ** -8)


def test_opposite_vectors_saturate():
    # |D| = 2: D = -2 is exact and D·D = 4 saturates to 4 - 2^-20, which rounds to 2x = 4;
    # D = +2 saturates to 2 - 2^-10 first, so 2x = (2 - 2^-10)² (rounded)
    x2 = run([[-1.0, 0, 0], [1.0, 0, 0]], [[1.0, 0, 0], [-1.0, 0, 0]], [1, 1]).to_float()
    assert x2[0] == 4.0
    assert x2[1] == round((2 - 2.0 ** -10) ** 2 * 4096) / 4096
    # and n = 8000 clamps 2x to the top of 13.12
    assert run([[0, 0, 1.0]], [[0, 0, -1.0]], [8000]).raw[0] == 2 ** 25 - 1


def test_matches_float_within_half_lsb():
    block = get_block("difference")
    raw = block.stimulus(count=500, seed=3)
    x2 = block.golden(raw)["x2"] * 2.0 ** -12
    d = (raw["r"] - raw["l"]) * 2.0 ** -10
    exact = raw["n"] * np.sum(d * d, axis=-1)  # n·|R-L|² = 2x
    # saturation of D (a component >= +2 or < -2) and of D·D (>= 4) is tested above
    clean = (np.max(d, axis=-1) < 2) & (np.min(d, axis=-1) >= -2) & (np.sum(d * d, axis=-1) < 4)
    assert np.count_nonzero(clean & (exact < 8)) > 100  # where f_2 is nonzero
    fits = clean & (exact < 8192)
    assert np.max(np.abs(x2 - exact)[fits]) <= 2.0 ** -13
    assert np.all(x2[clean & (exact >= 8192)] == 8192 - 2.0 ** -12)


@pytest.mark.parametrize("n", [0, 8001])
def test_n_outside_range_is_refused(n):
    with pytest.raises(ValueError, match=rf"^n must be in 1\.\.8000; 1 value\(s\) are not, "
                                         rf"first {n} \(raw {n}\)$"):
        run([[1.0, 0, 0]], [[0, 1.0, 0]], [n])


def test_n_max_is_configurable():
    config = DifferenceConfig(n_max=100)
    assert run([[1.0, 0, 0]], [[1.0, 0, 0]], [100], config).raw[0] == 0
    with pytest.raises(ValueError, match=r"^n must be in 1\.\.100; 2 value\(s\) are not, first 101 "):
        run([[1.0, 0, 0]] * 3, [[1.0, 0, 0]] * 3, [101, 5, 8000], config)


def test_config_errors_name_the_field():
    with pytest.raises(ValueError, match=r"^dd must be an unsigned format \(n\.m\), not S2\.20$"):
        DifferenceConfig(dd="S2.20")
    with pytest.raises(ValueError, match=r"^d must be a signed format \(Sn\.m\), not 1\.10$"):
        DifferenceConfig(d="1.10")


def test_constant_n_vectors_have_no_port_and_reach_the_peak_edge():
    raw = get_block("difference", n_const=16).stimulus(count=200, seed=1)
    assert set(raw) == {"r", "l"}
    x2 = get_block("difference", n_const=16).golden(raw)["x2"] * 2.0 ** -12
    # the grazing approach puts x = 2x/2 on 0..32 for this n: both sides of x = 2^k, k <= 4
    assert np.count_nonzero(x2 / 2 < 1) > 20 and np.count_nonzero((x2 / 2 > 16) & (x2 / 2 < 32)) > 5
