"""No generated comment reads as a tool's pragma, whatever the module's name.

The exported testbench's header and the top's header are wrapped comments; with module
names of 20 to 24 characters a line of the testbench's began ``// Verilator (--binary)``,
which Verilator took for its own directive (``%Error-BADVLTPRAGMA``).  Every name length
from 1 to 80 is checked here under Verilator itself (two families of names, 160 in one file
and one Verilator run), and every comment line against the words other tools
read (:data:`phongfx.hdl.comment.PRAGMA_WORDS`); and a testbench exported for a 22-character
name passes under both simulators and lints clean with its top (``-Wall``)."""

import re
import subprocess

import pytest

from phongfx.core.registry import get_block
from phongfx.hdl.comment import starts_pragma
from phongfx.hdl.top import header, port_map
from phongfx.sim.verilator_backend import tool_environment
from phongfx.sim import testbench as tb
from phongfx.sim.verilog_tb import verilog_testbench
from tests.sim.test_testbench import check_pass, vectors

LENGTHS = range(1, 81)
#: Plain names, and names that begin with a pragma word themselves (``verilator_...``).
FAMILIES = ("two_lights_conventional_", "verilator_synthesis_")


def names():
    return [(family * 8)[:length] for family in FAMILIES for length in LENGTHS]


def bits(width):
    return "" if width == 1 else f"[{width - 1}:0] "


def stub_top(ports, name):
    """The top's header above a module with its ports and no body: what the testbench
    instantiates, without building 160 tops."""
    declarations = ", ".join(f"{port['direction']} {bits(port['width'])}{port['name']}" for port in ports)
    return f"module {name}_top({declarations});\nendmodule\n"


def text(name, config, latency=3, body=True):
    """The top's header and the testbench of a top called ``name``; ``body=False`` keeps only
    the testbench's header, above an empty module."""
    ports = port_map(config)
    timing = {"clock_mhz": 100.0, "clock_source": "proxied: ecp5-clock-proxy", "requirement_mpx": 50.0}
    bench = verilog_testbench(config, name, 10, latency, reset_at=5)
    if not body:
        bench = bench[:bench.index(f"module tb_{name};")] + f"module tb_{name};\nendmodule\n"
    return header(ports, name, latency, 1, timing) + stub_top(ports, name) + bench


def comment_lines(source):
    return [line.split("//", 1)[1] for line in source.splitlines() if "//" in line]


def test_no_comment_line_starts_a_pragma():
    config = get_block("lirp").config
    for name in names():
        for line in comment_lines(text(name, config)):
            assert not starts_pragma(line), (name, line)


@pytest.mark.needs_verilator
def test_verilator_takes_every_name_length(tmp_path):
    config = get_block("lirp").config
    path = tmp_path / "all.v"
    # whole testbenches for the first family; the second's headers only, to keep the run short
    path.write_text("".join(text(name, config, body=name.startswith(FAMILIES[0][0])) for name in names()))
    verilator = tool_environment()
    # errors only: the stub tops are empty, and each testbench is a top of its own
    lint = subprocess.run([str(verilator), "--lint-only", "-Wno-fatal", "-Wno-lint", "-Wno-style", "-Wno-MULTITOP",
                           "-Wno-PINMISSING", str(path)], capture_output=True, text=True, timeout=120)
    assert lint.returncode == 0 and "%Error" not in lint.stderr, lint.stderr[-3000:]
    assert "BADVLTPRAGMA" not in lint.stderr
    # the word that used to start a line is there, in each testbench and each top header
    assert len(re.findall(r"\bVerilator\b", path.read_text())) == 2 * len(names())


#: A ``<scene>_<method>`` name of 22 characters: the testbench's header put ``Verilator
#: (--binary)`` first on a line for it.
NAME_22 = "two_lights_blinn_phong"


@pytest.mark.needs_verilator
@pytest.mark.needs_iverilog
def test_a_22_character_top_passes_under_verilator_and_icarus(tmp_path):
    assert len(NAME_22) == 22
    block, inputs, expected = vectors("lirp", limit=24)
    bench = tb.write_testbench(block, inputs, expected, tmp_path / NAME_22, NAME_22)
    cycles = check_pass(bench, *tb.run_verilator(bench.directory, NAME_22))
    assert check_pass(bench, *tb.run_icarus(bench.directory, NAME_22)) == cycles
    # and the testbench with the top lints clean under both (-Wall)
    files = [str(bench.directory / f"tb_{NAME_22}.v"), str(bench.directory / f"{NAME_22}_top.v")]
    lint = subprocess.run([str(tool_environment()), "--lint-only", "-Wall", "--timing", "--top-module",
                           f"tb_{NAME_22}", *files], capture_output=True, text=True, timeout=300)
    assert lint.returncode == 0 and "%" not in lint.stderr, lint.stderr[-3000:]
    icarus = subprocess.run(["iverilog", "-g2012", "-Wall", "-s", f"tb_{NAME_22}", "-o", "/dev/null", *files],
                            capture_output=True, text=True, timeout=300)
    assert icarus.returncode == 0 and not (icarus.stdout + icarus.stderr).strip(), icarus.stderr
