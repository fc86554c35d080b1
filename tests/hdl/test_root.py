import pytest
from amaranth.back import rtlil

from phongfx.config import RootConfig
from phongfx.core.registry import get_block
from phongfx.hdl.block import unbuilt
from phongfx.hdl.root import Root
from phongfx.hdl.shape import Shape
from phongfx.sim.harness import check


@pytest.mark.parametrize("k", range(5))
def test_latency_and_ports(k):
    dut = Root(RootConfig(k=k))
    assert dut.latency == 4 + k
    assert len(dut.i.payload.as_value()) == 2 * 3 * 12 + 6
    assert len(dut.o.payload.as_value()) == 16 + 1  # and the overflow flag


def test_shape_is_the_figure_7d_component():
    config = RootConfig(k=3, t="1.12")
    dut = Root(config)
    assert dut.latency == 3 + unbuilt(Shape(config.shape)).latency
    # elaborated as a submodule of its own, not inlined
    assert "cell \\top.shape \\shape\n" in rtlil.convert(dut, emit_src=False)


def test_constructor_wants_its_config():
    with pytest.raises(TypeError, match=r"^config must be a RootConfig, not "):
        Root(object())


@pytest.mark.parametrize("bubbles", [0.0, 0.25])
def test_harness(backend, bubbles):
    check(get_block("root"), backend=backend, bubbles=bubbles, count=300, seed=7).raise_on_mismatch()


@pytest.mark.parametrize("k", [0, 2, 3, 4])
def test_harness_every_k(k):
    check(get_block("root", k=k), bubbles=0.1, count=200, seed=k).raise_on_mismatch()


@pytest.mark.parametrize("changes", [
    # D rounded from 12 to 11 fraction bits; 5×11 products, 8×8 squarers, 1 - u from 16 bits
    dict(vec="S1.12", d="S1.11", m="5.0", m_max=31, frac="0.8", k=2, t="1.12",
         rounding="round_half_even"),
    # D keeps ±2 (|D| up to 4) with 9 fraction bits; frac asks for 12 bits of u, one more
    # than u holds (9 + s = 11), so its quantize appends a zero
    dict(d="S2.9", m="7.0", m_max=100, frac="0.12", k=3, rounding="truncate"),
])
def test_harness_other_formats(changes):
    check(get_block("root", **changes), count=300, seed=1).raise_on_mismatch()
