import pytest

from phongfx.config import ReflectConfig
from phongfx.core.registry import get_block
from phongfx.hdl.reflect import Reflect
from phongfx.sim.harness import check


def test_latency_and_ports():
    dut = Reflect(ReflectConfig())
    assert dut.latency == 4
    assert len(dut.i.payload.as_value()) == 2 * 3 * 12
    assert len(dut.o.payload.as_value()) == 3 * 12 + 1  # and the overflow flag


def test_constructor_wants_its_config():
    with pytest.raises(TypeError, match=r"^config must be a ReflectConfig, not "):
        Reflect(object())
    with pytest.raises(TypeError, match=r"^config must be a ReflectConfig, not DiffuseConfig\("):
        Reflect(get_block("diffuse").config)


@pytest.mark.parametrize("bubbles", [0.0, 0.3])
def test_harness(backend, bubbles):
    check(get_block("reflect"), backend=backend, bubbles=bubbles, count=300, seed=7).raise_on_mismatch()


@pytest.mark.parametrize("changes", [
    dict(vec="S1.7", dot="S1.9", out="S1.7", rounding="truncate"),
    dict(vec="S1.10", dot="S1.10", out="S2.8", rounding="round_half_even"),
])
def test_harness_other_formats(changes):
    check(get_block("reflect", **changes), count=300, seed=1).raise_on_mismatch()
