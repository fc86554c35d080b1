"""Ctrl-C: a real SIGINT to a child ``phongfx``: exit 130, one line, no half-built folder (in the
per-user cache, pointed at the test's folder, or beside an output)."""

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from tests.compiler.test_compile import TORUS


def _interrupted(args, cwd, folder):
    """Run ``python -m phongfx.cli ARGS`` in ``cwd`` with the cache in ``cwd/cache``, SIGINT it
    once its work has begun (a work folder appears in ``cwd/folder``, plus a moment); (code, stderr)."""
    env = dict(os.environ, PHONGFX_CACHE=str(Path(cwd, "cache")))  # an empty cache of its own
    # SIGINT at its default and unblocked in the child: a test worker that inherited it ignored (a sweep's pool
    # worker sets that) would pass it on, and Python then never raises KeyboardInterrupt
    child = subprocess.Popen([sys.executable, "-m", "phongfx.cli", *args], cwd=cwd, env=env,
                             stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                             preexec_fn=lambda: (signal.signal(signal.SIGINT, signal.SIG_DFL),
                                                 signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT})))
    deadline = time.monotonic() + 120
    while not _hidden(Path(cwd) / folder) and child.poll() is None and time.monotonic() < deadline:
        time.sleep(0.05)
    time.sleep(0.5)  # inside the tool run, not at its first line
    assert child.poll() is None, "the command ended before it could be interrupted"
    child.send_signal(signal.SIGINT)
    _, err = child.communicate(timeout=60)
    return child.returncode, err


def _hidden(root):
    """Work folders under ``root``: hidden ones (an output being staged) and cache entries being made."""
    if not Path(root).is_dir():
        return []
    return sorted(str(p) for p in Path(root).rglob("*")
                  if p.is_dir() and (p.name.startswith(".") or ".part-" in p.name))


def test_version():
    done = subprocess.run([sys.executable, "-m", "phongfx.cli", "--version"], capture_output=True, text=True)
    assert done.returncode == 0 and done.stdout.startswith("phongfx ")


@pytest.mark.needs_verilator
def test_ctrl_c_during_a_verilator_build_exits_130_in_one_line_and_leaves_no_temporary_folder(tmp_path):
    # an empty cache: the first Verilator build of lirp takes several seconds
    code, err = _interrupted(["sim", "lirp", "--vectors", "10"], tmp_path, "cache/verilator")
    assert code == 130
    assert err.strip().splitlines() == ["phongfx: interrupted"]
    assert "Traceback" not in err
    assert _hidden(tmp_path) == [] and not (tmp_path / "cache" / "verilator" / "failed").exists()
    assert not (tmp_path / "build").exists()  # no cache in the current folder


@pytest.mark.needs_yosys
def test_ctrl_c_during_synthesis_exits_130_in_one_line_and_leaves_no_temporary_folder(tmp_path):
    # Yosys, then nextpnr, on the shape unit: several seconds
    code, err = _interrupted(["synth", "shape", "--quiet"], tmp_path, "cache/synth")
    assert code == 130
    assert err.strip().splitlines() == ["phongfx: interrupted"]
    assert _hidden(tmp_path) == [] and not (tmp_path / "cache" / "synth" / "failed").exists()
    assert not (tmp_path / "build").exists()


@pytest.mark.needs_verilator
def test_ctrl_c_during_compile_keeps_the_previous_result_whole(tmp_path):
    (tmp_path / "tiny.toml").write_text(TORUS.format(error=1.0, against="phong"))
    out = tmp_path / "out"
    out.mkdir()
    (out / "manifest.json").write_text('{"previous": true}\n')
    # the search takes about a second; then the folder is staged (hidden, beside out) while the
    # frames are drawn and the RTL check's Verilator build runs: the SIGINT lands there
    code, err = _interrupted(["compile", "tiny.toml", "-o", "out", "--methods", "fig7", "--sampled", "--quiet"],
                             tmp_path, ".")
    assert code == 130 and err.strip().splitlines() == ["phongfx: interrupted"]
    assert sorted(p.name for p in out.iterdir()) == ["manifest.json"]
    assert (out / "manifest.json").read_text() == '{"previous": true}\n'
    assert _hidden(tmp_path) == []
