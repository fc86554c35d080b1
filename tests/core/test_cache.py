"""The per-user cache: where it is, entries made whole or not at all, ``phongfx cache``."""

import platformdirs
import pytest

from phongfx.cli import main
from phongfx.core import cache
from phongfx.core.cache import clear, folder, make_entry, root, usage


@pytest.fixture
def home(tmp_path, monkeypatch):
    """A cache of the test's own."""
    monkeypatch.setenv("PHONGFX_CACHE", str(tmp_path / "cache"))
    return tmp_path / "cache"


def test_the_folder_is_the_environment_variable_else_the_platforms(home, monkeypatch):
    assert root() == home.resolve() and folder("verilator") == home.resolve() / "verilator"
    monkeypatch.delenv("PHONGFX_CACHE")
    assert str(root()) == platformdirs.user_cache_dir("phongfx", appauthor=False)
    with pytest.raises(ValueError, match="^tool must be one of verilator, synth, sta, prove, compile, proxy, keys, not 'x'$"):
        folder("x")


def _writer(text, calls):
    def make(work):
        calls.append(work)
        (work / "out.txt").write_text(text)
        (work / "done").write_text("")
        return len(text)
    return make


def test_an_entry_is_made_once_then_read_back(home):
    calls = []
    entry, value = make_entry(folder("synth"), "k1", "done", _writer("abc", calls))
    assert value == 3 and entry == folder("synth") / "k1" and (entry / "out.txt").read_text() == "abc"
    again, value = make_entry(folder("synth"), "k1", "done", _writer("other", calls))
    assert again == entry and value is None and len(calls) == 1 and (entry / "out.txt").read_text() == "abc"
    assert [p.name for p in folder("synth").iterdir()] == ["k1"]  # no run folder left


def test_a_failed_run_is_kept_visibly_with_its_logs_and_the_error_points_there(home):
    def fails(work):
        (work / "tool.log").write_text("it broke\n")
        raise RuntimeError(f"tool failed; log {work / 'tool.log'}")

    with pytest.raises(RuntimeError) as error:
        make_entry(folder("synth"), "k2", "done", fails)
    failed = folder("synth") / "failed" / "k2"
    assert str(error.value) == f"tool failed; log {failed / 'tool.log'}"
    assert (failed / "tool.log").read_text() == "it broke\n"
    assert sorted(p.name for p in folder("synth").iterdir()) == ["failed"]  # no entry, no hidden folder
    # a run that returns without its completion file is not kept (a time-out, say)
    assert make_entry(folder("synth"), "k3", "done", lambda work: "late") == (None, "late")
    assert sorted(p.name for p in folder("synth").iterdir()) == ["failed"]


def test_an_interrupted_run_leaves_nothing(home):
    def interrupted(work):
        (work / "half").write_text("")
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        make_entry(folder("prove"), "k4", "done", interrupted)
    assert list(folder("prove").iterdir()) == []


def test_usage_counts_entries_and_bytes_per_tool_and_clear_empties(home):
    make_entry(folder("synth"), "a", "done", _writer("x" * 100, []))
    make_entry(folder("synth"), "b", "done", _writer("y" * 50, []))
    make_entry(folder("verilator"), "c", "done", _writer("z" * 10, []))
    assert usage() == [("verilator", 1, 10), ("synth", 2, 150)]
    assert clear() == 160 and usage() == [] and home.is_dir()
    assert clear() == 0


def test_cli_info_and_clear(home, capsys):
    make_entry(folder("sta"), "a", "done", _writer("x" * 2500, []))
    assert main(["cache", "--info"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0] == f"{home.resolve()}  (set PHONGFX_CACHE to move it)"
    assert lines[1].split() == ["sta", "1", "entries", "2.5", "kB"]
    assert lines[2].split() == ["total", "1", "entries", "2.5", "kB"]
    assert main(["cache"]) == 0 and capsys.readouterr().out.splitlines() == lines  # --info is the default
    assert main(["cache", "--clear"]) == 0
    assert capsys.readouterr().out == f"cleared {home.resolve()} (2.5 kB freed)\n"
    assert not (home / "sta").exists()
    assert main(["cache", "--info", "--clear"]) == 2  # one or the other


def test_size_text():
    from phongfx.cli.cache import size_text

    assert [size_text(n) for n in (0, 999, 1000, 123_456_789, 5 * 10**12)] == [
        "0 B", "999 B", "1.0 kB", "123.5 MB", "5000.0 GB"]
    assert cache.TOOLS == ("verilator", "synth", "sta", "prove", "compile", "proxy", "keys")


def test_a_remembered_key_is_made_once_per_identity_then_read_back(home, monkeypatch):
    from phongfx.core.cache import remembered_key

    calls = []

    def make(key):
        return lambda: calls.append(key) or key

    assert remembered_key(["design A", "flow 1"], make("k-a")) == "k-a"
    assert remembered_key(["design A", "flow 1"], make("other")) == "k-a" and calls == ["k-a"]
    (record,) = folder("keys").iterdir()
    assert record.read_text() == "k-a\n" and len(record.name) == 32
    monkeypatch.setattr(cache, "_KNOWN", {})  # a new process: read back from the file
    assert remembered_key(["design A", "flow 1"], make("other")) == "k-a" and calls == ["k-a"]
    # another identity (an edited source, another flow) is keyed afresh; None is never remembered
    assert remembered_key(["design A", "flow 2"], make("k-b")) == "k-b"
    assert remembered_key(None, make("k-c")) == "k-c" and remembered_key(None, make("k-d")) == "k-d"
    assert calls == ["k-a", "k-b", "k-c", "k-d"] and len(list(folder("keys").iterdir())) == 2
