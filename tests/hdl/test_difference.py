import pytest

from phongfx.config import DifferenceConfig
from phongfx.core.registry import get_block
from phongfx.hdl.difference import Difference
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
