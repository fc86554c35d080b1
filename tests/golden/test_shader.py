import numpy as np
import pytest

from phongfx.config import BlendConfig, BlinnConfig, ConventionalConfig, ShaderConfig, fig7_config, halfway_config
from phongfx.core.registry import get_block
from phongfx.explore.tables.extremes import run_block


def test_the_shader_is_the_unit_then_the_blend():
    shader = get_block("shader")
    raw = shader.stimulus(count=200, seed=3)
    unit = get_block("fig7", config=shader.config.units[0]).golden(raw)
    blend = get_block("blend", config=shader.config.blend).golden(unit)
    out = shader.golden(raw)
    assert set(out) == {"r", "g", "b"}
    for name in "rgb":
        assert np.array_equal(out[name], blend[name])
    assert len(np.unique(out["r"])) > 20  # the stimulus reaches many levels


def test_the_halfway_highlight_at_v_equal_minus_l_does_not_reach_the_pixel():
    # V = −L: the halfway unit's spec is 1.0 (H = 0), but N·L = −1 gates it off
    config = ShaderConfig(unit="halfway_datapath", units=(halfway_config(),),
                          blend=BlendConfig(ambient=((0.1, 0.2, 0.3),)))
    rows = {row.name: row for row in get_block("halfway_datapath").extremes()}
    raw = rows["V = −L (N = V), n_max"].build(config.units[0])
    unit = get_block("halfway_datapath", config=config.units[0]).golden(raw)
    assert np.all(unit["spec0"] == config.units[0].outputs["spec0"][0].one)
    out = get_block("shader", config=config).golden(raw)
    assert np.all(out["r"] == 26) and np.all(out["g"] == 51) and np.all(out["b"] == 77)  # 255·ka·M, rounded


def test_extreme_rows_hold():
    rows, _ = run_block("shader")
    assert len(rows) == 2
    for row in rows:
        assert row["golden"] == "pass" and row["rtl"] == "pass", row


def test_shader_raw_gives_the_shader_codes_and_the_diffuse_terms_chunk_by_chunk():
    from phongfx.golden.chunks import CHUNK
    from phongfx.golden.shader import shader_raw

    shader = get_block("shader")
    raw = shader.stimulus(count=CHUNK + 500, seed=6)
    out = shader_raw(shader.config, raw)
    whole = shader.golden(raw, whole=True)
    unit = get_block("fig7", config=shader.config.units[0]).golden(raw, whole=True)
    assert set(out) == {"r", "g", "b", "diff0", "diff1"}
    for name in "rgb":
        assert np.array_equal(out[name], whole[name])
    for name in ("diff0", "diff1"):
        assert np.array_equal(out[name], unit[name])
    assert len(out["r"]) > CHUNK and np.count_nonzero(out["diff0"]) > 100


def test_a_shared_input_feeds_every_copy_as_per_copy_inputs_would():
    grey = ((0.5, 0.5, 0.5),) * 2
    units = (ConventionalConfig(local_light=True), ConventionalConfig())
    shared = ShaderConfig(unit="conventional", units=units,
                          blend=BlendConfig(diff="1.15", diffuse=(grey,), specular=(grey,)))
    apart = shared.replace(share=False)
    raw = get_block("shader", config=shared).stimulus(count=300, seed=2)
    copied = {apart.prefix(copy) + name: raw[shared.port_name(copy, name)]
              for copy, sub in enumerate(units) for name in sub.inputs}
    want = get_block("shader", config=apart).golden(copied)
    got = get_block("shader", config=shared).golden(raw)
    for name in "rgb":
        assert np.array_equal(got[name], want[name])
    assert len(np.unique(got["r"])) > 20


def _lights(count, coloured=True):
    """Per-light blend constants, different for every light (a light in the wrong turn shows)."""
    return tuple((0.1 + 0.2 * i, 0.5 - 0.1 * i, 0.3) if coloured else (0.5, 0.5, 0.5) for i in range(count))


@pytest.mark.parametrize("name, config, intervals", [
    ("fig7, 2 lights", ShaderConfig(units=(fig7_config(),), blend=BlendConfig(
        diffuse=(_lights(2),), specular=(_lights(2)[::-1],))), [2]),
    # light 2 takes light 0's datapath light in turn 1, the other slot idles
    ("fig7, 3 point and directional lights", ShaderConfig(
        units=(fig7_config(lights=3, local_lights=(True, False, True)),),
        blend=BlendConfig(lights=3, diffuse=(_lights(3),), specular=(_lights(3),))), [2]),
    ("halfway, 4 lights", ShaderConfig(unit="halfway_datapath", units=(halfway_config(lights=4),),
                                       blend=BlendConfig(lights=4, diffuse=(_lights(4),), specular=(_lights(4),))),
     [2, 4]),
    ("conventional, 4 lights", ShaderConfig(unit="conventional", units=(ConventionalConfig(),) * 4,
                                            blend=BlendConfig(lights=4, diff="1.15", diffuse=(_lights(4),),
                                                              specular=(_lights(4),))), [2, 4]),
    ("blinn, 3 lights, not shared", ShaderConfig(unit="blinn", units=(BlinnConfig(),) * 3, share=False,
                                                 blend=BlendConfig(lights=3, diff="1.15", diffuse=(_lights(3),),
                                                                   specular=(_lights(3),))), [2, 3]),
])
def test_every_interval_gives_the_codes_of_interval_1(name, config, intervals):
    raw = get_block("shader", config=config).stimulus(count=400, seed=11)
    want = get_block("shader", config=config).golden(raw)
    assert len(np.unique(want["r"])) > 20
    for interval in intervals:
        got = get_block("shader", config=config.replace(interval=interval)).golden(raw)
        for channel in "rgb":
            assert np.array_equal(got[channel], want[channel]), (interval, channel)
