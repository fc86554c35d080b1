"""The shipped top: named ports and formats, its header, no overflow port, folder-independent
Verilog, lint, and what it does from power-up under Icarus."""

import hashlib
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from phongfx.core.registry import get_block
from phongfx.hdl.block import OVERFLOW
from phongfx.hdl.emit import verilog
from phongfx.hdl.top import BLOCK_PATH, Top, port_map, top_verilog
from phongfx.sim.testbench import run_icarus, verilog_testbench, write_testbench
from phongfx.sim.verilator_backend import tool_environment
from tests.hdl.test_emit import WAIVED

ROOT = Path(__file__).resolve().parent.parent.parent
CONTROL = {"clk": ("input", 1), "rst": ("input", 1), "in_valid": ("input", 1), "in_ready": ("output", 1),
           "out_valid": ("output", 1), "out_ready": ("input", 1)}


def module_ports(text, module):
    """``{port: (direction, width)}`` declared in ``module`` of Verilog ``text``."""
    body = text[text.index(f"module {module}("):]
    body = body[:body.index("endmodule")]
    declarations = re.findall(r"^\s*(input|output)\s+(?:\[(\d+):0\]\s+)?(\w+);", body, re.M)
    return {name: (direction, int(msb) + 1 if msb else 1) for direction, msb, name in declarations}


@pytest.mark.parametrize("unit", ["conventional", "blinn"])
def test_the_normal_enters_a_two_light_top_once(unit):
    from phongfx.config import BlendConfig, BlinnConfig, ConventionalConfig, ShaderConfig

    grey = ((0.5, 0.5, 0.5),) * 2
    cls = ConventionalConfig if unit == "conventional" else BlinnConfig
    config = ShaderConfig(unit=unit, units=(cls(),) * 2, blend=BlendConfig(diff="1.15", diffuse=(grey,), specular=(grey,)))
    names = [port["name"] for port in port_map(config)]
    assert names.count("in_normal_x") == 1 and names.count("in_n") == 1
    assert not [name for name in names if "_normal" in name and name.startswith("in_c")]
    assert {"in_c0_light_x", "in_c1_light_x"} <= set(names)


def test_lirp_ports():
    text = top_verilog(get_block("lirp").component(), "lirp")
    lanes = {f"in_{v}_{axis}": ("input", 12) for v in ("n0", "n1") for axis in "xyz"}
    assert module_ports(text, "lirp_top") == {
        **CONTROL, **lanes, "in_a": ("input", 11),
        "out_n_x": ("output", 12), "out_n_y": ("output", 12), "out_n_z": ("output", 12)}


def test_fig7_ports():
    text = top_verilog(get_block("fig7").component(), "fig7")
    vectors = {f"in_{v}_{axis}": ("input", 12) for v in ("n0", "n1", "v", "l0", "l1") for axis in "xyz"}
    assert module_ports(text, "fig7_top") == {
        **CONTROL, **vectors, "in_a": ("input", 11), "in_n": ("input", 13),
        "out_spec0": ("output", 16), "out_spec1": ("output", 16),
        "out_diff0": ("output", 11), "out_diff1": ("output", 11)}


def test_other_lane_counts_are_numbered():
    from phongfx.hdl.top import lane_suffix

    assert [lane_suffix(lane, 3) for lane in range(3)] == ["_x", "_y", "_z"]
    assert [lane_suffix(lane, 2) for lane in range(2)] == ["_0", "_1"]
    assert lane_suffix(0, 1) == ""


def test_port_map_offsets_follow_the_packed_payload():
    from phongfx.sim.harness import payload_fields

    config = get_block("fig7").config
    ports = port_map(config)
    for direction, fields in (("input", config.inputs), ("output", config.outputs)):
        mine = [(p["field"], p["lane"], p["offset"], p["width"], p["signed"]) for p in ports
                if p["field"] is not None and p["direction"] == direction]
        assert mine == payload_fields(fields)[0]
    assert [p["name"] for p in ports[:6]] == list(CONTROL)
    assert {p["format"] for p in ports if p["field"] is None} == {None}
    assert ports[6] == {"name": "in_n0_x", "direction": "input", "field": "n0", "lane": 0, "width": 12,
                        "format": "S1.10", "signed": True, "offset": 0}


