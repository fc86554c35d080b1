"""The interval certificate: sound on the example scenes' frames and domains, and with teeth."""

import json
from dataclasses import replace

import numpy as np
import pytest

from phongfx.certify import Certificate, certify
from phongfx.certify.bound import shader_config
from phongfx.explore.compile.measure import SceneEval
from phongfx.scene.domain import domain
from phongfx.scene.file import load_scene

#: The widths ``phongfx compile`` chooses for fig7 (its manifests' "widths").
TORUS = {"vec_frac": 10, "x2_frac": 5, "shape_t_frac": 10, "coef": 0, "order": 1, "k": 4}
LYON = {"vec_frac": 10, "x2_frac": 5, "shape_t_frac": 8, "coef": 0, "order": 2}
#: ... and on local-mesh (where conventional Phong is cheaper)
LOCAL = {"vec_frac": 16, "x2_frac": 11, "shape_t_frac": 17, "coef": 1, "order": 2, "k": 5}
#: ... and for fig8, the runner-up on both scenes.
TORUS_FIG8 = {"vec_frac": 10, "root_frac": 10, "t_frac": 11, "coef": 0, "order": 1, "k": 4}
LYON_FIG8 = {"vec_frac": 10, "root_frac": 8, "t_frac": 8, "coef": 2, "order": 1}


def _scene(name):
    """The scene and its whole domain, one region: these tests hold the bounding method to
    figures at given budgets (test_regions.py bounds region by region)."""
    spec = load_scene(f"scenes/{name}.toml")
    return spec, replace(domain(spec), regions=())


def _measured(spec, shader, params, geometries=None, method="fig7"):
    """Largest ``|out - (2^bits - 1)·I_ref|`` of the whole shader's golden model over the scene's
    frames (``geometries`` None) or over the given geometries, as the compiler measures it."""
    scene = SceneEval(spec, geometries)
    scale = (1 << spec.output.bits) - 1
    worst = 0.0
    for index in range(len(scene.renders)):
        codes, ref = scene.render(method, shader, params, index)[:2]
        worst = max(worst, float(np.max(np.abs(codes - ref * scale), initial=0.0)))
    return worst


def _sampled(spec, dom, shader, params, count, seed=11, method="fig7"):
    return max(_measured(spec, shader, params, method=method),
               _measured(spec, shader, params, [dom.sample(count, seed)], method))


#: the measurements other bounding methods' tests share
measured, sampled = _measured, _sampled


def test_methods_without_a_bounding_method_say_so():
    spec, dom = _scene("torus")
    got = certify("schlick", {}, spec, dom)
    assert isinstance(got, Certificate)
    assert (got.certified, got.bound_levels, got.method) == (False, None, "interval")
    assert got.why == "no bounding method for the schlick unit yet"


def test_point_lights_and_a_local_viewer_are_bounded():
    """local-mesh (a point light and a local camera) gets a bound, above what its frames and
    domain samples measure, at the compiler's widths and at the defaults."""
    spec, dom = _scene("local-mesh")
    for params, top in ((LOCAL, 8), ({}, 60)):
        shader = shader_config("fig7", params, spec)
        got = certify("fig7", params, spec, dom, shader=shader, max_boxes=20_000)
        measured = _sampled(spec, dom, shader, params, 20_000)
        assert 1.0 < measured <= got.bound_levels < top
        assert not got.certified and "over the required 1" in got.why


def test_the_halfway_unit_with_a_point_light_says_why_not():
    spec, dom = _scene("local-mesh")
    got = certify("halfway", {}, spec, dom)
    assert got.bound_levels is None
    assert got.why.startswith("the halfway unit with point lights or a local viewer is not bounded yet")


def test_the_bound_holds_on_the_torus_smoke():
    """A small budget and sample: the bound (looser, still sound) is above what is measured."""
    spec, dom = _scene("torus")
    shader = shader_config("fig7", TORUS, spec)
    got = certify("fig7", TORUS, spec, dom, shader=shader, max_boxes=20_000)
    measured = _sampled(spec, dom, shader, TORUS, 20_000)
    assert 1.0 < measured <= got.bound_levels < 30
    assert got.parts["output"] == 0.5 and got.parts["where"]["n"] == 16
    assert got.bound_levels == pytest.approx(got.parts["rounding"] + got.parts["approximation"] + 0.5, rel=1e-9)
    assert not got.certified and "over the required 1" in got.why


