"""A design's identity (phongfx.hdl.identity): equal designs share it, anything that changes the
hardware changes it (the config, the elaboration settings, any byte of the hardware's sources),
and a design whose code does not come from those sources has none."""

import shutil
import sys
import types
from pathlib import Path

from phongfx.core.registry import get_block
from phongfx.hdl import identity
from phongfx.hdl.dsp import dsp_mapping
from phongfx.hdl.handshake import Handshake
from phongfx.hdl.identity import HARDWARE_PACKAGES, design_identity, folder_digest, source_digest
from phongfx.hdl.overflow import overflow_checks


def _of(block, *extra):
    return design_identity(block.component_class, block.config, *extra)


def test_equal_designs_share_it_and_a_changed_field_does_not():
    fig7 = get_block("fig7")
    first = _of(fig7, "top")
    assert len(first) == 64 and int(first, 16) >= 0
    assert _of(get_block("fig7"), "top") == first
    assert _of(get_block("fig7", pipeline=1), "top") != first
    assert _of(get_block("fig8"), "top") != first
    assert _of(fig7, "other") != first
    assert design_identity((Handshake, fig7.component_class), fig7.config) != _of(fig7)


def test_the_elaboration_settings_are_part_of_it():
    shape = get_block("shape")
    plain = _of(shape)
    with overflow_checks(False):
        without = _of(shape)
    with dsp_mapping("ecp5"):
        mapped = _of(shape)
    assert len({plain, without, mapped}) == 3
    assert _of(shape) == plain  # restored on leaving


def test_a_source_edit_changes_it(monkeypatch):
    lirp = get_block("lirp")
    before = _of(lirp)
    monkeypatch.setattr(identity, "source_digest", lambda: "0" * 64)
    assert _of(lirp) != before
    monkeypatch.undo()
    assert _of(lirp) == before


def test_folder_digest_sees_every_byte_and_every_file(tmp_path):
    copy = tmp_path / "hdl"
    shutil.copytree(Path(identity.__file__).parent, copy, ignore=shutil.ignore_patterns("__pycache__"))
    first = folder_digest(copy)
    assert folder_digest(copy) == first
    lirp = copy / "lirp.py"
    text = lirp.read_bytes()
    lirp.write_bytes(text.replace(b"Lirp", b"Lirq", 1))
    edited = folder_digest(copy)
    assert edited != first
    lirp.write_bytes(text)
    assert folder_digest(copy) == first
    (copy / "notes.txt").write_text("not source")  # neither .py nor .v: not hardware
    assert folder_digest(copy) == first
    (copy / "extra.v").write_text("module extra; endmodule\n")
    assert folder_digest(copy) not in (first, edited)


def test_the_source_digest_covers_the_hardware_packages():
    assert HARDWARE_PACKAGES == ("phongfx.core", "phongfx.config", "phongfx.golden", "phongfx.hdl")
    assert len(source_digest()) == 64 and source_digest() == source_digest()


def test_code_from_elsewhere_has_none(monkeypatch):
    lirp = get_block("lirp")

    class Elsewhere(lirp.component_class):
        """A component class defined in a test, outside the hashed sources."""

    assert design_identity(Elsewhere, lirp.config) is None
    # a module of the hardware packages made from source text, as tests add a block
    monkeypatch.setitem(sys.modules, "phongfx.hdl.made_from_text", types.ModuleType("phongfx.hdl.made_from_text"))
    assert _of(lirp) is None
    monkeypatch.undo()
    assert _of(lirp) is not None
