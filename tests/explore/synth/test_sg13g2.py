"""IHP SG13G2 (130 nm, the open PDK) through the standard-cell flow: mapping onto its
cells without the ones a synthesis must not use, timing at its three corners, and the
gate-level netlist simulated with the cells' own Verilog models against the golden model
(Icarus).  The small ``shape`` block runs by default; Figure 7 and a compiled scene are
``slow``."""

import re

import pytest

from phongfx.core.registry import get_block
from phongfx.explore.synth.asic import time_at
from phongfx.explore.synth.fpga import SynthError, synth
from phongfx.explore.synth.gatelevel import check_gate_level, functional_models
from phongfx.explore.synth.liberty import dont_use, read_liberty
from phongfx.sim.testbench import write_testbench

TYPICAL = "sg13g2_stdcell_typ_1p20V_25C.lib"
SLOW = "sg13g2_stdcell_slow_1p08V_125C.lib"
FAST = "sg13g2_stdcell_fast_1p32V_m40C.lib"


def _models(folder):
    return folder / "sg13g2_stdcell.v", folder / "sg13g2_udp.v"


def test_functional_models_drop_timing_and_delayed_copies(sg13g2):
    text = functional_models(*_models(sg13g2))
    assert "specify" not in text and "delayed_" not in text and "$setuphold" not in text
    assert "ihp_dff_r (int_fwire_IQ, notifier, CLK, D, int_fwire_r, xcr_0);" in text
    assert len(re.findall(r"^module sg13g2_", text, re.M)) == 84


@pytest.mark.needs_sta
def test_shape_on_sg13g2_at_three_corners(asic_tools, sg13g2):
    result = synth("shape", target="asic", device=str(sg13g2 / TYPICAL))
    facts = read_liberty(sg13g2 / TYPICAL)
    assert (result["library"], result["corner"]) == ("sg13g2_stdcell_typ_1p20V_25C", "1.20 V, 25 °C, process 1")
    assert all(cell.startswith("sg13g2_") for cell in result["cells"])
    assert not set(result["cells"]) & set(dont_use(facts))
    assert result["ff"] == sum(n for cell, n in result["cells"].items() if cell in facts.sequential) > 0
    slow, fast = (time_at(result, sg13g2 / name) for name in (SLOW, FAST))
    assert (slow["corner"], fast["corner"]) == ("1.08 V, 125 °C, process 1", "1.32 V, -40 °C, process 1")
    # slower at high temperature and low voltage, faster at the other end
    assert fast["min_period_ns"] < result["min_period_ns"] < slow["min_period_ns"]
    assert time_at(result, sg13g2 / SLOW) == slow  # kept beside the netlist


@pytest.mark.needs_sta
def test_a_corner_must_hold_the_netlists_cells(asic_tools, sg13g2, tmp_path):
    result = synth("shape", target="asic", device=str(sg13g2 / TYPICAL))
    with pytest.raises(SynthError, match=r"lacks cells the netlist uses: sg13g2_"):
        time_at(result, "osu018")


def _bench(block, count, folder, name):
    # a small block's stimulus is exhaustive (tens of thousands of vectors): its first ``count``
    inputs = {port: codes[:count] for port, codes in block.stimulus(count, seed=3).items()}
    return write_testbench(block, inputs, block.golden(inputs), folder, name)


@pytest.mark.needs_sta
@pytest.mark.needs_iverilog
def test_gate_level_shape_matches_the_golden_model(asic_tools, sg13g2, tmp_path):
    bench = _bench(get_block("shape"), 200, tmp_path / "tb", "shape")
    result = check_gate_level(bench.directory, "shape", sg13g2 / TYPICAL, _models(sg13g2))
    assert result["passed"], result["output"]
    assert bench.vectors == 200 and re.search(r"^PASS 200 vectors", result["output"], re.M), result["output"]
    assert all(cell.startswith("sg13g2_") for cell in result["netlist"]["cells"])


