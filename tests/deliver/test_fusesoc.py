"""The FuseSoC core file of a compiled core: its text (name, filesets, targets), FuseSoC's
own reading of it, and its ``sim`` target run by the venv's FuseSoC (``make`` installs it
from PyPI) to PASS under Icarus Verilog and Verilator; the same on a real ``phongfx
compile`` output."""

import json
import re
import subprocess
import sys
from pathlib import Path

import pytest
import yaml  # FuseSoC's own dependency

from phongfx.core.registry import get_block
from phongfx.deliver.constraints import Clock
from phongfx.deliver.fusesoc import core_name, core_text, simulation_files, write_flow
from phongfx.hdl.top import port_map, top_verilog
from phongfx.sim.simulators import COROUTINES, VERILATOR_WARNINGS
from phongfx.sim.testbench import write_testbench

from tests.compiler.test_compile import TORUS  # the compiler tests' tiny torus scene

MODULE = "tiny_fig7"
VECTORS = 100
PASS = re.compile(r"^PASS (\d+) vectors, (\d+) cycles", re.M)


def fusesoc():
    """The venv's ``fusesoc`` (beside this Python); the test is skipped where it is missing."""
    path = Path(sys.executable).parent / "fusesoc"
    if not path.is_file():
        pytest.skip("FuseSoC is not installed in this venv (pip install fusesoc; make installs it)")
    return str(path)


def run_fusesoc(cores_root, work, *args, timeout=600):
    """``fusesoc --cores-root CORES_ROOT ARGS`` in ``work`` with an empty configuration (no
    library of the user's), its build tree under ``work``; returns (exit code, console)."""
    work.mkdir(exist_ok=True)
    (work / "fusesoc.conf").write_text("")
    ran = subprocess.run([fusesoc(), "--config", str(work / "fusesoc.conf"), "--cores-root", str(cores_root), *args],
                         cwd=work, capture_output=True, text=True, timeout=timeout)
    return ran.returncode, ran.stdout + ran.stderr


@pytest.fixture(scope="module")
def core_folder(tmp_path_factory):
    """A compiled core's folder as ``phongfx compile`` lays it out, from Figure 7's datapath
    with its first :data:`VECTORS` stimulus vectors (no scene compiled)."""
    folder = tmp_path_factory.mktemp("core")
    block = get_block("fig7")
    inputs = {port: codes[:VECTORS] for port, codes in block.stimulus(count=VECTORS, seed=3).items()}
    (folder / "verilog").mkdir()
    (folder / "verilog" / f"{MODULE}_top.v").write_text(top_verilog(block.component(), MODULE))
    write_testbench(block, inputs, block.golden(inputs), folder / "testbench", MODULE)
    flow = write_flow(folder, MODULE, Clock(40.0, "a test"), port_map(block.config), "fig7 in a test",
                      version="1.2.3")
    return folder, flow


