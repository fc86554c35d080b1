"""The shininess operand of Lyon's Figures 7c (``n``) and 8 (``m``), a port or a constant
(golden/shininess.py), in both blocks' golden models."""

import numpy as np
import pytest

from phongfx.config import DifferenceConfig, RootConfig
from phongfx.core.registry import get_block
from phongfx.golden.difference import difference
from phongfx.golden.fixed import Fixed
from phongfx.golden.root import root

#: block -> (config class, golden function, its output)
BLOCKS = {"difference": (DifferenceConfig, difference, "x2"), "root": (RootConfig, root, "spec")}


def _varied_x2(x2, count):
    # not all zero or saturated
    return np.count_nonzero(x2.raw) > count // 2 and np.count_nonzero(x2.raw < x2.fmt.max_raw) > 100


def _varied_spec(spec, count):
    # both sides of the peak edge
    return np.count_nonzero(spec.raw) > 50 and np.count_nonzero(spec.raw == 0) > 50


@pytest.mark.parametrize("block, value, varied", [
    *(("difference", n, _varied_x2) for n in (1, 16, 77, 8000)),
    *(("root", m, _varied_spec) for m in (1, 4, 7, 63)),
])
def test_a_constant_gives_the_codes_of_the_value_on_the_port(block, value, varied):
    kind, golden, out = BLOCKS[block]
    raw = get_block(block).stimulus(count=300, seed=5)
    config = kind(**{f"{kind.SHININESS}_const": value})
    r, l = Fixed(raw["r"], config.vec), Fixed(raw["l"], config.vec)
    fixed = golden(config, r, l)[out]
    fed = golden(kind(), r, l, Fixed(np.full(len(r), value), config.fmt(kind.SHININESS)))[out]
    assert fixed.fmt == fed.fmt
    assert np.array_equal(fixed.raw, fed.raw)
    assert varied(fixed, len(r))


@pytest.mark.parametrize("block, value, fmt", [("difference", 16, "13.0"), ("root", 4, "6.0")])
def test_a_constant_has_no_port_and_refuses_one(block, value, fmt):
    kind, golden, _ = BLOCKS[block]
    port = kind.SHININESS
    config = kind(**{f"{port}_const": value})
    assert set(config.inputs) == {"r", "l"}
    assert set(kind().inputs) == {"r", "l", port}
    r = Fixed.from_float([[1.0, 0, 0]], "S1.10")
    with pytest.raises(ValueError, match=rf"^{port} must not be given: {port}_const = {value} fixes it$"):
        golden(config, r, r, Fixed([value], fmt))
    with pytest.raises(ValueError, match=rf"^{port} must be given: {port}_const = 0 makes it an input$"):
        golden(kind(), r, r)
