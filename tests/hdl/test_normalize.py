import pytest

from phongfx.config import LirpConfig, NormalizeConfig
from phongfx.core.registry import get_block
from phongfx.hdl.normalize import Normalize
from phongfx.sim.harness import check


@pytest.mark.parametrize("order", [1, 2])
def test_latency_and_ports(order):
    dut = Normalize(NormalizeConfig(order=order))
    assert dut.latency == 4  # the same for both orders: drop-in interchangeable
    assert len(dut.i.payload.as_value()) == 3 * 12
    assert len(dut.o.payload.as_value()) == 3 * 12 + 1  # and the overflow flag


def test_constructor_wants_its_config():
    with pytest.raises(TypeError, match=r"^config must be a NormalizeConfig, not LirpConfig\("):
        Normalize(LirpConfig())


# each run drives ~10k vectors (directed and swept codes come first, whatever the count)
@pytest.mark.parametrize("bubbles", [0.0, 0.3])
def test_harness(backend, bubbles):
    check(get_block("normalize"), backend=backend, bubbles=bubbles, count=200,
          seed=7).raise_on_mismatch()


def test_harness_first_order(backend):
    check(get_block("normalize", order=1), backend=backend, bubbles=0.2, count=200,
          seed=11).raise_on_mismatch()


@pytest.mark.parametrize("changes", [
    dict(vec="S1.7", z="1.9", y2="1.9", g="1.9", out="S1.7", rounding="round_half_even"),
    # a 2-bit z: y² may overflow, so it saturates instead of declaring "error"
    dict(vec="S1.8", z="2.10", y2="1.10", g="2.11", out="S2.8", rounding="truncate"),
    dict(order=1, vec="S1.7", z="1.10", g="1.10", out="S1.7", rounding="truncate"),
])
def test_harness_other_formats(changes):
    check(get_block("normalize", **changes), count=200, seed=1).raise_on_mismatch()
