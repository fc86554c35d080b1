import pytest

import re

from phongfx.config import (BlendConfig, BlinnConfig, ConventionalConfig, SchlickConfig, ShaderConfig,
                            SphericalConfig, fig8_config)
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


def _two_lights(unit, cls, **changes):
    grey = ((0.5, 0.5, 0.5),) * 2
    return ShaderConfig(unit=unit, units=(cls(),) * 2,
                        blend=BlendConfig(diff="1.15", diffuse=(grey,), specular=(grey,)), **changes)


@pytest.mark.needs_verilator
@pytest.mark.parametrize("unit, cls", [("conventional", ConventionalConfig), ("blinn", BlinnConfig)])
def test_shared_inputs_fan_out_to_every_copy(unit, cls):
    shader = get_block("shader", config=_two_lights(unit, cls))
    check(shader, backend="verilator-fast", bubbles=0.2, count=400, seed=7).raise_on_mismatch()


def yosys_cells(config, tmp_path):
    """Cells of the shader after Yosys' ``proc; flatten; opt_merge; opt_clean``: logic fed by the
    same wires merged, as a synthesizer merges it."""
    from phongfx.explore.synth.toolrun import design_rtlil
    from phongfx.sim.tools import run_yosys

    tmp_path.mkdir()
    (tmp_path / "design.il").write_text(design_rtlil(get_block("shader", config=config), "top"))
    (tmp_path / "script.ys").write_text("read_rtlil design.il\nhierarchy -top top\nproc\nflatten\n"
                                        "opt_merge\nopt_clean\ntee -o stat.txt stat\n")
    run_yosys(tmp_path, "script.ys")
    return int(re.findall(r"(\d+) +cells\n", (tmp_path / "stat.txt").read_text())[-1])


@pytest.mark.needs_yosys
@pytest.mark.parametrize("unit, cls, shared, apart", [
    ("conventional", ConventionalConfig, 597, 693), ("blinn", BlinnConfig, 518, 589)])
def test_shared_normal_is_built_once(unit, cls, shared, apart, tmp_path):
    # the normalizer of N (and N·V) merged between the two copies: 14 % / 12 % of the cells
    config = _two_lights(unit, cls)
    assert yosys_cells(config, tmp_path / "shared") == shared
    assert yosys_cells(config.replace(share=False), tmp_path / "apart") == apart


def _coloured(lights, diff="1.10"):
    values = tuple((0.1 + 0.2 * i, 0.5 - 0.1 * i, 0.3) for i in range(lights))
    return BlendConfig(lights=lights, diff=diff, diffuse=(values,), specular=(values[::-1],))


SHARED_UNITS = {
    "conventional, 2 lights": ShaderConfig(unit="conventional", units=(ConventionalConfig(),) * 2,
                                           blend=_coloured(2, "1.15"), interval=2),
    "fig7, 2 lights": ShaderConfig(blend=_coloured(2), interval=2),
    # the datapath's second light idles in turn 1
    "fig8, 3 lights": ShaderConfig(unit="fig8", units=(fig8_config(lights=3),), blend=_coloured(3), interval=2),
}


def test_turns_add_interval_minus_one_to_the_latency():
    for config in SHARED_UNITS.values():
        shared, whole = get_block("shader", config=config), get_block("shader", config=config.replace(interval=1))
        assert shared.component().interval == config.interval == 2 and whole.component().interval == 1
        assert shared.latency == whole.latency + 1


@pytest.mark.needs_verilator
@pytest.mark.parametrize("name", list(SHARED_UNITS))
def test_lights_taking_turns_stall_and_reset_exactly(name):
    block = get_block("shader", config=SHARED_UNITS[name])
    check(block, backend="verilator-fast", bubbles=0.2, count=600, seed=3).raise_on_mismatch()
    result = check(block, backend="verilator-fast", bubbles=0.2, count=600, seed=4, stalls=0.3, reset_at=500)
    result.raise_on_mismatch()
    assert result.resets == 1 and result.resent > 0 and result.stall_cycles > 100
    # one pixel per two clocks at best: the stream takes at least twice as many cycles as pixels
    assert result.cycles > 2 * result.vectors


def test_lights_taking_turns_on_the_amaranth_simulator():
    block = get_block("shader", config=SHARED_UNITS["fig7, 2 lights"])
    result = check(block, backend="amaranth", bubbles=0.2, count=40, seed=5, stalls=0.3, reset_at=30)
    result.raise_on_mismatch()
    assert result.resets == 1 and result.stall_cycles > 0


def test_a_wrapper_that_ignores_the_interval_is_caught():
    from phongfx.hdl.handshake import Handshake

    class IgnoresInterval(Handshake):
        def __init__(self, block):
            super().__init__(block)
            self.interval = 1  # in_ready high while the block is busy with a pixel's turns

    block = get_block("shader", config=SHARED_UNITS["fig7, 2 lights"])
    result = check(block, backend="amaranth", bubbles=0.0, count=20, seed=5, stalls=0.1,
                   handshake=IgnoresInterval)
    assert result.mismatch_count > 0
