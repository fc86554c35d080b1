"""The witness: a design's worst input over the scene's domain, found by a fresh sample and a
local search, replayed bit-exactly through the golden model; the compiled design meets the
requirement on views that were never part of the compile."""

import dataclasses
import json
import os

import numpy as np
import pytest

from phongfx.compiler.compile import compile_scene, scene_domain
from phongfx.compiler.request import CompileRequest
from phongfx.explore.compile.climb import inside, points, state_of
from phongfx.explore.compile.measure import SceneEval
from phongfx.explore.compile.witness import explore, geometry, replay, search
from phongfx.scene.file import load_scene, parse_scene
from tests.compiler.test_compile import TORUS

SCENES = os.path.join(os.path.dirname(__file__), "..", "..", "..", "scenes")
#: fig7 on the tiny torus: narrow enough that the domain holds points of 2 levels or more
NARROW = {"vec_frac": 8, "x2_frac": 4, "shape_t_frac": 8, "coef": 0, "order": 1, "k": 4}
WIDE = {"vec_frac": 16, "x2_frac": 20, "shape_t_frac": 24, "coef": 16, "order": 2, "k": 4}


@pytest.fixture(scope="module")
def tiny():
    spec = parse_scene(TORUS.format(error=1.0, against="phong"), name="tiny")
    scene = SceneEval(spec)
    return spec, scene, scene_domain(spec, scene.geometries)


def test_the_witness_is_the_worst_found_and_replays_bit_exactly(tiny):
    spec, scene, domain = tiny
    witness = search("fig7", NARROW, spec, domain, samples=5000, analysis=scene.analysis)
    assert witness["error_levels"] >= 2 and witness["unrounded"] > witness["error_levels"] - 0.5
    assert witness["error_levels"] >= witness["sampled"]["error_levels"]  # the local search adds, never loses
    assert set(witness["codes"]) == {"n0", "n1", "a", "v", "l0"} and len(witness["codes"]["n0"]) == 3
    level = max(abs(witness["outputs"][c] - witness["reference_levels"][i]) for i, c in enumerate("rgb"))
    assert level == witness["error_levels"] and witness["replay"] == "phongfx certify DIR --replay"
    json.dumps(witness)  # JSON-able, for the manifest
    again = replay(witness, "fig7", NARROW, spec, analysis=scene.analysis)
    assert again["matches"] and again["codes_match"] and again["outputs_match"]
    assert again["error_levels"] == witness["error_levels"]
    # another design at the same point: its own outputs, no longer the witness's
    other = replay(witness, "fig7", WIDE, spec, analysis=scene.analysis)
    assert not other["matches"] and other["error_levels"] < witness["error_levels"]


def test_a_search_is_deterministic_and_its_seed_is_not_the_width_search_s(tiny):
    spec, scene, domain = tiny
    a = search("fig7", NARROW, spec, domain, samples=3000, analysis=scene.analysis, rounds=2)
    b = search("fig7", NARROW, spec, domain, samples=3000, analysis=scene.analysis, rounds=2)
    assert a["point"] == b["point"] and a["unrounded"] == b["unrounded"]
    assert a["seed"] != domain.seed and "3,000 fresh domain points" in a["found_by"]


def test_the_local_search_stays_in_the_domain(tiny):
    spec, scene, domain = tiny
    witness, hard = explore("fig7", NARROW, spec, domain, samples=3000, analysis=scene.analysis, hard=256)
    g = geometry(witness, spec)
    assert inside(state_of(g, domain), g, domain).all()
    # the hard points: the witness itself and neighbours of it and of where the climbs ended, all in the domain
    assert 200 <= len(hard) <= 256 and inside(state_of(hard, domain), hard, domain).all()
    assert np.allclose(hard.n0[0], witness["point"]["n0"])
    span = np.degrees(np.arccos(np.clip(np.sum(hard.n0 * hard.n1, -1), -1, 1)))
    assert span.max() <= domain.max_span_angle_deg + 1e-9


def test_a_state_outside_the_domain_is_rejected(tiny):
    spec, scene, domain = tiny
    g = domain.sample(64, 3)
    s = state_of(g, domain)
    assert inside(s, points(s, domain, g.rgb, g.bits), domain).all()
    s.n1[:] = -s.n0  # span ends 180° apart: past the domain's span angle
    assert not inside(s, points(s, domain, g.rgb, g.bits), domain).any()


def test_a_compiled_design_holds_on_views_never_compiled_smoke():
    """The done-when of the domain search, on a tiny scene: the chosen design's error on the torus
    turned about other axes (rendered only after the compile) meets the requirement."""
    spec = parse_scene(TORUS.format(error=1.0, against="phong"), name="tiny")
    compiled = compile_scene(CompileRequest(spec, methods=["fig7"]))
    assert compiled.witness["error_levels"] <= 1.0 and compiled.best["domain_points"] >= 2000
    for axis in ([1, 0, 0], [0, 0, 1]):
        turned = dataclasses.replace(spec, frames=dataclasses.replace(spec.frames, axis=tuple(axis), degrees=360.0,
                                                                      count=4))
        assert SceneEval(turned).error("fig7", compiled.best["params"])["max"] <= 1.0, axis


@pytest.mark.slow
def test_the_torus_design_holds_on_other_axes_and_in_between_angles():
    """scenes/torus.toml compiled (its domain at full size), then rendered about other axes, 32
    frames over 360° (in-between angles): within the requirement everywhere."""
    spec = load_scene(os.path.join(SCENES, "torus.toml"))
    compiled = compile_scene(CompileRequest(spec, methods=["fig7", "conventional"]))
    params, required = compiled.best["params"], spec.requirement.max_error_levels
    assert compiled.witness["error_levels"] <= required and compiled.witness["samples"] == 10 ** 7
    for axis in ([1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 0]):
        turned = dataclasses.replace(spec, frames=dataclasses.replace(spec.frames, axis=tuple(axis), degrees=360.0,
                                                                      count=32))
        assert SceneEval(turned).error(compiled.chosen, params)["max"] <= required, axis
