"""The highlight scan: domain points turned to their highlight's peak, then normals about the
worst of them, every point in the domain."""

import dataclasses

import numpy as np
import pytest

from phongfx.compiler.compile import scene_domain
from phongfx.explore.compile.climb import inside, state_of
from phongfx.explore.compile.highlight import KEEP, STEEP, cap_angle, scan
from phongfx.explore.compile.measure import SceneEval
from phongfx.scene.file import load_scene
from phongfx.scene.mesh import unit
from tests.explore.compile.test_witness import SCENES


@pytest.fixture(scope="module")
def local():
    spec = load_scene(f"{SCENES}/local-mesh.toml")
    scene = SceneEval(spec)
    return spec, scene_domain(spec, scene.geometries)


def test_the_cap_ends_where_t_falls_to_one_less_steep_over_n():
    n = np.array([1.0, 16.0, 32.0, 256.0])
    assert np.allclose(np.cos(2 * cap_angle(n)), 1 - STEEP / n)
    assert np.all(np.diff(cap_angle(n)) < 0)  # the higher n, the narrower the peak


def _peakedness(g):
    """(P,) the largest ``N·H`` over the lights of the points ``g``, and their ``n``."""
    h = np.stack([unit(np.asarray(light) + np.asarray(g.viewer)) for light in g.light])
    return np.max(np.sum(h * np.asarray(g.normal), -1), axis=0)


def test_the_scan_finds_the_peak_and_stays_in_the_domain(local):
    spec, domain = local
    seen = []

    def evaluate(g):  # an error that is a sharp specular peak: the scan must land on it
        seen.append(len(g.a))
        u = np.clip(_peakedness(g), 0.0, 1.0) ** (50 * np.asarray(g.n)) * 2.0
        return np.floor(u + 0.5), u

    rgb = np.array([light.rgb for light in spec.lights]).reshape(-1, 3)
    found, evaluated = scan(evaluate, domain.sample(2048, 5), domain, rgb, spec.output.bits, 11, 16, 2048)
    assert evaluated == sum(seen) == 2048 + KEEP * (2048 // KEEP)
    assert len(found.a) == 16
    assert np.all(inside(state_of(found, domain), found, domain))
    # every start is within the cap about H where t^n is steep, at the material's largest n
    assert np.all(_peakedness(found) >= np.cos(cap_angle(found.n)) - 1e-9)
    assert np.all(found.n == max(domain.materials[0][1]))
    # the domain's own sample of the same size lands near the peak less often: its 16 worst,
    # one by one, are below the scan's
    near, sampled = evaluate(found)[1], evaluate(domain.sample(4096, 11))[1]
    assert near.min() > 1.5 and np.all(np.sort(near) > np.sort(sampled)[-16:])


def test_the_scan_is_deterministic_and_empty_without_lights(local):
    spec, domain = local

    def evaluate(g):
        u = _peakedness(g)
        return np.zeros(len(u)), u

    rgb = np.array([light.rgb for light in spec.lights]).reshape(-1, 3)
    positions = domain.sample(512, 5)
    a, _ = scan(evaluate, positions, domain, rgb, spec.output.bits, 3, 8, 1024)
    b, _ = scan(evaluate, positions, domain, rgb, spec.output.bits, 3, 8, 1024)
    assert np.array_equal(a.normal, b.normal) and np.array_equal(a.position, b.position)
    dark = dataclasses.replace(domain, lights=())
    assert scan(evaluate, positions, dark, rgb, spec.output.bits, 3, 8, 1024) == (None, 0)