@pytest.mark.parametrize("name", ["lirp", "fig7", "spherical"])
def test_header_lists_every_port_with_its_format(name):
    block = get_block(name)
    text = top_verilog(block.component(), name)
    header = text[:text.index("/* Generated")]
    assert all(line.startswith("//") for line in header.splitlines())
    assert header.startswith(f"// {name}_top: ")
    assert f"Latency: {block.latency} cycle(s)" in header
    for words in ("Initiation interval: 1 clock: one vector every clock while out_ready is high", "AXI-Stream",
                  "synchronous and active high", "Power-up without a reset pulse",
                  "Sn.m is signed two's complement",
                  "1 sign bit + n integer bits + m fraction bits (1+n+m bits)",
                  "c * 2^-m", "[w-1:0], MSB first"):
        assert words in " ".join(line[2:].strip() for line in header.splitlines()), words
    # one line per port, the same data as port_map: the header is printed from it
    rows = re.findall(r"^//   (input|output) +(\w+) +(\d+)  (\S+) +(.*)$", header, re.M)
    assert [(d, n, int(w), f) for d, n, w, f, _ in rows] == \
        [(p["direction"], p["name"], p["width"], p["format"] or "-") for p in port_map(block.config)]
    for (_, _, _, _, meaning), port in zip(rows, port_map(block.config)):
        if port["field"] is not None:
            assert meaning.endswith(f"offset {port['offset']}")
            assert meaning.startswith("signed" if port["signed"] else "unsigned")


def test_overflow_port_only_for_simulation():
    component = get_block("lirp").component
    shipped = top_verilog(component(), "lirp")
    checked = top_verilog(component(), "lirp", overflow=True)
    assert "out_overflow" not in module_ports(shipped, "lirp_top")
    assert module_ports(checked, "lirp_top")["out_overflow"] == ("output", 1)
    # the shipped top is built without the checks: no flag registers at all
    assert "overflow_d" not in shipped and "overflow_d" in checked
    assert [p["name"] for p in port_map(get_block("lirp").config, overflow=True)][-1] == f"out_{OVERFLOW}"


def test_top_refuses_what_it_cannot_wrap():
    with pytest.raises(TypeError, match="^block must be a PipelinedBlock, not 3$"):
        Top(3, "x")
    with pytest.raises(ValueError, match="^top name must be a Verilog identifier, not 'a b'$"):
        Top(get_block("lirp").component(), "a b")


@pytest.mark.needs_verilator
def test_top_lints_clean(tmp_path):
    executable = tool_environment()
    path = tmp_path / "spherical_top.v"
    path.write_text(top_verilog(get_block("spherical").component(), "spherical"))
    lint = subprocess.run([str(executable), "--lint-only", "-Wall", *(f"-Wno-{w}" for w in WAIVED),
                           "--top-module", "spherical_top", str(path)], capture_output=True, text=True,
                          timeout=300)
    assert lint.returncode == 0 and "%Warning" not in lint.stderr, lint.stderr[-3000:]


# ---------------------------------------------------------------- the same bytes from any folder

_EMIT = """
import hashlib, importlib.util, sys
root = sys.argv[1]
folders = {"phongfx": "phongfx", "phongfx.golden": "golden", "phongfx.hdl": "hdl", "phongfx.sim": "sim"}

class Copy:
    # ahead of the checkout's editable install: the packages come from the copy
    @staticmethod
    def find_spec(name, path=None, target=None):
        if name in folders:
            return importlib.util.spec_from_file_location(name, f"{root}/{folders[name]}/__init__.py")
        return None

sys.meta_path.insert(0, Copy)
from phongfx.core.registry import get_block
from phongfx.hdl import emit
from phongfx.hdl.top import top_verilog
assert emit.__file__.startswith(root), emit.__file__
for name in ("lirp", "spherical"):
    block = get_block(name)
    for text in (emit.verilog(block.component(), name), top_verilog(block.component(), name)):
        print(hashlib.sha256(text.encode()).hexdigest())
"""


def test_verilog_is_the_same_from_another_folder(tmp_path):
    copy = tmp_path / "elsewhere" / "phongfx-copy"
    for folder in ("phongfx", "golden", "hdl", "sim"):
        shutil.copytree(ROOT / folder, copy / folder, ignore=shutil.ignore_patterns("__pycache__"))
    cwd = tmp_path / "somewhere" / "else"
    cwd.mkdir(parents=True)
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    done = subprocess.run([sys.executable, "-c", _EMIT, str(copy)], cwd=cwd, env=env, capture_output=True,
                          text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-3000:]
    here = []
    for name in ("lirp", "spherical"):
        block = get_block(name)
        for text in (verilog(block.component(), name), top_verilog(block.component(), name)):
            assert str(ROOT) not in text and "site-packages" not in text and 'src = "hdl/' in text
            here.append(hashlib.sha256(text.encode()).hexdigest())
    assert done.stdout.split() == here


