"""An output folder that cannot be one (under a regular file) fails at once, before the work."""

import time
from pathlib import Path

import pytest

from phongfx.cli import main
from phongfx.core.files import check_folder

SCENE = str(Path(__file__).resolve().parents[2] / "scenes" / "torus.toml")


@pytest.mark.parametrize("argv", [
    ["compile", SCENE, "-o", "{file}/out", "--quiet"],
    ["compile", SCENE, "-o", "{file}", "--quiet"],
    ["render", "--out", "{file}/sim", "--quiet"],
    ["render", "mesh", "--out", "{file}/mesh"],
    ["render", "frames", "--out", "{file}/frames", "--quiet"],
])
def test_a_bad_output_folder_fails_before_the_work(tmp_path, capsys, argv):
    blocker = tmp_path / "a-file"
    blocker.write_text("not a folder\n")
    start = time.perf_counter()
    assert main([part.replace("{file}", str(blocker)) for part in argv]) == 2
    assert time.perf_counter() - start < 3  # the compile itself takes 10–15 s, a render longer
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("phongfx: error: ") and err[0].endswith("a regular file: Not a directory")
    assert blocker.read_text() == "not a folder\n" and list(tmp_path.iterdir()) == [blocker]


def test_check_folder(tmp_path):
    assert check_folder(tmp_path / "new" / "deeper") == str(tmp_path / "new" / "deeper")
    (tmp_path / "f").write_text("")
    with pytest.raises(NotADirectoryError, match=r"the output folder is under .*f, a regular file: Not a directory"):
        check_folder(tmp_path / "f" / "x")
