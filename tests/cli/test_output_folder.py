"""An output folder that cannot be one (under a regular file) fails at once, before the work."""

import os
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


def _unwritable(tmp_path):
    """A folder this process cannot write into: a read-only one, or for root (whom
    permissions do not stop) /sys, which no one can make folders in."""
    if os.geteuid() != 0:
        locked = tmp_path / "locked"
        locked.mkdir(mode=0o555)
        return locked
    if not os.path.isdir("/sys"):
        pytest.skip("running as root without /sys: no folder to fail writing into")
    return Path("/sys")


@pytest.mark.parametrize("argv", [
    ["compile", SCENE, "-o", "{dir}/out", "--quiet"],
    ["compile", SCENE, "-o", "{dir}/new/out", "--quiet"],
    ["render", "--out", "{dir}/sim", "--quiet"],
])
def test_an_unwritable_output_folder_fails_before_the_work(tmp_path, capsys, argv):
    locked = _unwritable(tmp_path)
    argv = [part.replace("{dir}", str(locked)) for part in argv]
    out = next(part for part in argv if part.startswith(str(locked)))
    start = time.perf_counter()
    assert main(argv) == 2
    assert time.perf_counter() - start < 3  # the compile itself takes 10–46 s
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"phongfx: error: {out}: the output folder cannot be written: "
                                               f"{locked} is not writable (")
    assert not os.path.exists(out) and not [p for p in os.listdir(locked) if p.startswith(".phongfx")]
