import pytest

from phongfx.config import DiffuseConfig
from phongfx.core.registry import get_block
from phongfx.hdl.diffuse import Diffuse
from phongfx.sim.harness import check


def test_latency_and_ports():
    dut = Diffuse(DiffuseConfig())
    assert dut.latency == 2
    assert len(dut.i.payload.as_value()) == 2 * 3 * 12
    assert len(dut.o.payload.as_value()) == 11 + 1  # and the overflow flag


def test_constructor_wants_its_config():
    with pytest.raises(TypeError, match=r"^config must be a DiffuseConfig, not "):
        Diffuse(object())
    with pytest.raises(TypeError, match=r"^config must be a DiffuseConfig, not ReflectConfig\("):
        Diffuse(get_block("reflect").config)


@pytest.mark.parametrize("bubbles", [0.0, 0.3])
def test_harness(backend, bubbles):
    check(get_block("diffuse"), backend=backend, bubbles=bubbles, count=300, seed=7).raise_on_mismatch()


@pytest.mark.parametrize("changes", [
    dict(vec="S1.7", out="1.7", rounding="truncate"),
    dict(vec="S1.10", out="2.8", rounding="round_half_even"),
])
def test_harness_other_formats(changes):
    check(get_block("diffuse", **changes), count=300, seed=1).raise_on_mismatch()