@pytest.mark.needs_sta
@pytest.mark.needs_iverilog
def test_gate_level_catches_a_wrong_expectation(asic_tools, sg13g2, tmp_path):
    bench = _bench(get_block("shape"), 50, tmp_path / "tb", "shape")
    expected = bench.directory / "shape_expected.memh"
    lines = expected.read_text().splitlines()
    index = next(i for i, line in enumerate(lines) if line and not line.startswith("//"))
    lines[index] = format(int(lines[index], 16) ^ 1, f"0{len(lines[index])}x")
    expected.write_text("\n".join(lines) + "\n")
    result = check_gate_level(bench.directory, "shape", sg13g2 / TYPICAL, _models(sg13g2))
    assert not result["passed"] and "FAIL" in result["output"]


@pytest.mark.slow
@pytest.mark.needs_sta
@pytest.mark.needs_iverilog
def test_gate_level_fig7(asic_tools, sg13g2, tmp_path):
    bench = _bench(get_block("fig7"), 300, tmp_path / "tb", "fig7")
    result = check_gate_level(bench.directory, "fig7", sg13g2 / TYPICAL, _models(sg13g2))
    assert result["passed"], result["output"][-2000:]
    assert re.search(rf"^PASS {bench.vectors} vectors", result["output"], re.M)


@pytest.mark.needs_sta
def test_command_line_liberty_and_corner(asic_tools, sg13g2, capsys):
    from phongfx.cli import main

    assert main(["synth", "shape", "--target", "asic", "--liberty", str(sg13g2 / TYPICAL),
                 "--corner", str(sg13g2 / SLOW), "--quiet"]) == 0
    text = capsys.readouterr().out
    assert "| shape | sg13g2_stdcell_typ_1p20V_25C |" in text
    assert re.search(r"^\* the same netlist at sg13g2_stdcell_slow_1p08V_125C \(1\.08 V, 125 °C, process 1\): "
                     r"Fmax \d+\.\d MHz, worst path ", text, re.M), text


@pytest.mark.parametrize("argv, message", [
    (["--liberty", "{tmp}/none.lib"], "Liberty file {tmp}/none.lib does not exist"),
    (["--liberty", "{typ}", "--corner", "{tmp}/none.lib"], "Liberty file {tmp}/none.lib does not exist"),
    (["--target", "ecp5", "--corner", "{typ}"], "--corner applies to --target asic only, not to 'ecp5'"),
])
def test_command_line_bad_liberty_before_any_work(sg13g2, capsys, tmp_path, argv, message):
    from phongfx.cli import main

    argv = [a.format(tmp=tmp_path, typ=sg13g2 / TYPICAL) for a in argv]
    target = [] if "--target" in argv else ["--target", "asic"]
    assert main(["synth", "shape", *target, *argv, "--quiet", "--workdir", str(tmp_path / "work")]) == 2
    assert capsys.readouterr().err == f"phongfx: error: {message.format(tmp=tmp_path)}\n"
    assert not (tmp_path / "work").exists()


@pytest.mark.slow
@pytest.mark.needs_sta
@pytest.mark.needs_iverilog
def test_gate_level_compiled_scene(asic_tools, sg13g2, tmp_path):
    """The exported testbench of a compiled scene (its shipped top, the scene's own vectors)
    passes on the top's SG13G2 netlist."""
    import json
    from pathlib import Path

    from phongfx.cli import main

    scene = Path(__file__).resolve().parents[3] / "scenes" / "two-lights.toml"
    assert main(["compile", str(scene), "-o", str(tmp_path / "out"), "--target", "asic", "--testbench",
                 "--no-check", "--quiet"]) == 0
    module = json.loads((tmp_path / "out" / "manifest.json").read_text())["module"]
    result = check_gate_level(tmp_path / "out" / "testbench", module, sg13g2 / TYPICAL, _models(sg13g2))
    assert result["passed"], result["output"][-2000:]
    assert re.search(r"^PASS \d+ vectors", result["output"], re.M)
