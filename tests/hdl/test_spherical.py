import numpy as np
import pytest

from phongfx.config import SphericalConfig
from phongfx.core.registry import get_block
from phongfx.hdl.spherical import Spherical
from phongfx.sim.harness import check
from phongfx.sim.stimulus.spherical import span


def test_latency_and_ports():
    dut = Spherical(SphericalConfig())
    assert dut.latency == 3
    # init 1, b s bd sd 4 × 12, c 12, cd 3 × 12; spec and diff 4 × 12
    assert len(dut.i.payload.as_value()) == 1 + 4 * 12 + 12 + 36
    assert len(dut.o.payload.as_value()) == 48 + 1  # and the overflow flag


def test_constructor_wants_its_config():
    with pytest.raises(TypeError, match=r"^config must be a SphericalConfig, not "):
        Spherical(object())


@pytest.mark.parametrize("bubbles", [0.0, 0.25])
def test_harness(backend, bubbles):
    # spans of 1, 2 and 2048 pixels, init back to back, γ near 0 and π, n = 1 and 500,
    # the ROM address wrapping both ways; idle cycles must not step the interpolators
    check(get_block("spherical"), backend=backend, bubbles=bubbles, count=300, seed=7).raise_on_mismatch()


def test_harness_steps_before_init():
    # from reset, pixels before any init read θ = 0 and C = 0
    block = get_block("spherical")
    raw = block.stimulus(count=50, seed=2)
    raw = {name: np.concatenate([value[1:4], value]) for name, value in raw.items()}
    raw["init"][:3] = 0
    check(block, raw, bubbles=0.3, seed=2).raise_on_mismatch()


def test_harness_one_pixel_spans_back_to_back():
    block = get_block("spherical")
    g = np.random.default_rng(5)
    parts = [span(block.config, 1, g, b=int(b), s=int(s), c=4095)
             for b, s in g.integers(-2048, 2048, size=(200, 2))]
    raw = {name: np.concatenate([p[name] for p in parts]) for name in parts[0]}
    check(block, raw, bubbles=0.0, seed=5).raise_on_mismatch()


@pytest.mark.parametrize("changes", [
    # the paper's halo case (4 bits), and a wide ROM; an out narrower than c saturates
    dict(theta="S0.7", addr_bits=4, rom="0.4", c="1.8", out="0.6"),
    dict(theta="S0.15", addr_bits=10, rom="0.10", c="1.15", out="1.15", rounding="round_half_even"),
])
def test_harness_other_formats(changes):
    check(get_block("spherical", **changes), count=300, seed=1).raise_on_mismatch()
