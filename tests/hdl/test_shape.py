import pytest

from phongfx.config import ShapeConfig
from phongfx.config.shape import K_MAX
from phongfx.core.registry import get_block
from phongfx.hdl.shape import Shape
from phongfx.sim.harness import check
from phongfx.sim.stimulus.shape import stimulus


@pytest.mark.parametrize("k", range(K_MAX + 1))
def test_latency_and_ports(k):
    dut = Shape(ShapeConfig(k=k))
    assert dut.latency == 1 + k
    assert len(dut.i.payload.as_value()) == 25
    assert len(dut.o.payload.as_value()) == 16 + 1  # and the overflow flag


def test_constructor_wants_its_config():
    with pytest.raises(TypeError, match=r"^config must be a ShapeConfig, not "):
        Shape(object())


@pytest.mark.parametrize("bubbles", [0.0, 0.25])
def test_harness(backend, bubbles):
    # the default vectors hold all 32768 codes with 2x < 8 (k = 2): exhaustive
    check(get_block("shape"), backend=backend, bubbles=bubbles, count=300, seed=7).raise_on_mismatch()


@pytest.mark.parametrize("k", [*range(5), K_MAX])
def test_harness_every_k(k):
    block = get_block("shape", k=k)
    inputs = stimulus(block.config, count=200, seed=k, limit=1024)
    check(block, inputs, bubbles=0.1, seed=k).raise_on_mismatch()


@pytest.mark.parametrize("changes", [
    # exhaustive (2^12 and 2^10 codes); 1 - u rounded from 12 and 10 fraction bits
    dict(x2="8.8", k=3, t="1.10", rounding="round_half_even"),
    dict(x2="6.8", k=1, t="1.8", rounding="truncate"),
])
def test_harness_other_formats(changes):
    check(get_block("shape", **changes), count=300, seed=1).raise_on_mismatch()
