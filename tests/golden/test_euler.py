import numpy as np
import pytest

from phongfx.config import EulerConfig
from phongfx.core.registry import get_block
from phongfx.golden.euler import euler
from phongfx.golden.euler_setup import quantize_setup, span_setup
from phongfx.golden.fixed import Fixed
from phongfx.sim.stimulus.euler import span


def wrap(value, fmt):
    """``value`` kept in ``fmt``'s register width, two's complement."""
    modulus = 1 << fmt.width
    value %= modulus
    return value - modulus if value >= modulus // 2 else value


def loop(config, raw):
    """The unit as a plain Python loop over pixels: output p, then p += t, t += ds."""
    p_fmt, t_fmt, d_fmt = (config.fmt(name) for name in ("p", "t", "ds"))
    up_t, up_d = p_fmt.frac_bits - t_fmt.frac_bits, t_fmt.frac_bits - d_fmt.frac_bits
    p = t = ds = 0
    out = []
    for i in range(len(raw["init"])):
        if raw["init"][i]:
            p, t, ds = int(raw["p0"][i]), int(raw["t0"][i]), int(raw["ds"][i])
        out.append(p)
        p, t = wrap(p + (t << up_t), p_fmt), wrap(t + (ds << up_d), t_fmt)
    return np.array(out)


def run(config, raw):
    return euler(config, Fixed(raw["init"], "1.0"), Fixed(raw["p0"], config.p),
                 Fixed(raw["t0"], config.t), Fixed(raw["ds"], config.ds))


@pytest.mark.parametrize("changes", [
    {}, dict(p="S1.20", t="S2.16", ds="S3.12"),
    # narrow registers: random loads wrap at nearly every step
    dict(p="S1.6", t="S1.6", ds="S0.6"), dict(p="S0.10", t="S4.8", ds="S6.2", out="S1.4"),
])
def test_golden_matches_python_loop(changes):
    block = get_block("euler", **changes)
    raw = block.stimulus(count=600, seed=3)
    # pixels before any init keep the reset state: p = t = ds = 0
    raw = {name: np.concatenate([value[5:9], value]) for name, value in raw.items()}
    raw["init"][:4] = 0
    out = block.golden(raw)
    assert np.array_equal(out["p"], loop(block.config, raw))
    assert not np.any(out["p"][:4])


def test_span_follows_equation_14():
    config = EulerConfig()
    loads = quantize_setup(config, span_setup([0, 0, 1], [0.8, 0, 0.6], [0.6, 0, 0.8], 300))
    p = run(config, span(config, 300, np.random.default_rng(0), **loads))["p"].raw
    k = np.arange(300)
    assert np.array_equal(p, loads["p0"] + k * loads["t0"] + k * (k - 1) // 2 * loads["ds"])


def test_level_truncates_and_saturates():
    config = EulerConfig()
    one = 1 << 30
    codes = [-one, -1, 0, one // 256 - 1, one // 256, one - 1, one, 2 * one - 1]
    raw = {"init": np.ones(len(codes), dtype=np.int64), "p0": np.array(codes),
           "t0": np.zeros(len(codes), dtype=np.int64), "ds": np.zeros(len(codes), dtype=np.int64)}
    assert run(config, raw)["level"].raw.tolist() == [0, 0, 0, 0, 1, 255, 255, 255]


def test_config_errors_name_the_field():
    with pytest.raises(ValueError, match=r"^ds \(S3\.31\) may not have more fraction bits than "
                                         r"t \(S3\.30\): ds is added into t exactly$"):
        EulerConfig(ds="S3.31")
    with pytest.raises(ValueError, match=r"^t \(S3\.31\) may not have more fraction bits than "
                                         r"p \(S1\.30\): t is added into p exactly$"):
        EulerConfig(t="S3.31", ds="S3.31")
    with pytest.raises(ValueError, match=r"^p must be a signed format \(Sn\.m\), not 1\.30$"):
        EulerConfig(p="1.30")
    with pytest.raises(ValueError, match=r"^out: format must look like 'n\.m' \(unsigned\) or "
                                         r"'Sn\.m' \(signed\), not '8'$"):
        EulerConfig(out="8")
