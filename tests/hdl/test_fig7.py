import pytest

from phongfx.blocks import get_block
from phongfx.config import Fig7Config, ShapeConfig
from phongfx.hdl.fig7 import Fig7
from phongfx.sim.harness import check


def test_latency_is_the_sum_of_its_blocks():
    names = ("lirp", "normalize", "reflect", "difference", "shape")
    assert get_block("fig7").latency == sum(get_block(name).latency for name in names)
    assert get_block("fig7", shape=ShapeConfig(k=4)).latency == get_block("fig7").latency + 2


def test_one_light_has_one_specular_unit():
    dut = Fig7(Fig7Config(lights=1))
    assert set(dut.config.outputs) == {"spec0", "diff0"}
    assert len(dut._difference) == len(dut._shape) == len(dut._diffuse) == 1
    dut._MustUse__silence = True


def test_harness(backend):
    count = 150 if backend == "amaranth" else 2000
    check(get_block("fig7"), backend=backend, bubbles=0.2, count=count, seed=11).raise_on_mismatch()


def test_harness_back_to_back_k1_one_light():
    block = get_block("fig7", shape=ShapeConfig(k=1), lights=1)
    check(block, bubbles=0.0, count=100, seed=2).raise_on_mismatch()
