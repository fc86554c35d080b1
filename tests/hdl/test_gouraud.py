import numpy as np
import pytest

from phongfx.config import GouraudConfig
from phongfx.core.registry import get_block
from phongfx.hdl.gouraud import Gouraud
from phongfx.sim.harness import check


def test_latency_and_ports():
    dut = Gouraud(GouraudConfig())
    assert dut.latency == 1
    assert len(dut.i.payload.as_value()) == 1 + 32 + 34
    assert len(dut.o.payload.as_value()) == 32 + 8 + 1  # and the overflow flag


def test_constructor_wants_its_config():
    with pytest.raises(TypeError, match=r"^config must be a GouraudConfig, not "):
        Gouraud(object())


@pytest.mark.parametrize("bubbles", [0.0, 0.25])
def test_harness(backend, bubbles):
    check(get_block("gouraud"), backend=backend, bubbles=bubbles, count=300, seed=7).raise_on_mismatch()


def test_harness_steps_before_init():
    block = get_block("gouraud")
    raw = block.stimulus(count=50, seed=2)
    raw = {name: np.concatenate([value[1:4], value]) for name, value in raw.items()}
    raw["init"][:3] = 0
    check(block, raw, bubbles=0.3, seed=2).raise_on_mismatch()


@pytest.mark.parametrize("changes", [dict(p="S1.20", dp="S3.12"), dict(p="S1.6", dp="S3.4", out="S1.4")])
def test_harness_other_formats(changes):
    check(get_block("gouraud", **changes), count=300, seed=1).raise_on_mismatch()
