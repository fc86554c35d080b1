from fractions import Fraction

import numpy as np
import pytest

from phongfx.config import SchlickConfig
from phongfx.core.format import Format
from phongfx.core.registry import get_block
from phongfx.golden.fixed import Fixed
from phongfx.golden.schlick import divisor, schlick
from phongfx.papers.schlick import FIGURE1_N, schlick_table
from phongfx.sim.stimulus.schlick import directed, sweep_n

EVERY_T = np.arange((1 << 15) + 1)  # every code of 1.15 in 0..1


def run(t, n, config=SchlickConfig()):
    t = np.asarray(t)
    n = np.broadcast_to(np.asarray(n), t.shape)
    return schlick(config, Fixed(t, config.t), Fixed(n, config.n))["spec"]


def exact_lsb(t, n, config):
    """``S_n(t)·2^F`` as a float from the exact rational (``Fraction``), code by code."""
    one, out_one = config.fmt("t").one, config.fmt("out").one
    return np.array([float(Fraction(int(a) * out_one, int(b) * (one - int(a)) + int(a)))
                     for a, b in zip(t, n)])


@pytest.mark.parametrize("n", [1, 2, 6, 16, 64, 8000])
def test_truncation_is_under_one_lsb_of_float(n):
    # t/(n - n·t + t) is exact in float here: n·t holds 13 + 16 bits, the sum is exact and
    # the division correctly rounded, never onto the next code (it is ≥ 2^-43 away)
    t = EVERY_T * 2.0 ** -15
    error = (t / (n - n * t + t) - run(EVERY_T, n).to_float()) * 2.0 ** 15
    assert np.min(error) >= 0 and np.max(error) < 1


@pytest.mark.parametrize("n", [2, 6, 64, 8000])
def test_round_half_up_is_within_half_an_lsb(n):
    config = SchlickConfig(rounding="round_half_up")
    t = EVERY_T * 2.0 ** -15
    error = (t / (n - n * t + t) - run(EVERY_T, n, config).to_float()) * 2.0 ** 15
    assert np.max(np.abs(error)) <= 0.5


def test_equals_the_floor_of_the_exact_rational():
    config = SchlickConfig(t="1.10", n="6.0", n_max=63, out="1.12")
    raw = get_block("schlick", config=config).stimulus(count=300, seed=3)
    spec = run(raw["t"], raw["n"], config).raw
    assert np.array_equal(spec, np.floor(exact_lsb(raw["t"], raw["n"], config)).astype(np.int64))


def test_s1_is_t_and_the_ends_are_exact():
    assert np.array_equal(run(EVERY_T, 1).raw, EVERY_T)
    ns = np.arange(1, 8001)
    assert np.all(run(np.full(8000, 1 << 15), ns).raw == 1 << 15)  # S_n(1) = 1
    assert not np.any(run(np.zeros(8000, dtype=np.int64), ns).raw)  # S_n(0) = 0


@pytest.mark.parametrize("config", [SchlickConfig(), SchlickConfig(rounding="round_half_up")])
@pytest.mark.parametrize("n", [2, 6, 16, 64, 1000, 8000])
def test_monotone_in_t(config, n):
    assert np.all(np.diff(run(EVERY_T, n, config).raw) >= 0)


def test_monotone_falling_in_n():
    # S_n(t) = 1/(1 + n(1/t - 1)) falls with n for t < 1
    ns = np.arange(1, 8001)
    for t in (1, 1 << 14, (1 << 15) - 1):
        assert np.all(np.diff(run(np.full(8000, t), ns).raw) <= 0)


def test_divisor_is_exact_and_spans_one_to_n_max():
    config = SchlickConfig()
    t, n = directed(config)["t"], directed(config)["n"]
    den = divisor(config, Fixed(t, config.t), Fixed(n, config.n))
    assert den.fmt == config.den == Format(13, 15)
    assert np.array_equal(den.raw, n * ((1 << 15) - t) + t)
    assert den.raw.min() == 1 << 15 and den.raw.max() == 8000 << 15


def test_inputs_are_validated():
    config = SchlickConfig()
    with pytest.raises(ValueError, match=r"^t must be in 0\.\.1; 1 value\(s\) are not, "
                                         r"first 1\.00003 \(raw 32769\)$"):
        run([0, 32769], 5)
    with pytest.raises(ValueError, match=r"^n must be in 1\.\.8000; 2 value\(s\) are not, "
                                         r"first 0 \(raw 0\)$"):
        run([0, 1, 2], [0, 8001, 5], config)


def test_config_errors_name_the_field():
    with pytest.raises(ValueError, match=r"^rounding must be one of truncate, round_half_up "
                                         r"\(the divider floors\), not 'round_half_even'$"):
        SchlickConfig(rounding="round_half_even")
    with pytest.raises(ValueError, match=r"^rounding must be one of truncate, round_half_up, "
                                         r"round_half_even, not 'nearest'$"):
        SchlickConfig(rounding="nearest")
    with pytest.raises(ValueError, match=r"^t must hold exactly 1\.0 \(at least 1 integer bit\), "
                                         r"not 0\.16$"):
        SchlickConfig(t="0.16")
    with pytest.raises(ValueError, match=r"^out must be an unsigned format \(n\.m\), not S1\.15$"):
        SchlickConfig(out="S1.15")
    with pytest.raises(ValueError, match=r"^n_max must be an integer in 1\.\.63, not 64$"):
        SchlickConfig(n="6.0", n_max=64)
    with pytest.raises(ValueError, match=r"^n must be an integer format \(m = 0\), not 6\.2$"):
        SchlickConfig(n="6.2")
    with pytest.raises(ValueError, match=r"^t \(1\.31\) shifted by 31 quotient bits exceeds 62 bits$"):
        SchlickConfig(t="1.31", out="1.31")
    assert SchlickConfig().quotient_bits == 16
    assert SchlickConfig(rounding="round_half_up").quotient_bits == 17


def test_vectors_hold_the_directed_set_and_every_t():
    config = SchlickConfig()
    raw = get_block("schlick").stimulus(count=10, seed=0)
    d = directed(config)
    assert np.array_equal(raw["t"][:len(d["t"])], d["t"]) and np.array_equal(raw["n"][:len(d["n"])], d["n"])
    assert set(d["n"].tolist()) >= {1, 2, 7999, 8000, 4095, 1}
    assert sweep_n(config) == [6, 8000]
    pairs = set(zip(raw["t"].tolist(), raw["n"].tolist()))
    assert all((t, n) in pairs for n in (6, 8000) for t in range((1 << 15) + 1))
    assert len(raw["t"]) == len(d["t"]) + 2 * ((1 << 15) + 1) + 10


def test_figure1_table(tmp_path):
    path = tmp_path / "fig" / "schlick_fig1.png"
    rows = schlick_table(path)
    assert [row["n"] for row in rows] == list(FIGURE1_N)
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert sorted(p.name for p in path.parent.iterdir()) == ["schlick_fig1.png"]  # no temp left
    measured = [(row["max_float"], row["t_at_max"]) for row in rows]
    np.testing.assert_allclose(measured, [(0, 0), (0.09017, 0.38196), (0.16271, 0.68500),
                                          (0.18789, 0.85995), (0.19965, 0.96188)], atol=1e-4)
    for row in rows:
        # the unit's floor moves each value down by under 1 LSB of 1.15
        assert abs(row["max_fixed"] - row["max_float"]) < 2.0 ** -15
        assert row["max_lsb"] < 1
