"""Outputs written whole: a staged folder replaces its place only when complete."""

import os

import pytest

from phongfx.core.files import staged_folder


def _tree(root):
    return sorted(os.path.relpath(os.path.join(d, f), root) for d, _, files in os.walk(root) for f in files)


def test_a_completed_folder_replaces_the_previous_one_whole(tmp_path):
    out = tmp_path / "out"
    (out / "frames").mkdir(parents=True)
    (out / "frames" / "old.png").write_text("old")
    with staged_folder(out) as work:
        assert os.path.dirname(work) == str(tmp_path) and os.path.basename(work).startswith(".out.")
        assert not os.path.exists(os.path.join(work, "frames"))
        open(os.path.join(work, "manifest.json"), "w").write("{}")
    assert _tree(out) == ["manifest.json"]
    assert sorted(os.listdir(tmp_path)) == ["out"]


@pytest.mark.parametrize("failure", [RuntimeError("tool failed"), KeyboardInterrupt()])
def test_a_failed_run_leaves_the_previous_folder_and_no_trace(tmp_path, failure):
    out = tmp_path / "out"
    out.mkdir()
    (out / "manifest.json").write_text("previous")
    with pytest.raises(type(failure)):
        with staged_folder(out) as work:
            open(os.path.join(work, "half.png"), "w").write("half")
            raise failure
    assert _tree(out) == ["manifest.json"] and (out / "manifest.json").read_text() == "previous"
    assert sorted(os.listdir(tmp_path)) == ["out"]


def test_a_new_folder_appears_only_when_complete(tmp_path):
    out = tmp_path / "a" / "out"
    with staged_folder(out) as work:
        assert not out.exists()
        open(os.path.join(work, "x"), "w").write("x")
    assert _tree(out) == ["x"]


def test_a_regular_file_in_the_way_fails_before_any_work(tmp_path):
    (tmp_path / "file").write_text("")
    with pytest.raises(NotADirectoryError, match="is under .*file, a regular file"):
        with staged_folder(tmp_path / "file" / "out"):
            pytest.fail("the body ran")