def test_the_core_names_the_module_and_lists_what_the_folder_holds(core_folder):
    folder, flow = core_folder
    text = (folder / f"{MODULE}.core").read_text()
    assert text.startswith("CAPI=2:\n")
    core = yaml.safe_load(text)
    assert core["name"] == core_name(MODULE, "1.2.3") == "phongfx:scene:tiny_fig7:1.2.3"
    assert flow["fusesoc_name"] == core["name"] and flow["fusesoc_core"] == "tiny_fig7.core"
    assert flow["clock_mhz"] == 40.0 and flow["clock_period_ns"] == 25.0
    files = {name: [next(iter(f)) if isinstance(f, dict) else f for f in fileset["files"]]
             for name, fileset in core["filesets"].items()}
    assert files == {"rtl": ["verilog/tiny_fig7_top.v"], "tb": simulation_files(MODULE),
                     "sdc": ["constraints/tiny_fig7.sdc"], "lpf": ["constraints/tiny_fig7.lpf"],
                     "ice40_clock": ["constraints/tiny_fig7_ice40_clock.py", "constraints/tiny_fig7_nextpnr.sdc"]}
    assert all((folder / path).is_file() for paths in files.values() for path in paths)
    memh = [f for f in core["filesets"]["tb"]["files"] if isinstance(f, dict)]
    assert [list(f.values())[0] for f in memh] == [  # read by $readmemh from the run directory
        {"file_type": "user", "copyto": "tiny_fig7_in.memh"}, {"file_type": "user", "copyto": "tiny_fig7_expected.memh"}]
    assert [core["filesets"][name]["file_type"] for name in ("rtl", "tb", "sdc", "lpf")] == [
        "verilogSource", "verilogSource", "SDC", "LPF"]
    targets = core["targets"]
    assert {name: t["toplevel"] for name, t in targets.items()} == {
        "default": "tiny_fig7_top", "sim": "tb_tiny_fig7", "lint": "tiny_fig7_top", "ecp5": "tiny_fig7_top",
        "ice40": "tiny_fig7_top", "asic": "tiny_fig7_top"}
    assert targets["default"]["filesets"] == ["rtl"] and targets["sim"]["filesets"] == ["rtl", "tb"]
    assert targets["sim"]["default_tool"] == "icarus"
    assert targets["sim"]["tools"] == {"icarus": {"iverilog_options": ["-g2012"]},
                                       "verilator": {"mode": "binary",
                                                     "verilator_options": VERILATOR_WARNINGS + COROUTINES}}
    assert targets["lint"]["tools"] == {"verilator": {"mode": "lint-only", "verilator_options": ["-Wall"]}}


def test_the_description_is_one_quoted_line():
    core = yaml.safe_load(core_text("m", 'a "scene": 40 MHz, # not a comment'))
    assert core["description"] == 'a "scene": 40 MHz, # not a comment'


def test_fusesoc_reads_the_core(core_folder, tmp_path):
    folder, flow = core_folder
    code, out = run_fusesoc(folder, tmp_path / "work", "core", "show", flow["fusesoc_name"])
    assert code == 0, out
    assert re.search(r"^Name:\s+phongfx:scene:tiny_fig7:1\.2\.3$", out, re.M), out
    for target in ("default", "sim", "lint", "ecp5", "ice40", "asic"):
        assert re.search(rf"^\s*{target}\b", out, re.M), (target, out)


@pytest.mark.needs_iverilog
def test_the_sim_target_passes_under_icarus(core_folder, tmp_path):
    folder, flow = core_folder
    code, out = run_fusesoc(folder, tmp_path / "work", "run", "--target", "sim", flow["fusesoc_name"])
    assert code == 0, out[-3000:]
    assert [int(n) for n in PASS.search(out).groups()][0] == VECTORS, out[-3000:]
    assert "FAIL" not in out
    # the .memh files were copied to the run directory, where $readmemh looks
    run_dir = tmp_path / "work" / "build" / "phongfx_scene_tiny_fig7_1.2.3" / "sim-icarus"
    assert (run_dir / "tiny_fig7_in.memh").read_text() == (folder / "testbench" / "tiny_fig7_in.memh").read_text()


@pytest.mark.needs_iverilog
def test_a_wrong_expected_value_fails_the_sim_target(core_folder, tmp_path):
    """The PASS is earned: one changed word of the expected outputs gives FAIL lines."""
    folder, flow = core_folder
    broken = tmp_path / "core"
    subprocess.run(["cp", "-r", str(folder), str(broken)], check=True)
    expected = broken / "testbench" / f"{MODULE}_expected.memh"
    lines = expected.read_text().splitlines()
    lines[7] = format(int(lines[7], 16) ^ 1, f"0{len(lines[7])}x")
    expected.write_text("\n".join(lines) + "\n")
    _, out = run_fusesoc(broken, tmp_path / "work", "run", "--target", "sim", flow["fusesoc_name"])
    assert re.search(r"^FAIL vector 7 field ", out, re.M) and not PASS.search(out), out[-3000:]


