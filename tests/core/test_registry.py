"""The block registry: records, not tuples; each block's faces found by its name."""

import dataclasses
import importlib
import os
from pathlib import Path

import pytest

from phongfx.core.registry import REGISTRY, Block, Entry, block_names, get_block

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
#: package -> folder of the repository (setuptools package-dir)
FOLDERS = {"phongfx.config": "phongfx/config", "phongfx.golden": "golden", "phongfx.hdl": "hdl",
           "phongfx.sim.stimulus": "sim/stimulus"}


def test_names_and_order():
    assert block_names() == tuple(REGISTRY)
    assert block_names()[:3] == ("lirp", "normalize", "reflect")
    assert block_names()[-4:] == ("fig7", "fig8", "halfway_datapath", "shader")
    assert all(isinstance(entry, Entry) and entry.name == name for name, entry in REGISTRY.items())


@pytest.mark.parametrize("name", list(REGISTRY))
def test_every_face_lives_in_a_file_named_after_the_block(name):
    entry = REGISTRY[name]
    for face in ("config", "golden", "component", "stimulus", "extremes"):
        module, _, attribute = getattr(entry, face).partition(":")
        package, _, leaf = module.rpartition(".")
        assert os.path.isfile(os.path.join(ROOT, FOLDERS[package], f"{leaf}.py")), (face, module)
        assert hasattr(importlib.import_module(module), attribute), (face, getattr(entry, face))
        assert leaf == entry.module
    # the datapaths share one module per folder; every other block has its own name
    assert entry.module == ("datapath" if name in ("fig7", "fig8", "halfway_datapath") else name)


@pytest.mark.parametrize("name", list(REGISTRY))
def test_block_from_the_registry(name):
    block = get_block(name)
    assert isinstance(block, Block) and block.name == name
    assert block.config == REGISTRY[name].default_config()
    assert block.latency >= 1
    raw = block.stimulus(count=4, seed=1)
    assert set(raw) == set(block.config.inputs)
    outputs = block.golden(raw)
    assert set(outputs) == set(block.config.outputs)
    rows = block.extremes()
    assert rows and {row.block for row in rows} == {name}


def test_changes_and_errors():
    assert get_block("shape", k=1).config.k == 1
    assert get_block("shape").config.k == 2
    with pytest.raises(ValueError, match=r"unknown block 'nope'; valid blocks: lirp, normalize, "):
        get_block("nope")
    config = get_block("shape", k=3).config
    assert get_block("shape", config=config, t="1.12").config == config.replace(t="1.12")


def test_a_face_can_be_swapped_for_a_test():
    block = get_block("lirp")

    class Other:
        def __init__(self, config):
            self.config = config

    swapped = dataclasses.replace(block, component_class=Other)
    assert isinstance(swapped.component(), Other) and swapped.config is block.config


def test_every_face_is_written_out_where_it_is_registered():
    """grep follows a block or a method to each of its objects: every path of the two
    registries is a literal string of their source (no path assembled from a name), and
    names an object that exists."""
    from phongfx.core import methods, registry
    from phongfx.core.methods import METHODS

    text = Path(registry.__file__).read_text() + Path(methods.__file__).read_text()
    paths = [getattr(entry, face) for entry in REGISTRY.values()
             for face in ("config", "golden", "component", "stimulus", "extremes")]
    paths += [path for method in METHODS.values() for path in method.faces.values()]
    assert len(paths) == 5 * len(REGISTRY) + sum(len(m.faces) for m in METHODS.values()) > 150
    assert [path for path in paths if f'"{path}"' not in text] == []
    for entry in REGISTRY.values():
        for face in ("config", "golden", "component", "stimulus", "extremes"):
            assert callable(entry.load(face)), (entry.name, face)
    for method in METHODS.values():
        for face in method.faces:
            assert method.load(face) is not None, (method.name, face)
