"""The compiler's shader of a method at an architecture: depth, light sharing, shared inputs."""

import pytest

from phongfx.explore.compile import run as runs
from phongfx.explore.compile.analysis import Analysis


def analysis(light_local=(False, False), local_viewer=False):
    """A scene of ``len(light_local)`` lights (True: a point light), one material, n = 16."""
    lights = len(light_local)
    return Analysis(local_lights=any(light_local), local_viewer=local_viewer, light_local=tuple(light_local),
                    lights=lights, n_values=(16,), n_lo=16, n_hi=16, single_n=True, max_span_angle_deg=5.0,
                    min_normal_length=0.9, g1_error=0.0, g2_error=0.0, highlight_in_span=0.1, spans=10,
                    pixels=100, ambient=((0.1, 0.1, 0.1),), diffuse=(((0.3, 0.3, 0.3),) * lights,),
                    specular=(((0.2, 0.2, 0.2),) * lights,))


def test_no_architecture_is_depth_0_one_pixel_per_clock_shared():
    config = runs.build("fig7", {}, analysis())
    assert (config.interval, config.share, config.units[0].pipeline, config.blend.pipeline) == (1, True, 0, 0)
    assert config == runs.build("fig7", {}, analysis(), dict(runs.ARCHITECTURE))


def test_the_depth_goes_to_the_unit_and_the_blend():
    config = runs.build("fig7", {}, analysis(), {"pipeline": 3, "interval": 2})
    assert (config.units[0].pipeline, config.units[0].normalize.pipeline, config.blend.pipeline) == (3, 3, 3)
    assert config.interval == 2 and config.physical_units[0].lights == 1
    # the conventional unit is pipelined by hand: the blend alone takes the depth
    conventional = runs.build("conventional", {}, analysis(), {"pipeline": 2, "share": False})
    assert conventional.blend.pipeline == 2 and not hasattr(conventional.units[0], "pipeline")
    assert "c1_normal" in conventional.inputs
    with pytest.raises(ValueError, match="^architecture keys must be among pipeline, interval, share, not depth$"):
        runs.build("fig7", {}, analysis(), {"depth": 1})


def test_architectures_are_the_depths_times_the_legal_intervals():
    two = runs.architectures("fig7", analysis())
    assert len(two) == 10 and two[0] == {"pipeline": 0, "interval": 1, "share": True}
    assert {a["interval"] for a in two} == {1, 2} and {a["pipeline"] for a in two} == set(range(5))
    # four lights: 3 cycles of 2 would idle one, so 1, 2 and 4
    assert {a["interval"] for a in runs.architectures("blinn", analysis((False,) * 4))} == {1, 2, 4}
    # a point light and a directional one cannot take turns on one copy of the conventional unit
    assert {a["interval"] for a in runs.architectures("conventional", analysis((True, False)))} == {1}
    # nor on one datapath light: its L is interpolated, the other's a constant
    assert {a["interval"] for a in runs.architectures("fig7", analysis((True, False)))} == {1}
    assert {a["interval"] for a in runs.architectures("fig7", analysis((True, False, True, False)))} == {1, 2}