@pytest.mark.parametrize("method, name, params", [("fig8", "torus", TORUS_FIG8), ("halfway", "lyon-balls", {})])
def test_the_bound_holds_for_the_other_units_smoke(method, name, params):
    spec, dom = _scene(name)
    shader = shader_config(method, params, spec)
    got = certify(method, params, spec, dom, shader=shader, max_boxes=20_000)
    measured = _sampled(spec, dom, shader, params, 20_000, method=method)
    assert got.bound_levels is not None and measured <= got.bound_levels


@pytest.mark.slow
@pytest.mark.parametrize("method, name, params", [
    ("fig7", "torus", TORUS), ("fig7", "torus", {}),
    ("fig7", "torus", {"vec_frac": 8, "x2_frac": 4, "shape_t_frac": 8, "coef": 2, "order": 1, "k": 4}),
    ("fig7", "lyon-balls", LYON), ("fig7", "lyon-balls", {}), ("fig7", "lyon-balls", {**LYON, "vec_frac": 11}),
    ("fig8", "torus", TORUS_FIG8), ("fig8", "torus", {}), ("fig8", "lyon-balls", LYON_FIG8),
    ("halfway", "torus", {}), ("halfway", "lyon-balls", {}),
    ("fig7", "local-mesh", LOCAL), ("fig7", "local-mesh", {}), ("fig8", "local-mesh", {}),
])
def test_the_bound_holds_on_frames_and_domain(method, name, params):
    spec, dom = _scene(name)
    shader = shader_config(method, params, spec)
    got = certify(method, params, spec, dom, shader=shader)
    measured = _sampled(spec, dom, shader, params, 100_000, method=method)
    assert got.bound_levels is not None and measured <= got.bound_levels


def _worse(shader, frac_drop):
    """The shader with its shape function's squarers ``frac_drop`` bits narrower and truncating:
    the hardware made deliberately worse, its ports and blend unchanged but for that format."""
    unit = shader.units[0]
    t = unit.shape.fmt("t")
    narrow = f"{t.int_bits}.{t.frac_bits - frac_drop}"
    shape = unit.shape.replace(t=narrow, rounding="truncate")
    unit = unit.replace(shape=shape)
    return replace(shader, units=(unit,), blend=shader.blend.replace(spec=narrow))


@pytest.mark.parametrize("name, params, drop, boxes", [("torus", TORUS, 4, 100_000), ("local-mesh", LOCAL, 10, 20_000)])
def test_a_worse_quantize_breaks_the_old_bound_and_raises_the_new_one(name, params, drop, boxes):
    """The check has teeth: a hardware whose squarers truncate ``drop`` fraction bits shorter is
    measured over the unchanged bound, and the bound computed over it rises above that (the
    torus: lights and viewer at infinity; local-mesh: a point light and a local viewer)."""
    spec, dom = _scene(name)
    shader = shader_config("fig7", params, spec)
    worse = _worse(shader, drop)
    before = certify("fig7", params, spec, dom, shader=shader, max_boxes=boxes).bound_levels
    measured = _sampled(spec, dom, worse, params, 20_000)
    after = certify("fig7", params, spec, dom, shader=worse, max_boxes=20_000).bound_levels
    assert before + 5 < measured <= after


def test_a_wide_design_is_certified_and_early_stops_once_it_is():
    """At wide widths and g2 the torus's bound meets 1 level; ``early`` stops refining there
    (a bound that meets the requirement, from a fraction of the boxes)."""
    spec, dom = _scene("torus")
    wide = {"vec_frac": 14, "x2_frac": 14, "shape_t_frac": 18, "coef": 8, "order": 2, "k": 4}
    shader = shader_config("fig7", wide, spec)
    quick = certify("fig7", wide, spec, dom, shader=shader, early=True)
    assert quick.certified and quick.why == ""
    assert 0.5 < quick.bound_levels < 1.5 and quick.parts["boxes"] < 100_000
    assert json.loads(json.dumps(quick.as_dict()))["method"] == "interval"
    assert _sampled(spec, dom, shader, wide, 20_000) <= quick.bound_levels


def test_a_backside_test_that_may_differ_is_named():
    """Lyon's balls at vec_frac 10: the diffuse unit's N·L error bound (about 4.3e-3) is wider
    than the terminator band 1/255, so where n = 1's highlight crosses the terminator the
    hardware may gate off what the reference shows: the bound pays the whole specular term."""
    spec, dom = _scene("lyon-balls")
    got = certify("fig7", LYON, spec, dom, max_boxes=60_000)
    assert got.parts["where"]["n"] == 1 and got.parts["backside"] > 1 / 255
    assert got.bound_levels > 30 and "backside test may differ" in got.why
    wider = certify("fig7", {**LYON, "vec_frac": 11}, spec, dom, max_boxes=60_000)
    assert "backside" not in wider.parts and wider.bound_levels < 20
