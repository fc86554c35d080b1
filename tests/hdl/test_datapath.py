import pytest
from amaranth.hdl import Fragment

from phongfx.config import (DatapathConfig, DifferenceConfig, NormalizeConfig, RootConfig, ShapeConfig,
                            fig8_config)
from phongfx.core.registry import get_block
from phongfx.hdl.datapath import Datapath
from phongfx.sim.harness import check


def test_latency_is_the_sum_of_its_blocks():
    front = get_block("lirp").latency + get_block("normalize").latency
    fig7 = ("reflect", "difference", "shape")
    assert get_block("fig7").latency == front + sum(get_block(name).latency for name in fig7)
    assert get_block("fig7", shape=ShapeConfig(k=4)).latency == get_block("fig7").latency + 2
    assert get_block("fig8").latency == front + get_block("reflect").latency + get_block("root").latency
    halfway = ("halfway", "difference", "shape")
    assert get_block("halfway_datapath").latency == front + sum(get_block(n).latency for n in halfway)


def _instances(config):
    """Sub-block instance names of the elaborated design."""
    fragment = Fragment.get(Datapath(config), None)
    return sorted(name.rstrip("0123456789") for _, name, _ in fragment.subfragments)


def test_only_the_needed_blocks_are_built():
    # lights and viewer at infinity: one LIRP and one normalizer (for N), nothing for L or V
    infinite = _instances(DatapathConfig(lights=2))
    assert infinite.count("lirp") == 1 and infinite.count("normalize") == 1
    assert infinite.count("difference") == infinite.count("shape") == infinite.count("diffuse") == 2
    assert "root" not in infinite and "halfway" not in infinite
    local = _instances(DatapathConfig(lights=2, local_lights=True, local_viewer=True))
    assert local.count("lirp") == 4 and local.count("normalize") == 4
    # a point light beside a directional one: only the point light gets an L interpolator
    mixed = _instances(DatapathConfig(lights=2, local_lights=(False, True)))
    assert mixed.count("lirp") == 2 and mixed.count("normalize") == 2
    assert set(DatapathConfig(lights=2, local_lights=(False, True)).inputs) >= {"l0", "l1_0", "l1_1"}
    viewer = _instances(fig8_config(lights=1, local_viewer=True))
    assert viewer.count("lirp") == 2 and viewer.count("root") == 1 and "shape" not in viewer


def test_one_light_has_one_specular_unit():
    assert set(Datapath(DatapathConfig(lights=1)).config.outputs) == {"spec0", "diff0"}


@pytest.mark.parametrize("name", ["fig7", "fig8", "halfway_datapath"])
def test_harness(backend, name):
    count = 100 if backend == "amaranth" else 1500
    check(get_block(name), backend=backend, bubbles=0.2, count=count, seed=11).raise_on_mismatch()


@pytest.mark.parametrize("changes", [
    dict(local_lights=True, local_viewer=True, lights=1),
    dict(local_lights=True, lights=2, direction_normalize=NormalizeConfig(order=1)),
    dict(shape=ShapeConfig(k=1), lights=1),
    dict(local_lights=(True, False), lights=2),
])
def test_harness_local_and_other_configs(backend, changes):
    count = 80 if backend == "amaranth" else 1000
    check(get_block("fig7", **changes), backend=backend, bubbles=0.1, count=count, seed=3).raise_on_mismatch()


def test_harness_fig8_local_viewer():
    check(get_block("fig8", local_viewer=True, lights=1), bubbles=0.0, count=80, seed=4).raise_on_mismatch()


#: the constant-shininess checks run on the simulator and the fast Verilator back end
FAST = ["amaranth", pytest.param("verilator-fast", marks=pytest.mark.needs_verilator)]


@pytest.mark.parametrize("backend", FAST)
@pytest.mark.parametrize("name, changes", [
    ("fig7", dict(difference=DifferenceConfig(n_const=16))),
    ("fig8", dict(root=RootConfig(m_const=4))),
    # the halfway unit's difference block multiplies by n·2^2: n_const 64 is n = 16
    ("halfway_datapath", dict(difference=DifferenceConfig(vec="S2.10", n="15.0", n_max=32000,
                                                          n_const=64))),
])
def test_harness_constant_shininess(backend, name, changes):
    block = get_block(name, **changes)
    assert block.config.shininess is None and block.latency == get_block(name).latency
    count = 100 if backend == "amaranth" else 1000
    check(block, backend=backend, bubbles=0.2, count=count, seed=13).raise_on_mismatch()


def test_constant_shininess_drops_only_the_port():
    for name, changes, width in (("fig7", dict(difference=DifferenceConfig(n_const=16)), 13),
                                 ("fig8", dict(root=RootConfig(m_const=4)), 6)):
        fixed, fed = Datapath(get_block(name, **changes).config), Datapath(get_block(name).config)
        assert len(fed.i.payload.as_value()) - len(fixed.i.payload.as_value()) == width
        assert fixed.latency == fed.latency
        # the same sub-blocks: the constant lives inside the unit
        assert _instances(fixed.config) == _instances(fed.config)
