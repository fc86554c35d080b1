import contextvars

import pytest

from phongfx.hdl.context import scoped

SETTING = contextvars.ContextVar("test_setting", default="outside")


def test_a_setting_holds_inside_and_is_restored_even_on_an_error():
    with scoped(SETTING, "inside") as value:
        assert value == "inside" and SETTING.get() == "inside"
        with scoped(SETTING, "deeper"):
            assert SETTING.get() == "deeper"
        assert SETTING.get() == "inside"
    with pytest.raises(RuntimeError):
        with scoped(SETTING, "failing"):
            raise RuntimeError
    assert SETTING.get() == "outside"
