"""The certified search's test of a width point: the cheap measured screen, then the certificate,
asked once per point, its regions first once an earlier one needed them; and what the proof of
minimality says of a point it failed (no whole-sample measurement)."""

from types import SimpleNamespace

from phongfx.certify.certificate import Certificate
from phongfx.explore.compile.certified import CertifiedTest
from phongfx.scene.requirement import Requirement


class Screen:
    """A scene whose cheap measured test fails the points with ``vec_frac`` under ``floor``."""

    def __init__(self, floor):
        self.floor, self.asked = floor, []
        self.spec, self.analysis = SimpleNamespace(name="s", requirement=Requirement()), None

    def fails_screen(self, method, params):
        self.asked.append(dict(params))
        return params["vec_frac"] < self.floor


def _certifier(calls, needs_regions_under):
    def certifier(method, params, spec, domain, *, early, analysis, regions_first=False):
        calls.append((params["vec_frac"], regions_first))
        regions = params["vec_frac"] < needs_regions_under
        bound = 1.2 if params["vec_frac"] >= 10 else 2.4
        parts = {"regions": [], "whole_bound": 1.7} if regions else {}
        why = "" if bound < 1.5 else "the bound 2.400 levels rounds to 2, over the required 1"
        return Certificate(bound < 1.5, bound, "fake", parts, why)
    return certifier


def test_the_certificate_is_asked_only_past_the_screen_once_per_point_and_regions_first_once_needed():
    calls, scene = [], Screen(floor=8)
    test = CertifiedTest(scene, "fig7", None, _certifier(calls, needs_regions_under=13))
    assert test({"vec_frac": 14}) and test({"vec_frac": 12}) and not test({"vec_frac": 9})
    assert not test({"vec_frac": 7}) and test({"vec_frac": 12})  # 7: the screen alone; 12 again: kept
    # 14 needed no regions, 12 passed by them: from then on the regions first
    assert calls == [(14, False), (12, False), (9, True)]


def test_a_failing_point_that_needed_the_regions_does_not_put_them_first():
    calls = []
    test = CertifiedTest(Screen(floor=8), "fig7", None, _certifier(calls, needs_regions_under=10))
    assert not test({"vec_frac": 9}) and test({"vec_frac": 11}) and test({"vec_frac": 10})
    assert calls == [(9, False), (11, False), (10, False)]


def test_a_failed_point_is_explained_by_its_screen_or_its_certificate():
    calls, scene = [], Screen(floor=8)
    test = CertifiedTest(scene, "fig7", None, _certifier(calls, needs_regions_under=0))
    assert test.failure({"vec_frac": 7}) == {
        "why": "measured past the requirement (on its frames or the worst points measured before)"}
    assert test.failure({"vec_frac": 9}) == {
        "bound_levels": 2.4,
        "why": "its certificate misses the requirement: the bound 2.400 levels rounds to 2, over the required 1"}
    assert calls == [(9, False)]


def test_a_passed_points_margin_is_how_far_its_bound_stayed_under_the_limit():
    calls = []
    test = CertifiedTest(Screen(floor=8), "fig7", None, _certifier(calls, needs_regions_under=0))
    assert test({"vec_frac": 12}) and not test({"vec_frac": 9})
    # 1.2 under the limit 1.5 of a 1-level requirement; none for a failed or an unasked point
    assert abs(test.margin({"vec_frac": 12}) - 0.3) < 1e-12
    assert test.margin({"vec_frac": 9}) is None and test.margin({"vec_frac": 13}) is None
    assert calls == [(12, False), (9, False)]  # the margins asked no certificate

