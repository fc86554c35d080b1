"""Amounts in words (phongfx.core.words): "1 level", never "1 levels"."""

import math

from phongfx.core.words import levels, plural


def test_one_level_is_singular_and_the_rest_plural():
    assert levels(1) == "1 level" and levels(1.0) == "1 level" and levels(2) == "2 levels"
    assert levels(0) == "0 levels" and levels(0.5) == "0.5 levels" and levels(math.inf) == "inf levels"
    assert levels(1, ".3f") == "1.000 levels" and plural(3, "frame") == "3 frames"
