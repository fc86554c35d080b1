import numpy as np
import pytest

from phongfx.config import GouraudConfig
from phongfx.core.registry import get_block
from phongfx.golden.euler_setup import gouraud_curve, quantize_gouraud, span_setup
from phongfx.golden.fixed import Fixed
from phongfx.golden.gouraud import gouraud
from phongfx.sim.stimulus.gouraud import span


def loop(config, raw):
    """The unit as a plain Python loop over pixels: output p, then p += dp."""
    p_fmt, up = config.fmt("p"), config.fmt("p").frac_bits - config.fmt("dp").frac_bits
    modulus = 1 << p_fmt.width
    p = dp = 0
    out = []
    for i in range(len(raw["init"])):
        if raw["init"][i]:
            p, dp = int(raw["p0"][i]), int(raw["dp"][i])
        out.append(p)
        p = (p + (dp << up)) % modulus
        p = p - modulus if p >= modulus // 2 else p
    return np.array(out)


@pytest.mark.parametrize("changes", [{}, dict(p="S1.20", dp="S3.12"), dict(p="S1.6", dp="S3.4")])
def test_golden_matches_python_loop(changes):
    block = get_block("gouraud", **changes)
    raw = block.stimulus(count=600, seed=3)
    raw = {name: np.concatenate([value[5:9], value]) for name, value in raw.items()}
    raw["init"][:4] = 0
    out = block.golden(raw)
    assert np.array_equal(out["p"], loop(block.config, raw))
    assert not np.any(out["p"][:4])


def test_span_follows_the_chord():
    # the float chord, within the rounding of p0 plus n roundings of dp (1/2 LSB each)
    config = GouraudConfig()
    setup = span_setup([0, 0, 1], [0.8, 0, 0.6], [0.6, 0, 0.8], 2048)
    raw = span(config, 2048, np.random.default_rng(0), **quantize_gouraud(config, setup))
    p = gouraud(config, Fixed(raw["init"], "1.0"), Fixed(raw["p0"], config.p), Fixed(raw["dp"], config.dp))
    error = np.abs(p["p"].to_float() - gouraud_curve(setup)) * 2.0 ** 30
    assert np.max(error) <= (1 + 2047) / 2


def test_config_errors_name_the_field():
    with pytest.raises(ValueError, match=r"^dp \(S3\.31\) may not have more fraction bits than "
                                         r"p \(S1\.30\): dp is added into p exactly$"):
        GouraudConfig(dp="S3.31")
    with pytest.raises(ValueError, match=r"^dp must be a signed format \(Sn\.m\), not 3\.30$"):
        GouraudConfig(dp="3.30")
