"""A compile request: the scene and every option, each checked where it is made, its error
naming the field, the value and what it may be."""

import pytest

from phongfx.compiler.request import CompileRequest
from phongfx.scene.file import parse_scene
from tests.compiler.test_compile import TORUS


def _tiny():
    return parse_scene(TORUS.format(error=1.0, against="phong"), name="tiny.toml")


@pytest.mark.parametrize("field, value, allowed", [
    ("certify", "yes", r"one of none, chosen, search"), ("target", "xc7", r"one of ecp5, ice40, asic"),
    ("method", "phong", r"one of fig7, .*, conventional"), ("samples", 0, r"a positive integer"),
    ("final_samples", 2.5, r"a positive integer"), ("workers", 0, r"a positive integer"),
    ("freq", -1, r"a number of MHz in \(0, 10000\]"), ("prove_timeout", 0, r"a number of seconds in \(0, inf\]"),
    ("seed", "1", r"an integer"), ("clock", 1e6, r"a number of MHz in \(0, 10000\]")])
def test_a_request_names_the_field_the_value_and_what_it_may_be(field, value, allowed):
    options = {"methods": [value]} if field == "method" else {field: value}
    with pytest.raises(ValueError, match=rf"^{field} must be {allowed}, not {value!r}$"):
        CompileRequest(_tiny(), **options)
