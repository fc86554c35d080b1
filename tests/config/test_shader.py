import pytest

from phongfx.config import BlendConfig, BlinnConfig, ConventionalConfig, ShaderConfig, fig7_config


def _blend(lights=2, **changes):
    grey = ((0.5, 0.5, 0.5),) * lights
    return BlendConfig(**{"lights": lights, "diffuse": (grey,), "specular": (grey,), **changes})


def test_defaults_are_figure_7_with_two_lights_and_grey_blend():
    config = ShaderConfig()
    assert config.unit == "fig7" and config.copies == 1
    assert set(config.inputs) == set(fig7_config().inputs)
    assert list(config.outputs) == ["r", "g", "b"]
    assert config.terms == [(0, "diff0", None, "spec0"), (0, "diff1", None, "spec1")]


def test_one_light_units_take_one_copy_each_with_prefixed_inputs():
    units = (ConventionalConfig(local_light=True), ConventionalConfig())
    config = ShaderConfig(unit="conventional", units=units, blend=_blend(diff="1.15"), share=False)
    assert config.copies == 2 and config.terms[1] == (1, "diffuse", None, "specular")
    assert {"c0_normal", "c0_light", "c1_normal", "c1_n"} <= set(config.inputs)
    assert "normal" not in config.inputs and config.shared == ()


def test_what_does_not_depend_on_the_light_enters_once():
    units = (ConventionalConfig(local_light=True), ConventionalConfig())
    config = ShaderConfig(unit="conventional", units=units, blend=_blend(diff="1.15"))
    assert config.shared == ("normal", "view", "n")
    assert list(config.inputs) == ["normal", "view", "n", "c0_light", "c1_light"]
    assert config.port_name(1, "normal") == "normal" and config.port_name(1, "light") == "c1_light"
    # V is shared only when every copy takes it alike (a local viewer in one copy only: not)
    mixed = config.replace(units=(ConventionalConfig(local_viewer=True), ConventionalConfig()))
    assert mixed.shared == ("normal", "n") and {"c0_view", "c1_view"} <= set(mixed.inputs)
    blinn = ShaderConfig(unit="blinn", units=(BlinnConfig(),) * 2, blend=_blend(diff="1.15"))
    assert list(blinn.inputs) == ["normal", "n", "c0_light", "c0_half", "c1_light", "c1_half"]
    # one copy (Lyon's datapaths hold every light): nothing changes
    assert list(ShaderConfig().inputs) == list(ShaderConfig(share=False).inputs) == list(fig7_config().inputs)


def test_material_port_comes_from_the_blend():
    grey = ((0.5, 0.5, 0.5),) * 2
    blend = BlendConfig(ambient=((0, 0, 0), (0.1, 0.1, 0.1)), diffuse=(grey, grey), specular=(grey, grey))
    assert "material" in ShaderConfig(blend=blend).inputs


def test_replace_sends_unit_settings_to_every_unit_and_pipeline_to_the_blend():
    config = ShaderConfig().replace(pipeline=2, vec_frac=12)
    assert config.units[0].pipeline == 2 and config.units[0].vec_frac == 12
    assert config.blend.pipeline == 2
    # the conventional unit is pipelined by hand: it has no depth to take, the blend takes it
    units = (ConventionalConfig(),) * 2
    conventional = ShaderConfig(unit="conventional", units=units, blend=_blend(diff="1.15")).replace(pipeline=3)
    assert conventional.units == units and conventional.blend.pipeline == 3


@pytest.mark.parametrize("changes, error, message", [
    (dict(unit="lirp"), ValueError, r"^unit must be one of fig7, .*, not 'lirp'$"),
    (dict(units=()), ValueError, r"^copies \(len\(units\)\) must be an integer in 1\.\.8, not 0$"),
    (dict(blend=_blend(spec="1.12")), ValueError,
     r"^blend\.spec \(1\.12\) must equal the unit's spec0 \(1\.15\): they are connected$"),
    (dict(units=(ConventionalConfig(),)), TypeError, r"^units\[0\] must be a DatapathConfig, not "),
    (dict(blend=_blend(lights=1)), ValueError,
     r"^blend\.lights must be 2 \(the lights the units compute\), not 1$"),
    (dict(blend=_blend(diff="1.12")), ValueError,
     r"^blend\.diff \(1\.12\) must equal the unit's diff0 \(1\.10\): they are connected$"),
    (dict(blend=_blend(diff="", gate=False, diffuse=(((0, 0, 0),) * 2,))), ValueError,
     r"^blend\.diff must be a format: the fig7 unit has a diffuse output$"),
])
def test_bad_configs_are_refused(changes, error, message):
    with pytest.raises(error, match=message):
        ShaderConfig(**changes)


def test_lights_take_turns_on_fewer_units():
    four = _blend(lights=4, diffuse=(((0.5,) * 3,) * 4,), specular=(((0.5,) * 3,) * 4,))
    config = ShaderConfig(units=(fig7_config(lights=4, local_lights=(True, False, True, False)),),
                          blend=four, interval=2)
    assert (config.lights, config.per_cycle) == (4, 2)
    assert config.physical_units[0].lights == 2 and config.physical_units[0].local_lights == (True, False)
    # turn 1: lights 2 and 3 on the datapath's lights 0 and 1; the rest is the same for both turns
    assert config.feeds(1)[0]["l0_0"] == "l2_0" and config.feeds(1)[0]["l1"] == "l3"
    assert config.feeds(1)[0]["n0"] == "n0" and config.inputs == config.replace(interval=1).inputs
    blinn = ShaderConfig(unit="blinn", units=(BlinnConfig(),) * 4, blend=four.replace(diff="1.15"), interval=2)
    assert len(blinn.physical_units) == 2
    assert blinn.feeds(1) == [{"normal": "normal", "light": "c2_light", "half": "c2_half", "n": "n"},
                              {"normal": "normal", "light": "c3_light", "half": "c3_half", "n": "n"}]


@pytest.mark.parametrize("changes, message", [
    (dict(interval=3), r"^interval must be one of 1, 2, 4 for 4 lights, not 3: 2 lights per cycle are done "
                       r"in 2 cycles$"),
    (dict(interval=5), r"^interval \(4 lights\) must be an integer in 1\.\.4, not 5$"),
    (dict(interval=4), r"^units\[0\] and units\[1\] \(lights 0 and 1\) share one physical unit at "
                       r"interval 4, so they must be equal: "),
])
def test_turns_that_cannot_be_taken_are_refused(changes, message):
    units = (ConventionalConfig(local_light=True), ConventionalConfig()) * 2
    blend = _blend(lights=4, diff="1.15", diffuse=(((0.5,) * 3,) * 4,), specular=(((0.5,) * 3,) * 4,))
    with pytest.raises(ValueError, match=message):
        ShaderConfig(unit="conventional", units=units, blend=blend, **changes)
    assert ShaderConfig(unit="conventional", units=units, blend=blend, interval=2).per_cycle == 2
    with pytest.raises(ValueError, match=r"^lights 0 and 1 share one datapath light at interval 2, so "
                                         r"local_lights must be equal for them, not True and False$"):
        ShaderConfig(units=(fig7_config(local_lights=(True, False)),), interval=2)
