"""The package's own entry points: a few names, each the object of its home module."""

import pytest

import phongfx
from phongfx.config import DatapathConfig, fig7_config, fig8_config, halfway_config
from phongfx.core.format import Format
from phongfx.core.registry import block_names, get_block
from phongfx.deliver.component import load_core


def test_entry_points_are_the_homes_objects():
    assert sorted(phongfx.__all__) == sorted(["Format", "get_block", "block_names", "DatapathConfig",
                                              "fig7_config", "fig8_config", "halfway_config", "load_core"])
    homes = {"Format": Format, "get_block": get_block, "block_names": block_names,
             "DatapathConfig": DatapathConfig, "fig7_config": fig7_config, "fig8_config": fig8_config,
             "halfway_config": halfway_config, "load_core": load_core}
    for name in phongfx.__all__:
        assert getattr(phongfx, name) is homes[name]
    assert phongfx.get_block("fig7").config == phongfx.fig7_config()


def test_an_unknown_name_is_an_attribute_error():
    with pytest.raises(AttributeError, match=r"module 'phongfx' has no attribute 'nope'"):
        phongfx.nope
