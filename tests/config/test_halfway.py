import pytest

from phongfx.config import HalfwayConfig, NormalizeConfig


def test_vec_frac_sets_the_normalizer_of_h():
    unit = HalfwayConfig(pipeline=1).with_vec_frac(12)
    assert (unit.vec, unit.hvec, unit.dot, unit.out) == ("S1.12", "S2.13", "S2.14", "S2.12")
    # its ports take H (hvec), its guard bits follow the vectors as the datapath's normalizer
    assert unit.normalize == NormalizeConfig(vec="S2.13", out="S2.13", z="1.14", y2="1.14",
                                             g="1.14", pipeline=1)
    assert unit.variant == "g2proj" and unit.h == "mean"


def test_vec_frac_at_10_is_the_default():
    assert HalfwayConfig().with_vec_frac(10) == HalfwayConfig()


def test_the_normalizer_takes_h():
    with pytest.raises(ValueError, match=r"^normalize\.vec \(S1\.10\) must equal hvec \(S2\.11\): "
                                         r"the normalizer takes H$"):
        HalfwayConfig(normalize=NormalizeConfig())
