import numpy as np
import pytest

from phongfx.config import EulerConfig
from phongfx.core.registry import get_block
from phongfx.hdl.euler import Euler
from phongfx.sim.harness import check
from phongfx.sim.stimulus.euler import span


def test_latency_and_ports():
    dut = Euler(EulerConfig())
    assert dut.latency == 1
    # init 1, p0 32, t0 34, ds 34; p 32, level 8
    assert len(dut.i.payload.as_value()) == 1 + 32 + 34 + 34
    assert len(dut.o.payload.as_value()) == 32 + 8 + 1  # and the overflow flag


def test_constructor_wants_its_config():
    with pytest.raises(TypeError, match=r"^config must be a EulerConfig, not "):
        Euler(object())


@pytest.mark.parametrize("bubbles", [0.0, 0.25])
def test_harness(backend, bubbles):
    # spans of 1, 2 and 2048 pixels, init back to back, every register at its extremes
    # (wrapping), random spans; idle cycles must not step the registers
    check(get_block("euler"), backend=backend, bubbles=bubbles, count=300, seed=7).raise_on_mismatch()


def test_harness_steps_before_init():
    # from reset, pixels before any init output p = 0
    block = get_block("euler")
    raw = block.stimulus(count=50, seed=2)
    raw = {name: np.concatenate([value[1:4], value]) for name, value in raw.items()}
    raw["init"][:3] = 0
    check(block, raw, bubbles=0.3, seed=2).raise_on_mismatch()


def test_harness_one_pixel_spans_back_to_back():
    block = get_block("euler")
    g = np.random.default_rng(5)
    parts = [span(block.config, 1, g) for _ in range(200)]
    raw = {name: np.concatenate([p[name] for p in parts]) for name in parts[0]}
    check(block, raw, bubbles=0.0, seed=5).raise_on_mismatch()


@pytest.mark.parametrize("changes", [
    # fraction bits growing along the chain, narrow wrapping registers, a signed level
    dict(p="S1.20", t="S2.16", ds="S3.12"),
    dict(p="S1.6", t="S1.6", ds="S0.6", out="S1.4"),
])
def test_harness_other_formats(changes):
    check(get_block("euler", **changes), count=300, seed=1).raise_on_mismatch()
