"""Ctrl-C: a real SIGINT to a child ``phongfx``: exit 130, one line, no half-built folder."""

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from tests.explore.compile.test_compiler import TORUS


def _interrupted(args, cwd, folder):
    """Run ``python -m phongfx.cli ARGS`` in ``cwd``, SIGINT it once its work has begun (a hidden
    work folder appears in ``cwd/folder``, plus a moment); (code, stderr)."""
    env = {k: v for k, v in os.environ.items() if k != "PHONGFX_BUILD"}  # the cache under cwd/build
    child = subprocess.Popen([sys.executable, "-m", "phongfx.cli", *args], cwd=cwd, env=env,
                             stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 120
    while not _hidden(Path(cwd) / folder) and child.poll() is None and time.monotonic() < deadline:
        time.sleep(0.05)
    time.sleep(0.5)  # inside the tool run, not at its first line
    assert child.poll() is None, "the command ended before it could be interrupted"
    child.send_signal(signal.SIGINT)
    _, err = child.communicate(timeout=60)
    return child.returncode, err


def _hidden(root):
    return sorted(str(p) for p in Path(root).rglob(".*") if p.is_dir()) if Path(root).is_dir() else []


def test_version():
    done = subprocess.run([sys.executable, "-m", "phongfx.cli", "--version"], capture_output=True, text=True)
    assert done.returncode == 0 and done.stdout.startswith("phongfx ")


@pytest.mark.verilator
def test_ctrl_c_during_a_verilator_build_exits_130_in_one_line_and_leaves_no_temporary_folder(tmp_path):
    # an empty cache: the first Verilator build of lirp takes several seconds
    code, err = _interrupted(["sim", "lirp", "--vectors", "10"], tmp_path, "build/verilator")
    assert code == 130
    assert err.strip().splitlines() == ["phongfx: interrupted"]
    assert "Traceback" not in err
    assert _hidden(tmp_path / "build") == []


def test_ctrl_c_during_synthesis_exits_130_in_one_line_and_leaves_no_temporary_folder(tmp_path):
    # Yosys, then nextpnr, on the shape unit: several seconds
    code, err = _interrupted(["synth", "shape", "--quiet"], tmp_path, "build/synth")
    assert code == 130
    assert err.strip().splitlines() == ["phongfx: interrupted"]
    assert _hidden(tmp_path / "build") == []




@pytest.mark.verilator
def test_ctrl_c_during_compile_keeps_the_previous_result_whole(tmp_path):
    (tmp_path / "tiny.toml").write_text(TORUS.format(error=1.0, against="phong"))
    out = tmp_path / "out"
    out.mkdir()
    (out / "manifest.json").write_text('{"previous": true}\n')
    # the search takes about a second; then the folder is staged (hidden, beside out) while the
    # frames are drawn and the RTL check's Verilator build runs: the SIGINT lands there
    code, err = _interrupted(["compile", "tiny.toml", "-o", "out", "--methods", "fig7", "--quiet"], tmp_path, ".")
    assert code == 130 and err.strip().splitlines() == ["phongfx: interrupted"]
    assert sorted(p.name for p in out.iterdir()) == ["manifest.json"]
    assert (out / "manifest.json").read_text() == '{"previous": true}\n'
    assert _hidden(tmp_path) == []
