"""The choice among searched methods: the witness must meet the requirement, and with
``certified`` a certificate too (a fake certifier here, so that the rule is tested apart from
any bounding method; :mod:`tests.certify` tests the real ones)."""

import pytest

from phongfx.certify.certificate import Certificate
from phongfx.explore.compile.compiler import compile_scene
from phongfx.scene.file import parse_scene

from .test_compiler import TORUS


def _tiny():
    return parse_scene(TORUS.format(error=1.0, against="phong"), name="tiny.toml")


class Fake:
    """Certifies fig7 where every width is at least ``floor``'s (bound 1.2, else 3.0): a bound
    that holds where the sampled choice's witness did; no bound for the other methods."""

    def __init__(self, floor):
        self.floor, self.calls = floor, []

    def __call__(self, method, params, spec, domain, early=False, analysis=None):
        self.calls.append((method, dict(params), early))
        if method != "fig7":
            return Certificate(False, None, "fake", why=f"no bounding method for the {method} unit yet")
        bound = 1.2 if all(params[k] >= v for k, v in self.floor.items()) else 3.0
        return Certificate(bound < 1.5, bound, "fake")


def test_the_chosen_designs_certificate_is_kept_without_changing_the_choice():
    fake = Fake(floor={"vec_frac": 99})
    out = compile_scene(_tiny(), methods=["fig7", "conventional"], certifier=fake)
    assert out.certificate is not None and out.certainty is None
    assert fake.calls == [(out.chosen, out.best["params"], False)]


def test_certified_widens_until_the_certificate_meets_and_says_what_it_cost():
    sampled = compile_scene(_tiny(), methods=["fig7"])
    floor = {**sampled.best["params"], "vec_frac": sampled.best["params"]["vec_frac"] + 1}
    out = compile_scene(_tiny(), methods=["fig7"], certifier=Fake(floor), certified=True)
    assert out.chosen == "fig7" and out.certificate.certified and out.certificate.bound_levels == 1.2
    assert out.best["params"] == floor  # the cheapest certified widths
    assert out.certainty["sampled"]["params"] == sampled.best["params"]
    assert out.certainty["sampled"]["certificate"]["bound_levels"] == 3.0
    extra = out.best["cost"]["cost"] / sampled.best["cost"]["cost"] - 1
    assert out.certainty["extra_cost"] == pytest.approx(extra) and extra > 0
    assert out.witness["error_levels"] <= 1.0


def test_certified_without_any_certifiable_method_chooses_nothing_and_says_why():
    out = compile_scene(_tiny(), methods=["conventional"], certifier=Fake({}), certified=True)
    assert out.chosen is None
    assert out.certainty["why"] == "no method has a certified design within the requirement"
    assert out.certainty["methods"]["conventional"] == {
        "certified": False, "why": "no bounding method for the conventional unit yet"}
