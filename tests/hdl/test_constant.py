"""Multiplying by a constant (hdl/constant.py): canonical signed digits, and the constant
shininess of Lyon's Figures 7c (``n_const``) and 8 (``m_const``) in both blocks' hardware."""

import pytest
from amaranth.back import rtlil

from phongfx.config import DifferenceConfig, RootConfig
from phongfx.core.registry import get_block
from phongfx.hdl.constant import signed_digits
from phongfx.hdl.difference import Difference
from phongfx.hdl.root import Root
from phongfx.sim.harness import check

#: block -> (config class, component, the multipliers a constant removes at a depth)
BLOCKS = {"difference": (DifferenceConfig, Difference, lambda depth: 1 + (depth >= 3)),  # n·D·D, split at 3
          "root": (RootConfig, Root, lambda depth: 3)}  # the three m × |D_i|

#: the constant-shininess checks run on the simulator and the fast Verilator back end
FAST = ["amaranth", pytest.param("verilator-fast", marks=pytest.mark.needs_verilator)]


def constant(block, value, **changes):
    kind = BLOCKS[block][0]
    return {f"{kind.SHININESS}_const": value, **changes}


@pytest.mark.parametrize("constant, digits", [
    (1, [(1, 0)]), (16, [(1, 4)]), (7, [(-1, 0), (1, 3)]), (77, [(1, 0), (-1, 2), (1, 4), (1, 6)]),
    (8000, [(1, 6), (-1, 8), (1, 13)]),
])
def test_signed_digits(constant, digits):
    assert signed_digits(constant) == digits


def test_signed_digits_are_canonical():
    for value in range(1, 4096):
        digits = signed_digits(value)
        assert sum(sign << shift for sign, shift in digits) == value
        assert all(b[1] - a[1] >= 2 for a, b in zip(digits, digits[1:]))  # none adjacent


@pytest.mark.parametrize("backend", FAST)
@pytest.mark.parametrize("block, value", [("difference", 1), ("difference", 16), ("difference", 8000),
                                          ("root", 1), ("root", 4), ("root", 63)])
def test_harness_constant(backend, block, value):
    check(get_block(block, **constant(block, value)), backend=backend, bubbles=0.2, count=300,
          seed=value).raise_on_mismatch()


@pytest.mark.parametrize("depth", range(4))
@pytest.mark.parametrize("block, value", [("difference", 77), ("root", 5)])
def test_a_constant_drops_the_port_not_a_cycle(block, value, depth):
    kind, component, _ = BLOCKS[block]
    fixed = component(kind(**constant(block, value, pipeline=depth)))
    assert fixed.latency == component(kind(pipeline=depth)).latency
    assert len(fixed.i.payload.as_value()) == 2 * 3 * 12
    # difference at depth 3 splits n·D·D into partial products: the constant goes through them too
    check(get_block(block, **constant(block, value, pipeline=depth)), count=100, seed=depth).raise_on_mismatch()


def multipliers(component):
    """``$mul`` cells of the elaborated design (sub-blocks included)."""
    return rtlil.convert(component).count("cell $mul ")


@pytest.mark.parametrize("depth", [0, 3])
@pytest.mark.parametrize("block, values", [("difference", (16, 77, 8000)), ("root", (4, 45, 63))])
def test_a_constant_leaves_no_shininess_multiplier(block, values, depth):
    # the shininess multipliers become shifts and adds; difference keeps its three squarers
    kind, component, removed = BLOCKS[block]
    fed = multipliers(component(kind(pipeline=depth)))
    if block == "difference":
        assert fed == 4 + (depth >= 3)
    for value in values:
        assert fed - multipliers(component(kind(**constant(block, value, pipeline=depth)))) == removed(depth)
