"""The width search's question answered fast and the same: the worst points without a full sort,
a point the domain fails measured only until it does (its screen of earlier worst points first),
and the whole measurement still there when its numbers are asked for."""

import numpy as np
import pytest

from phongfx.compiler.compile import scene_domain
from phongfx.explore.compile import points as points_module
from phongfx.explore.compile.measure import SceneEval, meets
from phongfx.explore.compile.points import DomainPoints, worst_index
from phongfx.scene.file import parse_scene
from tests.compiler.test_compile import TORUS
from tests.explore.compile.test_measure import PASSING


def test_the_worst_points_are_those_of_a_full_sort_in_its_order():
    rng = np.random.default_rng(7)
    for trial in range(400):
        size = int(rng.integers(1, 2000))
        levels = rng.integers(0, int(rng.integers(1, 4)), size)  # few levels: many ties
        pool = rng.random(int(rng.integers(1, 40)))
        unrounded = rng.choice(pool, size) if trial % 2 else rng.random(size)
        count = int(rng.integers(1, 64))
        np.testing.assert_array_equal(worst_index(levels, unrounded, count),
                                      np.lexsort((unrounded, levels))[-count:])


@pytest.fixture
def tiny():
    spec = parse_scene(TORUS.format(error=1.0, against="phong"), name="tiny")
    scene = SceneEval(spec)
    scene.measure_domain(DomainPoints(spec, scene_domain(spec, scene.geometries, samples=3000)))
    return spec, scene


def _counting(monkeypatch):
    """The number of domain points the measurements shade, as a list that grows."""
    shaded = []
    original = points_module.shade_points

    def counted(method, config, params, against, g, *args):
        shaded.append(len(g))
        return original(method, config, params, against, g, *args)
    monkeypatch.setattr(points_module, "shade_points", counted)
    return shaded


def test_a_point_the_domain_fails_is_measured_until_it_does(tiny, monkeypatch):
    spec, scene = tiny
    shaded = _counting(monkeypatch)
    assert scene.passes("fig7", PASSING)  # measured whole: every one of the 3000 points
    assert sum(shaded) == 3000
    failing = {**PASSING, "vec_frac": 9}  # within 1 level on the frames, 2 on the domain
    shaded.clear()
    assert not scene.passes("fig7", failing)
    assert 0 < sum(shaded) <= 32  # PASSING's worst points (its screen) already fail it
    key = ("fig7", tuple(sorted(failing.items())))
    assert key in scene.failed and key not in scene.cache and scene.points_measured == 2
    error = scene.error("fig7", failing)  # the numbers asked for: the whole sample measured
    assert error["domain_points"] == 3000 and error["domain_max"] == 2 and not meets(error, 1.0)
    assert key in scene.cache and scene.points_measured == 2


def test_the_answer_is_that_of_the_whole_measurement(tiny):
    spec, scene = tiny
    fresh = SceneEval(spec)
    fresh.measure_domain(scene.points)
    tried = [{**PASSING, name: value} for name, values in
             (("vec_frac", (12, 10, 9, 8)), ("x2_frac", (6, 5, 4)), ("coef", (4, 2, 0))) for value in values]
    answers = [scene.passes("fig7", params) for params in tried]
    assert answers == [meets(fresh.error("fig7", params), 1.0) for params in tried]
    assert True in answers and False in answers and scene.failed  # some failed on part of the domain only


