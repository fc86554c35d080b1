"""A requirement's limit on a certificate's continuous bound."""

from phongfx.scene.requirement import Requirement


def test_the_bound_limit_is_what_rounds_to_the_required_levels():
    assert Requirement(max_error_levels=1).bound_limit == 1.5
    # floor(B + 1/2) <= 2.7 exactly when B < 2.5
    assert Requirement(max_error_levels=2.7).bound_limit == 2.5