@pytest.mark.needs_verilator
@pytest.mark.slow
def test_the_sim_target_passes_under_verilator(core_folder, tmp_path):
    from phongfx.sim.verilator_backend import tool_environment

    tool_environment()  # VERILATOR_ROOT: Edalize's Makefile runs $VERILATOR_ROOT/bin/verilator
    folder, flow = core_folder
    code, out = run_fusesoc(folder, tmp_path / "work", "run", "--target", "sim", "--tool", "verilator",
                            flow["fusesoc_name"])
    assert code == 0, out[-3000:]
    assert int(PASS.search(out).group(1)) == VECTORS, out[-3000:]


@pytest.mark.needs_iverilog
def test_a_compiled_scene_s_core_passes_its_sim_target(tmp_path, capsys):
    """On a real ``phongfx compile`` output: the core, the constraints at the compiled
    clock and the testbench come with it, and FuseSoC runs the sim target to PASS."""
    from phongfx.cli import main

    scene = tmp_path / "tiny.toml"
    scene.write_text(TORUS.format(error=1.0, against="phong"))
    out = tmp_path / "out"
    assert main(["compile", str(scene), "-o", str(out), "--methods", "fig7", "--no-check", "--quiet"]) == 0
    data = json.loads((out / "manifest.json").read_text())
    flow, module = data["flow"], data["module"]
    printed = capsys.readouterr().out
    assert f"constraints: {out}/constraints (clk {flow['clock_mhz']:g} MHz: .sdc, .lpf for ECP5, " in printed
    assert (f"FuseSoC core: {out}/tiny_fig7.core (run: fusesoc --cores-root {out} run --target sim "
            f"{flow['fusesoc_name']})\n") in printed
    assert sorted(p.name for p in (out / "constraints").iterdir()) == [
        "tiny_fig7.lpf", "tiny_fig7.sdc", "tiny_fig7_ice40_clock.py", "tiny_fig7_nextpnr.sdc"]
    assert module == "tiny_fig7" and flow["fusesoc_name"] == core_name(module)
    assert flow["clock_mhz"] == data["timing"]["clock_mhz"] > 0
    assert f"create_clock -name clk -period {flow['clock_period_ns']:g} [get_ports clk]" in \
        (out / "constraints" / f"{module}.sdc").read_text()
    assert f'FREQUENCY PORT "clk" {flow["clock_mhz"]:g} MHz;' in (out / "constraints" / f"{module}.lpf").read_text()
    code, log = run_fusesoc(out, tmp_path / "work", "run", "--target", "sim", flow["fusesoc_name"])
    assert code == 0 and int(PASS.search(log).group(1)) == data["testbench"]["vectors"], log[-3000:]



@pytest.mark.needs_verilator
def test_the_lint_target_is_verilator_s_lint_of_the_top_with_every_warning(core_folder, tmp_path):
    """The lint target says what ``verilator --lint-only -Wall`` says of the shipped top, and
    passes exactly when that is clean."""
    from phongfx.sim.verilator_backend import tool_environment

    verilator = tool_environment()
    folder, flow = core_folder
    code, out = run_fusesoc(folder, tmp_path / "work", "run", "--target", "lint", flow["fusesoc_name"])
    direct = subprocess.run([str(verilator), "--lint-only", "-Wall", "--top-module", f"{MODULE}_top",
                             str(folder / "verilog" / f"{MODULE}_top.v")], capture_output=True, text=True)
    total = re.compile(r"Exiting due to (\d+) warning")
    # the same count (Verilator prints the first 50 only, in an order of its own), none when clean
    assert total.findall(out) == total.findall(direct.stderr)
    assert (code == 0) == (direct.returncode == 0) == (not total.findall(direct.stderr)), out[-3000:]
    config = tmp_path / "work" / "build" / "phongfx_scene_tiny_fig7_1.2.3" / "lint-verilator" / "config.mk"
    assert re.search(r"^VERILATOR_OPTIONS\s*:= -Wall$", config.read_text(), re.M)
