import pytest

from phongfx.config import LirpConfig
from phongfx.core.registry import get_block
from phongfx.hdl.lirp import Lirp
from phongfx.sim.harness import check


def test_latency_and_ports():
    dut = Lirp(LirpConfig())
    assert dut.latency == 2
    assert len(dut.i.payload.as_value()) == 2 * 3 * 12 + 11
    assert len(dut.o.payload.as_value()) == 3 * 12 + 1  # and the overflow flag


def test_constructor_wants_its_config():
    with pytest.raises(TypeError, match=r"^config must be a LirpConfig, not "):
        Lirp(object())


@pytest.mark.parametrize("bubbles", [0.0, 0.3])
def test_harness(backend, bubbles):
    check(get_block("lirp"), backend=backend, bubbles=bubbles, count=300, seed=7).raise_on_mismatch()


def test_harness_other_formats():
    block = get_block("lirp", vec="S1.7", a="1.5", out="S1.6", rounding="round_half_even")
    check(block, count=300, seed=1).raise_on_mismatch()
