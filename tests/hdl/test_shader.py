import pytest

from phongfx.config import (BlendConfig, ConventionalConfig, SchlickConfig, ShaderConfig, SphericalConfig,
                            fig8_config)
from phongfx.core.registry import get_block
from phongfx.sim.harness import check

GREY = (0.5, 0.5, 0.5)


def _shader(**changes):
    return get_block("shader", config=ShaderConfig(**changes))


def test_latency_is_the_unit_and_the_blend():
    for depth in (0, 2, 4):
        shader = get_block("shader").config.replace(pipeline=depth)
        unit = get_block("fig7", config=shader.units[0])
        blend = get_block("blend", config=shader.blend)
        assert get_block("shader", config=shader).latency == unit.latency + blend.latency


@pytest.mark.needs_verilator
def test_copies_of_different_latencies_meet_at_the_blend():
    # a point light's copy normalizes its L (3 cycles more): the directional one's terms wait
    units = (ConventionalConfig(local_light=True), ConventionalConfig())
    latencies = [get_block("conventional", config=u).latency for u in units]
    assert latencies[0] > latencies[1]
    shader = _shader(unit="conventional", units=units, blend=BlendConfig(diff="1.15"))
    assert shader.latency == max(latencies) + get_block("blend", config=shader.config.blend).latency
    check(shader, backend="verilator-fast", bubbles=0.2, count=300, seed=4).raise_on_mismatch()


def test_harness(backend):
    count = 60 if backend == "amaranth" else 600
    check(get_block("shader"), backend=backend, bubbles=0.2, count=count, seed=5).raise_on_mismatch()


@pytest.mark.needs_verilator
@pytest.mark.parametrize("name, changes", [
    # two materials, one coloured light: the material port selects the constants
    ("fig8 two materials", dict(units=(fig8_config(lights=1),), blend=BlendConfig(
        lights=1, ambient=((0.1, 0.0, 0.2), (0.0, 0.0, 0.0)),
        diffuse=(((0.6, 0.3, 0.1),), ((0.2, 0.2, 0.9),)),
        specular=(((0.4, 0.4, 0.4),), ((0.8, 0.1, 0.1),)), coef_frac=6))),
    # one copy per light, one of them with a local L
    ("conventional, two copies", dict(unit="conventional", units=(ConventionalConfig(), ConventionalConfig()),
                                      blend=BlendConfig(diff="1.15"))),
    # no diffuse output: no gate
    ("schlick", dict(unit="schlick", units=(SchlickConfig(),), blend=BlendConfig(
        lights=1, diff="", gate=False, diffuse=(((0, 0, 0),),), specular=((GREY,),)))),
    # the diffuse term is the first lane of a vector output
    ("spherical", dict(unit="spherical", units=(SphericalConfig(),), blend=BlendConfig(
        lights=1, diff="1.11", spec="1.11", diffuse=((GREY,),), specular=((GREY,),)))),
    ("fig7 depth 4", dict(blend=BlendConfig(pipeline=4), units=(get_block("fig7", pipeline=4).config,))),
])
def test_harness_units_materials_and_depths(name, changes):
    check(_shader(**changes), backend="verilator-fast", bubbles=0.1, count=400, seed=9).raise_on_mismatch()
