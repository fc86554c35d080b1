"""The choice among searched methods: the witness must meet the requirement, and with
``certify="search"`` a certificate too (a fake in place of :func:`phongfx.certify.certify` here,
so that the rule is tested apart from any bounding method; :mod:`tests.certify` tests the real
ones)."""

from phongfx.certify.certificate import Certificate
from phongfx.compiler import compile as compiling
from phongfx.compiler.compile import certifier_of, compile_scene
from phongfx.compiler.request import CompileRequest
from phongfx.explore.compile.certified import uncertifiable
from phongfx.scene.file import parse_scene

from tests.compiler.test_compile import TORUS


def _tiny():
    return parse_scene(TORUS.format(error=1.0, against="phong"), name="tiny.toml")


class Fake:
    """Certifies fig7 where every width is at least ``floor``'s (bound 1.2, else 3.0): a bound
    that holds where the sampled choice's witness did; no bound for the other methods."""

    def __init__(self, floor):
        self.floor, self.calls = floor, []

    def __call__(self, method, params, spec, domain, early=False, analysis=None, max_boxes=300_000):
        if max_boxes:  # not the probe of whether the method is bounded at all
            self.calls.append((method, dict(params), early))
        if method != "fig7":
            return Certificate(False, None, "fake", why=f"no bounding method for the {method} unit yet")
        bound = 1.2 if all(params[k] >= v for k, v in self.floor.items()) else 3.0
        return Certificate(bound < 1.5, bound, "fake")


def _certified_by(monkeypatch, fake):
    """The compiler's certificates given by ``fake``."""
    monkeypatch.setattr(compiling, "certify", fake)
    return fake


def test_the_compilers_certifier_is_phongfx_certify_kept_where_the_request_says(tmp_path):
    from phongfx.certify import certify

    assert certifier_of(CompileRequest(_tiny())) is None
    assert certifier_of(CompileRequest(_tiny(), certify="search")) is certify
    assert certifier_of(CompileRequest(_tiny(), certify="chosen", certificates=tmp_path)).__qualname__ == (
        "remembering.<locals>.certifier")


def test_the_chosen_designs_certificate_is_kept_without_changing_the_choice(monkeypatch):
    fake = _certified_by(monkeypatch, Fake(floor={"vec_frac": 99}))
    out = compile_scene(CompileRequest(_tiny(), methods=["fig7", "conventional"], certify="chosen"))
    assert out.certificate is not None and not out.certified and "conventional" in out.results
    assert fake.calls == [(out.chosen, out.best["params"], False)]


def test_certified_searches_each_method_once_and_ships_the_certificate_its_search_passed_it_by(monkeypatch):
    sampled = compile_scene(CompileRequest(_tiny(), methods=["fig7"]))
    floor = {**sampled.best["params"], "vec_frac": sampled.best["params"]["vec_frac"] + 1}
    fake = _certified_by(monkeypatch, Fake(floor))
    out = compile_scene(CompileRequest(_tiny(), methods=["fig7"], certify="search"))
    assert out.chosen == "fig7" and out.certified and out.certificate.certified
    assert out.certificate.bound_levels == 1.2
    assert out.best["params"] == floor  # the cheapest certified widths
    assert out.best["certificate"]["bound_levels"] == 1.2 and out.best["certificate"]["certified"]
    assert [call for call in fake.calls if not call[2]] == []  # no certificate refined to the end
    assert out.certificate.as_dict() == {k: v for k, v in out.best["certificate"].items() if k != "refined"}
    assert out.best["certificate"]["refined"].startswith("until it met the requirement")
    early = [tuple(sorted(p.items())) for m, p, e in fake.calls if e]
    assert len(early) == len(set(early))  # each width point's certificate asked once
    assert out.witness["error_levels"] <= 1.0 and not out.rounds and out.refused is None


def test_certified_rejects_an_uncertifiable_method_unsearched_and_refuses_with_each_reason(monkeypatch):
    fake = _certified_by(monkeypatch, Fake({"vec_frac": 99}))
    out = compile_scene(CompileRequest(_tiny(), methods=["conventional", "fig7"], certify="search"))
    assert out.chosen is None and out.results["fig7"]["feasible"] is False
    assert "conventional" not in out.results  # not searched at all
    assert out.rejected["conventional"] == "not certifiable: no bounding method for the conventional unit yet"
    why = out.results["fig7"]["why"][-1]
    lead = ("no width point is certified within the requirement; the lowest bound found is "
            "3.000 levels at ")
    assert why.startswith(lead) and why[len(lead):] == str(fake.calls[0][1])  # all 3.0: the first asked
    refused = out.refused
    assert refused["why"] == "certificate" and out.hint is None
    assert refused["text"][0] == "no design of tiny is certified within 1 level against phong:"
    assert refused["text"][1] == "  conventional: not certifiable: no bounding method for the conventional unit yet"
    assert refused["text"][2].startswith("  fig7: no width point is certified within")
    assert refused["text"][-1] == ("--sampled chooses by the measured error alone (certified: false): "
                                   "phongfx compile tiny.toml -o DIR --sampled")


def test_a_certificate_without_a_bound_only_for_an_overflow_does_not_make_a_method_uncertifiable():
    assert uncertifiable(Certificate(False, None, "interval", why="no bounding method for the x unit yet")) == (
        "no bounding method for the x unit yet")
    assert uncertifiable(Certificate(False, None, "interval", {"faults": ["x2"]}, "x2 may overflow")) is None
    assert uncertifiable(Certificate(False, 3.0, "interval", why="the bound 3.000 levels rounds to 3")) is None


def test_only_a_sampled_choice_has_a_quick_witness_search_first(monkeypatch):
    """The local search from the width search's own worst points spares a fresh sample when it
    misses the requirement; a certified design's witness cannot miss, so there it is not run."""
    from phongfx.explore.compile import witness

    quick, explore = [], witness.explore

    def counted(*args, starts=None, **options):
        quick.append(starts is not None)
        return explore(*args, starts=starts, **options)

    monkeypatch.setattr(witness, "explore", counted)
    sampled = compile_scene(CompileRequest(_tiny(), methods=["fig7"]))
    assert quick[:2] == [True, False]  # each fresh sample after a quick search that did not miss
    floor = {**sampled.best["params"], "vec_frac": sampled.best["params"]["vec_frac"] + 1}
    del quick[:]
    _certified_by(monkeypatch, Fake(floor))
    out = compile_scene(CompileRequest(_tiny(), methods=["fig7"], certify="search"))
    assert out.certified and quick == [False]
