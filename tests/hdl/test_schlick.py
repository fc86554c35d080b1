import pytest

from phongfx.config import SchlickConfig
from phongfx.core.registry import get_block
from phongfx.hdl.schlick import Schlick
from phongfx.sim.harness import check
from phongfx.sim.stimulus.schlick import stimulus


@pytest.mark.parametrize("changes, latency, widths", [
    ({}, 17, (16 + 13, 16)),
    (dict(rounding="round_half_up"), 18, (16 + 13, 16)),
    (dict(t="1.10", n="6.0", n_max=63, out="1.12"), 14, (11 + 6, 13)),
])
def test_latency_and_ports(changes, latency, widths):
    dut = Schlick(SchlickConfig(**changes))
    assert dut.latency == latency == 1 + dut.config.quotient_bits
    assert (len(dut.i.payload.as_value()), len(dut.o.payload.as_value()) - 1) == widths  # - the overflow flag


def test_constructor_wants_its_config():
    with pytest.raises(TypeError, match=r"^config must be a SchlickConfig, not "):
        Schlick(object())


@pytest.mark.parametrize("bubbles", [0.0, 0.25])
def test_harness(backend, bubbles):
    # the default vectors hold every t code of 1.15 for n = 6 and n = 8000: exhaustive
    check(get_block("schlick"), backend=backend, bubbles=bubbles, count=300, seed=7).raise_on_mismatch()


@pytest.mark.parametrize("changes", [
    dict(rounding="round_half_up"),
    # every t code for n = 6 and 63; t and out of different scales, an extra quotient bit
    dict(t="1.10", n="6.0", n_max=63, out="1.12", rounding="round_half_up"),
    dict(t="1.12", n="10.0", n_max=1023, out="2.10"),
    # n = 1 only: the divisor (1.12) is narrower than t (3.12), whose integer bits stay 0
    dict(t="3.12", n="1.0", n_max=1),
])
def test_harness_other_formats(changes):
    block = get_block("schlick", **changes)
    inputs = stimulus(block.config, count=500, seed=2, limit=4096)
    check(block, inputs, bubbles=0.1, seed=2).raise_on_mismatch()
