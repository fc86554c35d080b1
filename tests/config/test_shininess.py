"""The constant shininess of Lyon's Figure 7c (``n_const``) and Figure 8 (``m_const``): one
mixin, ConstantShininess, for both blocks."""

import pytest

from phongfx.config import DifferenceConfig, RootConfig, fig7_config, fig8_config
from phongfx.config.base import ConstantShininess

#: block config -> (port, default largest value)
BLOCKS = {DifferenceConfig: ("n", 8000), RootConfig: ("m", 63)}


@pytest.mark.parametrize("kind", BLOCKS)
def test_both_blocks_take_the_mixin(kind):
    port, top = BLOCKS[kind]
    config = kind()
    assert isinstance(config, ConstantShininess) and config.SHININESS == port
    assert (config.shininess_max, config.shininess_const, config.shininess_range) == (top, 0, (1, top))
    fixed = kind(**{f"{port}_const": 7})
    assert (fixed.shininess_const, fixed.shininess_range) == (7, (7, 7))


@pytest.mark.parametrize("kind", BLOCKS)
def test_constant_shininess_drops_its_port(kind):
    port, _ = BLOCKS[kind]
    assert list(kind().inputs) == ["r", "l", port]
    assert list(kind(**{f"{port}_const": 4}).inputs) == ["r", "l"]


@pytest.mark.parametrize("kind, changes, message", [
    (DifferenceConfig, dict(n_const=-1), r"^n_const must be an integer in 0\.\.8000, not -1$"),
    (DifferenceConfig, dict(n_const=8001), r"^n_const must be an integer in 0\.\.8000, not 8001$"),
    (DifferenceConfig, dict(n_max=100, n_const=101), r"^n_const must be an integer in 0\.\.100, not 101$"),
    (DifferenceConfig, dict(n_const=16.0), r"^n_const must be an integer in 0\.\.8000, not 16\.0$"),
    (DifferenceConfig, dict(n_const=True), r"^n_const must be an integer in 0\.\.8000, not True$"),
    (DifferenceConfig, dict(n_max=9000), r"^n_max must be an integer in 1\.\.8191, not 9000$"),
    (DifferenceConfig, dict(n="13.2"), r"^n must be an integer format \(m = 0\), not 13\.2$"),
    (DifferenceConfig, dict(n="S13.0"), r"^n must be an unsigned format \(n\.m\), not S13\.0$"),
    (RootConfig, dict(m_const=-1), r"^m_const must be an integer in 0\.\.63, not -1$"),
    (RootConfig, dict(m_const=64), r"^m_const must be an integer in 0\.\.63, not 64$"),
    (RootConfig, dict(m_max=10, m_const=11), r"^m_const must be an integer in 0\.\.10, not 11$"),
    (RootConfig, dict(m_const="4"), r"^m_const must be an integer in 0\.\.63, not '4'$"),
    (RootConfig, dict(m_max=64), r"^m_max must be an integer in 1\.\.63, not 64$"),
    (RootConfig, dict(m="6.2"), r"^m must be an integer format \(m = 0\), not 6\.2$"),
])
def test_errors_name_the_field(kind, changes, message):
    with pytest.raises(ValueError, match=message):
        kind(**changes)


@pytest.mark.parametrize("kind", BLOCKS)
def test_with_shininess_narrows_the_port_or_fixes_it(kind):
    port, _ = BLOCKS[kind]
    narrowed = kind().with_shininess(40)
    assert (getattr(narrowed, port), narrowed.shininess_max, narrowed.shininess_const) == ("6.0", 40, 0)
    fixed = kind().with_shininess(40, 9)
    assert (fixed.shininess_max, fixed.shininess_const, list(fixed.inputs)) == (40, 9, ["r", "l"])


@pytest.mark.parametrize("n_hi, n_const, m", [(64, 0, (8, 0)), (64, 16, (8, 4)), (50, 20, (8, 4)),
                                               (50, 21, (8, 5)), (1, 1, (1, 1))])
def test_fit_of_both_figures(n_hi, n_const, m):
    fig7 = fig7_config().unit.fit(fig7_config(), n_hi, n_const).difference
    assert (fig7.n, fig7.n_max, fig7.n_const) == (f"{n_hi.bit_length()}.0", n_hi, n_const)
    fig8 = fig8_config().unit.fit(fig8_config(), n_hi, n_const).root
    assert (fig8.m_max, fig8.m_const) == m  # m = ⌈√n_hi⌉, m_const = √n_const rounded
