"""A width point measured on the frames and on a sample of the scene's domain: the larger is
the criterion, the domain skipped where the frames already miss, hard points and the domain
in the journal's key, the spherical unit on rasterized random poses."""

import dataclasses

import numpy as np
import pytest

from phongfx.compiler.compile import scene_domain
from phongfx.explore.compile import run as runs
from phongfx.explore.compile.journal import scene_key
from phongfx.explore.compile.measure import GUARD, SceneEval, meets, met_at
from phongfx.explore.compile.points import DomainPoints, take
from phongfx.scene.file import parse_scene
from tests.compiler.test_compile import TORUS
from tests.explore.compile.test_witness import NARROW, WIDE

PASSING = {**WIDE, "vec_frac": 12, "x2_frac": 8, "shape_t_frac": 12, "coef": 4}


@pytest.fixture(scope="module")
def tiny():
    spec = parse_scene(TORUS.format(error=1.0, against="phong"), name="tiny")
    scene = SceneEval(spec)
    domain = scene_domain(spec, scene.geometries, samples=3000)
    scene.measure_domain(DomainPoints(spec, domain))
    return spec, scene, domain


def test_the_criterion_is_the_larger_of_frames_and_domain(tiny):
    spec, scene, domain = tiny
    error = scene.error("fig7", PASSING)
    assert error["frames_max"] <= 1.0 and error["domain_points"] == 3000 and error["domain_climbed"] > 0
    assert error["max"] == max(error["frames_max"], error["domain_max"])
    assert error["max_unrounded"] >= error["domain_unrounded"] > 0
    frames_only = SceneEval(spec).error("fig7", PASSING)
    assert frames_only["max"] == error["frames_max"] and "domain_max" not in frames_only


def test_the_domain_is_skipped_where_the_frames_miss_unless_asked(tiny):
    spec, scene, domain = tiny
    error = scene.error("fig7", NARROW)
    assert error["frames_max"] > 1.0 and error["domain_max"] is None and error["domain_points"] == 0
    complete = scene.error("fig7", NARROW, complete=True)
    assert complete["domain_max"] >= 1 and complete["max"] >= error["max"]
    assert scene.error("fig7", NARROW) is complete  # the cache now holds the complete measurement


def test_the_screen_fails_a_point_by_its_frames_or_earlier_worst_points_without_the_whole_sample(tiny):
    spec, _, domain = tiny
    scene = SceneEval(spec)
    scene.measure_domain(DomainPoints(spec, domain))
    narrow = {**NARROW, "k": 3}  # fails on the frames: no domain point measured, kept as failed
    assert scene.fails_screen("fig7", narrow) and ("fig7", tuple(sorted(narrow.items()))) in scene.failed
    assert not scene.passes("fig7", narrow) and not scene.cache
    assert not scene.fails_screen("fig7", PASSING) and not scene.cache  # passes: nothing measured whole
    whole = scene.error("fig7", PASSING)  # now the screen holds this measurement's worst points
    assert not scene.fails_screen("fig7", PASSING) and whole["max"] <= 1.0
    # a point whose frames pass but which some of those worst points fail (the whole sample: 2 levels)
    worse = {**PASSING, "vec_frac": 9}
    assert SceneEval(spec).error("fig7", worse)["frames_max"] <= 1.0
    assert scene.fails_screen("fig7", worse) and ("fig7", tuple(sorted(worse.items()))) in scene.failed
    assert scene.error("fig7", worse)["max"] == 2.0


def test_the_guard_on_the_domain_s_continuous_error():
    assert meets({"max": 1.0, "domain_unrounded": 1.5 - GUARD}, 1.0)
    assert not meets({"max": 1.0, "domain_unrounded": 1.5 - GUARD + 1e-6}, 1.0)
    assert not meets({"max": 2.0}, 1.0) and meets({"max": 1.0}, 1.0)  # frames only: the integer error
    assert met_at({"max": 1.0, "domain_unrounded": 1.45}) == 2 and met_at({"max": 3.0}) == 3


def test_the_journal_key_covers_the_domain_and_its_hard_points(tiny):
    spec, scene, domain = tiny
    points = DomainPoints(spec, domain)
    base = scene_key(spec, scene.geometries, points.key())
    other = DomainPoints(spec, dataclasses.replace(domain, seed=domain.seed + 1))
    assert scene_key(spec, scene.geometries, other.key()) != base
    assert scene_key(spec, scene.geometries) != base  # frames only
    points.add_hard(take(points.chunks[0][0], np.arange(10)))
    assert points.hard_points == 10 and scene_key(spec, scene.geometries, points.key()) != base


def test_the_sample_is_drawn_once_seeded_and_in_the_domain_s_chunks(tiny):
    spec, scene, domain = tiny
    a, b = DomainPoints(spec, domain), DomainPoints(spec, domain)
    assert sum(len(g) for g, *_ in a.chunks) == 3000
    np.testing.assert_array_equal(a.chunks[0][0].n0, b.chunks[0][0].n0)
    np.testing.assert_array_equal(a.chunks[0][0].n0, domain.sample(3000, domain.seed).n0)


def test_the_spherical_unit_is_measured_on_random_poses(tiny):
    spec, scene, domain = tiny
    assert not runs.per_pixel("spherical") and runs.per_pixel("fig7")
    points = DomainPoints(spec, dataclasses.replace(domain, samples=1500))
    params = {"addr_bits": 16, "rom_bits": 16, "theta_frac": 20, "coef": 16}
    config = runs.build("spherical", params, scene.analysis)
    measured = points.error("spherical", config, params)
    assert measured["points"] >= 1500 and measured["climbed"] == 0
    assert measured["how"].startswith("visible pixels of") and measured["max"] > 1  # 4n stands for n only roughly
