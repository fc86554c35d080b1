import pytest

from phongfx.config import BlinnConfig
from phongfx.core.registry import get_block
from phongfx.hdl.blinn import LATENCY, Blinn
from phongfx.sim.harness import check
from phongfx.sim.stimulus.blinn import stimulus

SMALL = dict(vec="S1.10", n="6.0", n_max=63, m="0.12", rsqrt_addr=6, y="1.12", nr="3.14",
             dot="S2.12", t="1.10", log_addr=5, log="0.14", exp_addr=6, exp="2.13", out="1.12")


@pytest.mark.parametrize("changes, widths", [
    ({}, (9 * 17 + 13, 2 * 16)),
    (SMALL, (9 * 12 + 6, 2 * 13)),
])
def test_latency_and_ports(changes, widths):
    dut = Blinn(BlinnConfig(**changes))
    assert dut.latency == LATENCY == 14
    assert (len(dut.i.payload.as_value()), len(dut.o.payload.as_value()) - 1) == widths  # - the overflow flag


def test_constructor_wants_its_config():
    with pytest.raises(TypeError, match=r"^config must be a BlinnConfig, not "):
        Blinn(object())


@pytest.mark.parametrize("bubbles", [0.0, 0.25])
def test_harness(backend, bubbles):
    # the directed set (axes, zero and shortest N, t = 1, backfacing H, every edge n) and
    # random highlights, spread and junk codes
    check(get_block("blinn"), backend=backend, bubbles=bubbles, count=300, seed=7).raise_on_mismatch()


@pytest.mark.parametrize("changes", [
    dict(rounding="truncate"),
    dict(rounding="round_half_even", t="1.16", out="2.16"),
    # narrow formats everywhere: an 11-bit t, 64-word tables, n up to 63
    SMALL,
])
def test_harness_other_formats(changes):
    block = get_block("blinn", **changes)
    inputs = stimulus(block.config, count=400, seed=2)
    check(block, inputs, bubbles=0.1, seed=2).raise_on_mismatch()