def test_src_paths_relative_to_the_repository():
    from phongfx.hdl.emit import portable_src

    venv = f"{ROOT}/.venv/lib/python3.11/site-packages"
    text = (f'  (* src = "{ROOT}/hdl/lirp.py:42" *)\n  wire a;\n'
            f'  (* src = "{venv}/amaranth/hdl/_ir.py:283" *)\n  input clk;\n'
            f'  assign b = c + (* src = "/elsewhere/x.py:1|{ROOT}/hdl/fixed.py:7" *) d;\n'
            f'  assign e = f + (* src = "/elsewhere/x.py:1" *) g;\n')
    assert portable_src(text) == ('  (* src = "hdl/lirp.py:42" *)\n  wire a;\n  input clk;\n'
                                  '  assign b = c + (* src = "hdl/fixed.py:7" *) d;\n  assign e = f + g;\n')


# ---------------------------------------------------------------- power-up

def _power_up(tmp_path, name, top_text=None):
    """The exported testbench without its first reset, on the shipped top (or ``top_text``)."""
    block = get_block(name)
    inputs = block.stimulus(count=10, seed=3)
    bench = write_testbench(block, inputs, block.golden(inputs), tmp_path / name, name)
    (bench.directory / f"tb_{name}.v").write_text(
        verilog_testbench(block.config, name, bench.vectors, block.latency, reset_at=bench.reset_at,
                          reset_cycles=0))
    if top_text is not None:
        (bench.directory / f"{name}_top.v").write_text(top_text)
    return run_icarus(bench.directory, name)


@pytest.mark.needs_iverilog
@pytest.mark.parametrize("name", ["lirp", "blinn"])
def test_defined_from_power_up_under_icarus(tmp_path, name):
    ok, text = _power_up(tmp_path, name)
    assert ok and "PASS" in text, text[-3000:]


@pytest.mark.needs_iverilog
def test_amaranth_s_own_text_starts_at_x_under_icarus(tmp_path):
    # its always @* blocks' only trigger (a declaration initializer) is no event under -g2012:
    # out_valid is X until the valid pipeline has been refilled; the shipped top's continuous
    # assignments (test_defined_from_power_up_under_icarus) are evaluated at time 0
    block = get_block("lirp")
    ok, text = _power_up(tmp_path, "lirp", verilog(Top(block.component(), "lirp"), "lirp_top"))
    assert not ok and "FAIL cycle 2: out_valid or in_ready is X" in text, text[-3000:]


def test_header_gives_the_interval_the_clock_and_the_requirement():
    from phongfx.config import ShaderConfig
    from phongfx.hdl.top import timing_line

    block = get_block("shader", config=ShaderConfig(interval=2))
    text = top_verilog(block.component(), "turns", timing={
        "clock_mhz": 120.0, "clock_source": "proxied: ecp5-clock-proxy", "requirement_mpx": 75.0, "met": False})
    words = " ".join(line[2:].strip() for line in text[:text.index("/* Generated")].splitlines())
    assert f"Latency: {block.latency} cycle(s)" in words
    assert "Initiation interval: 2 clocks: one pixel every 2 clocks while out_ready is high" in words
    assert ("Timing: clock 120.0 MHz (proxied: ecp5-clock-proxy); 60.0 Mpixel/s (one pixel every 2 clocks); "
            "requirement 75.0 Mpixel/s: MISSED by 15.0 Mpixel/s (20 %).") in words
    assert timing_line({"clock_mhz": 200.0, "clock_source": "synthesized: nextpnr-ecp5", "pixel_rate_mpx": 200.0,
                        "requirement_mpx": 150.0, "met": True}) == \
        "Timing: clock 200.0 MHz (synthesized: nextpnr-ecp5); 200.0 Mvector/s; requirement 150.0 Mvector/s: met."
    assert timing_line({"met": None}) is None
    with pytest.raises(ValueError, match="^timing keys must be among clock_mhz, clock_source, pixel_rate_mpx, "
                                         "requirement_mpx, met, not fmax$"):
        timing_line({"fmax": 3})


def test_the_block_s_instances_sit_under_block_path():
    """The compile names a shader's sub-blocks from the shipped top, under ``BLOCK_PATH``."""
    from phongfx.explore.compile.emit import submodules

    block = get_block("fig7")
    shipped = submodules(top_verilog(block.component(), "fig7"), f"fig7_top.{BLOCK_PATH}")
    assert shipped and shipped == submodules(verilog(block.component(), "fig7"), "fig7")
