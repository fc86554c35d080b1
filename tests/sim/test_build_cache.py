"""The Verilator build cache (phongfx.sim.build_cache): a known design is keyed without being
elaborated, to the same key as when its RTLIL was hashed; an edit of the hardware's sources keys
it afresh."""

import pytest
from amaranth.back import rtlil

from phongfx.core import cache
from phongfx.core.registry import get_block
from phongfx.hdl import identity
from phongfx.hdl.handshake import Handshake
from phongfx.sim.build_cache import cached_build


@pytest.fixture
def conversions(tmp_path, monkeypatch):
    """A cache of the test's own, forgotten keys, and the list of RTLIL conversions made."""
    monkeypatch.setenv("PHONGFX_CACHE", str(tmp_path / "cache"))
    monkeypatch.setattr(cache, "_KNOWN", {})
    made = []
    convert = rtlil.convert

    def counted(*args, **kwargs):
        made.append(kwargs.get("name"))
        return convert(*args, **kwargs)

    monkeypatch.setattr(rtlil, "convert", counted)
    return made


def _fake_compile(work, source, log):
    (work / "top").write_text("#!/bin/sh\n")
    log.write_text("built\n")


def _build(component, root):
    return cached_build(component, "lirp", "top", "// top\n", _fake_compile, root=root)


def test_a_known_design_is_not_elaborated_to_find_its_build(conversions, tmp_path, monkeypatch):
    root = tmp_path / "builds"
    first = _build(get_block("lirp").component(), root)
    assert first.built and conversions == ["lirp"]  # the key, once (the Verilog is Yosys' own path)
    again = _build(get_block("lirp").component(), root)
    assert not again.built and again.directory == first.directory and conversions == ["lirp"]
    monkeypatch.setattr(cache, "_KNOWN", {})  # a new process reads the key back from the cache
    assert _build(get_block("lirp").component(), root).directory == first.directory
    assert conversions == ["lirp"]
    # the key is the one the RTLIL gives, so builds made before identities existed still serve
    fresh = _build(Handshake(get_block("lirp").component()), root)
    assert fresh.directory != first.directory and conversions == ["lirp", "lirp"]


def test_a_source_edit_keys_the_design_afresh(conversions, tmp_path, monkeypatch):
    root = tmp_path / "builds"
    first = _build(get_block("lirp").component(), root)
    monkeypatch.setattr(identity, "source_digest", lambda: "edited")
    second = _build(get_block("lirp").component(), root)
    # elaborated again (the remembered key is not trusted); the same RTLIL finds the same build
    assert conversions == ["lirp", "lirp"] and second.directory == first.directory and not second.built
    changed = _build(get_block("lirp", pipeline=1).component(), root)
    assert changed.directory != first.directory and changed.built


def test_a_cold_build_writes_its_verilog_from_the_rtlil_its_key_hashed(conversions, tmp_path, monkeypatch):
    # converting a shader to RTLIL is three of the four seconds of its Verilog: a cold build
    # converts it once, for its key, and Yosys writes that text
    from phongfx.hdl.emit import verilog

    fragments, sources = [], []
    convert_fragment = rtlil.convert_fragment

    def counted(*args, **kwargs):
        fragments.append(1)
        return convert_fragment(*args, **kwargs)

    def compile_(work, source, log):
        sources.append(source.read_text())
        _fake_compile(work, source, log)

    monkeypatch.setattr(rtlil, "convert_fragment", counted)
    built = cached_build(get_block("lirp").component(), "lirp", "top", "// top\n", compile_,
                         root=tmp_path / "builds")
    assert built.built and conversions == ["lirp"] and fragments == [1]
    assert sources == [verilog(get_block("lirp").component(), "lirp", emit_src=False) + "// top\n"]


def _wait_for_lock(root, started, done):
    from phongfx.sim.build_cache import runtime_lock

    started.set()
    with runtime_lock(root, False, ("toy",)):
        done.set()


def test_builds_without_run_time_objects_take_turns_and_kept_ones_need_no_turn(tmp_path):
    import multiprocessing
    import time

    from phongfx.sim.build_cache import keep_runtime, runtime_lock

    context = multiprocessing.get_context("fork")
    started, done = context.Event(), context.Event()
    with runtime_lock(tmp_path, False, ("toy",)):
        other = context.Process(target=_wait_for_lock, args=(tmp_path, started, done))
        other.start()
        assert started.wait(10)
        time.sleep(0.3)
        assert not done.is_set()  # the other build waits for this one's objects
    assert done.wait(10)
    other.join(10)
    # once the objects are kept, nobody waits: taken while this process holds the lock
    work = tmp_path / "work"
    work.mkdir()
    (work / "verilated.o").write_bytes(b"object")
    keep_runtime(tmp_path, work, False, ("toy",))
    started.clear()
    done.clear()
    with runtime_lock(tmp_path, False, ("other",)):
        other = context.Process(target=_wait_for_lock, args=(tmp_path, started, done))
        other.start()
        assert done.wait(10)
    other.join(10)
