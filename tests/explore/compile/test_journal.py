"""A rerun of the same scene resumes from the journal of measured width points."""

from phongfx.compiler.compile import compile_scene
from phongfx.compiler.request import CompileRequest
from phongfx.explore.compile import measure
from phongfx.explore.compile.journal import Journal, scene_key
from phongfx.explore.compile.measure import SceneEval
from phongfx.scene.file import parse_scene
from tests.explore.compile.test_costing import TORUS


def _counting(monkeypatch):
    calls = []
    original = SceneEval._error

    def counted(self, method, params, *args, **kwargs):
        calls.append((method, params))
        return original(self, method, params, *args, **kwargs)
    monkeypatch.setattr(measure.SceneEval, "_error", counted)
    return calls


def test_a_rerun_measures_nothing_again(tmp_path, monkeypatch):
    calls = _counting(monkeypatch)
    spec = parse_scene(TORUS, name="tiny")
    first = compile_scene(CompileRequest(spec, methods=["fig7"], journal=tmp_path))
    measured = len(calls)
    assert measured > 5 and first.scene.resumed == 0
    second = compile_scene(CompileRequest(spec, methods=["fig7"], journal=tmp_path))
    # a point first measured until it failed and later whole is measured twice but journalled once
    assert measured >= first.scene.points_measured > 5
    assert len(calls) == measured and second.scene.resumed == first.scene.points_measured
    assert second.best["params"] == first.best["params"] and second.best["max"] == first.best["max"]


def test_an_interrupted_journal_resumes_its_complete_lines(tmp_path, monkeypatch):
    spec = parse_scene(TORUS, name="tiny")
    scene = SceneEval(spec, journal=tmp_path)
    scene.error("fig7", {"k": 4})
    path = Journal(tmp_path, scene_key(spec, scene.geometries)).path
    with open(path, "a") as file:
        file.write('["fig7", [["k", 3]], {"max"')  # torn by a kill
    again = SceneEval(spec, journal=tmp_path)
    assert list(again.cache) == [("fig7", (("k", 4),))]
    again.error("fig7", {"k": 2})  # appended on a line of its own
    assert len(SceneEval(spec, journal=tmp_path).cache) == 2


def test_another_scene_does_not_reuse_the_journal(tmp_path):
    a = SceneEval(parse_scene(TORUS, name="tiny"))
    b = SceneEval(parse_scene(TORUS.replace("n = 16", "n = 17"), name="tiny"))
    assert scene_key(a.spec, a.geometries) != scene_key(b.spec, b.geometries)
