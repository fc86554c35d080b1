import pytest
from amaranth.back import rtlil

from phongfx.config import DifferenceConfig
from phongfx.core.registry import get_block
from phongfx.hdl.difference import Difference, signed_digits
from phongfx.sim.harness import check


def test_latency_and_ports():
    dut = Difference(DifferenceConfig())
    assert dut.latency == 4
    assert len(dut.i.payload.as_value()) == 2 * 3 * 12 + 13
    assert len(dut.o.payload.as_value()) == 25 + 1  # and the overflow flag


def test_constructor_wants_its_config():
    with pytest.raises(TypeError, match=r"^config must be a DifferenceConfig, not "):
        Difference(object())


@pytest.mark.parametrize("bubbles", [0.0, 0.3])
def test_harness(backend, bubbles):
    check(get_block("difference"), backend=backend, bubbles=bubbles, count=300, seed=7).raise_on_mismatch()


@pytest.mark.parametrize("changes", [
    # D keeps ±2 exactly but rounds to 7 fraction bits; D·D rounds and saturates at 8
    dict(vec="S1.8", d="S2.7", dd="3.12", n="10.0", n_max=1000, x2="11.8", rounding="round_half_even"),
    dict(n_max=255, x2="6.12", rounding="truncate"),
])
def test_harness_other_formats(changes):
    check(get_block("difference", **changes), count=300, seed=1).raise_on_mismatch()


#: the constant-shininess checks run on the simulator and the fast Verilator back end
FAST = ["amaranth", pytest.param("verilator-fast", marks=pytest.mark.needs_verilator)]


@pytest.mark.parametrize("backend", FAST)
@pytest.mark.parametrize("n", [1, 16, 8000])
def test_harness_constant_n(backend, n):
    check(get_block("difference", n_const=n), backend=backend, bubbles=0.2, count=300,
          seed=n).raise_on_mismatch()


@pytest.mark.parametrize("depth", range(4))
def test_constant_n_drops_the_port_not_a_cycle(depth):
    fixed = Difference(DifferenceConfig(n_const=77, pipeline=depth))
    assert fixed.latency == Difference(DifferenceConfig(pipeline=depth)).latency
    assert len(fixed.i.payload.as_value()) == 2 * 3 * 12
    # depth 3 splits n·D·D into partial products: the constant goes through them too
    check(get_block("difference", n_const=77, pipeline=depth), count=100, seed=depth).raise_on_mismatch()


def multipliers(component):
    """``$mul`` cells of the elaborated design (sub-blocks included)."""
    return rtlil.convert(component).count("cell $mul ")


@pytest.mark.parametrize("depth", [0, 3])
def test_constant_n_leaves_only_the_squarers(depth):
    # the n·D·D multiplier (two partial products at depth 3) becomes shifts and adds
    assert multipliers(Difference(DifferenceConfig(pipeline=depth))) == 4 + (depth >= 3)
    for n in (16, 77, 8000):
        assert multipliers(Difference(DifferenceConfig(n_const=n, pipeline=depth))) == 3


@pytest.mark.parametrize("constant, digits", [
    (1, [(1, 0)]), (16, [(1, 4)]), (7, [(-1, 0), (1, 3)]), (77, [(1, 0), (-1, 2), (1, 4), (1, 6)]),
    (8000, [(1, 6), (-1, 8), (1, 13)]),
])
def test_signed_digits(constant, digits):
    assert signed_digits(constant) == digits


def test_signed_digits_are_canonical():
    for constant in range(1, 4096):
        digits = signed_digits(constant)
        assert sum(sign << shift for sign, shift in digits) == constant
        assert all(b[1] - a[1] >= 2 for a, b in zip(digits, digits[1:]))  # none adjacent