@pytest.mark.parametrize("method, params", [
    ("fig7", {"vec_frac": 12, "x2_frac": 8, "shape_t_frac": 12, "coef": 4, "order": 2}),
    ("fig8", {"vec_frac": 12, "root_frac": 12, "t_frac": 14, "coef": 4, "order": 2}),
    ("conventional", {"vec_frac": 12, "rsqrt_addr": 8, "table_addr": 6, "coef": 4}),
])
def test_against_itself_the_float_form_is_computed_once_per_chunk_and_the_same(method, params, monkeypatch):
    from phongfx.explore.compile import run as runs

    spec = parse_scene(TORUS.format(error=1.0, against="self"), name="tiny")
    scene = SceneEval(spec)
    domain = scene_domain(spec, scene.geometries, samples=3000)
    narrower = {**params, "vec_frac": 11}  # another width, the same float form
    configs = [(runs.build(method, p, scene.analysis), p) for p in (params, narrower)]
    sizes = []
    original = runs.own_specular

    def counted(method, config, params, g, n):
        sizes.append(len(g))
        return original(method, config, params, g, n)
    monkeypatch.setattr(runs, "own_specular", counted)
    points = DomainPoints(spec, domain)
    kept = [points.error(method, config, p) for config, p in configs]
    assert sizes.count(3000) == 1  # the chunk's terms once; the local search's points are its own
    monkeypatch.setattr(runs, "own_key", lambda *args: None)  # computed afresh every time
    fresh = DomainPoints(spec, domain)
    assert [fresh.error(method, config, p) for config, p in configs] == kept
    assert sizes.count(3000) == 3 and kept[0]["points"] == 3000


def test_an_infeasible_method_reports_the_best_point_it_tried(monkeypatch):
    from phongfx.explore.compile.search import search_widths

    spec = parse_scene(TORUS.format(error=0.5, against="phong"), name="tiny")

    def searched():
        scene = SceneEval(spec)
        scene.measure_domain(DomainPoints(spec, scene_domain(spec, scene.geometries, samples=3000)))
        return search_widths(scene, "conventional")
    fast = searched()
    monkeypatch.setattr(SceneEval, "passes", lambda self, method, params: meets(self.error(method, params), 0.5))
    whole = searched()  # every point measured whole, as before the measurements stopped early
    # its widest widths, measured only until they failed, are its best: measured whole to say so
    assert fast == whole and not fast["feasible"] and fast["params"] == fast["widest"]["params"] != \
        fast["default"]["params"]


def test_while_a_core_is_idle_a_twin_measures_every_other_chunk_and_nothing_changes(monkeypatch):
    """The last width search, alone, has a core to spare: every other chunk of the sample is
    measured by a forked twin of the process; the numbers, and where a point that fails on the
    domain stops, are those of one process."""
    from phongfx.explore.compile import run as runs
    from phongfx.explore.compile import workers
    from phongfx.explore.compile.workers import Twin
    from phongfx.scene.sampling import CHUNK

    spec = parse_scene(TORUS.format(error=1.0, against="phong"), name="tiny")
    scene = SceneEval(spec)
    domain = scene_domain(spec, scene.geometries, samples=2 * CHUNK + 1000)
    alone, twinned = DomainPoints(spec, domain), DomainPoints(spec, domain)
    assert len(alone.chunks) == 3
    twins = []

    class Counted(Twin):
        def __init__(self, function):
            twins.append(function)
            super().__init__(function)

    monkeypatch.setattr(workers, "Twin", Counted)
    conventional = {"vec_frac": 12, "rsqrt_addr": 8, "table_addr": 6, "coef": 4}
    # measured whole; within a limit; past one in the first chunk (no screen yet: the twin's chunk
    # is not waited for); a point the domain fails, measured whole
    for method, params, limit in (("fig7", PASSING, None), ("fig7", PASSING, (1, 1.4)),
                                  ("conventional", conventional, (0, 0.3)), ("fig7", {**PASSING, "vec_frac": 8}, None)):
        config = runs.build(method, params, scene.analysis)
        monkeypatch.setattr(workers, "spare_core", lambda: False)
        one = alone.error(method, config, params, limit)
        monkeypatch.setattr(workers, "spare_core", lambda: True)
        assert twinned.error(method, config, params, limit) == one
        assert (one is None) == (limit == (0, 0.3))
    assert len(twins) == 4
