"""Gate-level check: synthesized netlists with the FPGA cell models, against golden."""

import re
from pathlib import Path

import pytest

from phongfx.core.registry import get_block
from phongfx.explore.synth.netlist import NETLIST_TARGETS, cell_models, check_netlist, synth_netlist
from phongfx.sim import fast_backend


def test_cell_models_inline_their_includes_and_add_the_dsp():
    ecp5 = cell_models("ecp5")
    assert "`include" not in ecp5
    for cell in ("module LUT4", "module CCU2C", "module TRELLIS_FF", "module MULT18X18D"):
        assert cell in ecp5
    ice40 = cell_models("ice40")
    assert "module SB_MAC16" in ice40 and "module MULT18X18D" not in ice40
    with pytest.raises(ValueError, match="netlist target must be one of 'ecp5', 'ice40', not 'asic'"):
        cell_models("asic")
    assert tuple(NETLIST_TARGETS) == ("ecp5", "ice40")


def test_unknown_device_is_named(tmp_path):
    with pytest.raises(ValueError, match="device must be one of '25k', '45k', '85k' for ecp5, not 'up5k'"):
        synth_netlist(get_block("lirp"), "ecp5", "up5k", workdir=tmp_path)


@pytest.mark.needs_yosys
@pytest.mark.needs_verilator
@pytest.mark.parametrize("name,depth,target", [("lirp", 3, "ecp5"), ("difference", 3, "ecp5"),
                                               ("shape", 1, "ice40"), ("diffuse", 0, "ecp5")])
def test_netlists_match_golden(name, depth, target):
    block = get_block(name, pipeline=depth)
    result = check_netlist(block, target, count=300, seed=depth, bubbles=0.2)
    assert result.backend.startswith(f"{target} netlist")
    assert result.vectors > 0 and result.mismatch_count == 0, result.describe()
    cells = synth_netlist(block, target)["cells"]
    if target == "ecp5":  # the products are DSPs, with the pipeline's registers where it has them
        assert cells["MULT18X18D"] >= 2 and cells.get("LUT4", 0) + cells["CCU2C"] > 0
        if depth >= 3:
            assert re.search(r'REG_INPUTA_CLK\("CLK0"\)', Path(synth_netlist(
                block, target)["netlist"]).read_text())
    else:
        assert "SB_LUT4" in cells


@pytest.mark.needs_yosys
@pytest.mark.needs_verilator
def test_a_broken_netlist_is_caught():
    # the DSPs' output registers turned off: every product one clock early
    block = get_block("lirp", pipeline=3)
    netlist = Path(synth_netlist(block, "ecp5")["netlist"]).read_text()
    broken = netlist.replace('.REG_OUTPUT_CLK("CLK0")', '.REG_OUTPUT_CLK("NONE")')
    assert broken != netlist
    result = fast_backend.check(block, count=100, seed=1, bubbles=0.0,
                                design=broken + cell_models("ecp5"))
    assert result.mismatch_count > 0


@pytest.mark.slow
@pytest.mark.needs_yosys
@pytest.mark.needs_verilator
@pytest.mark.parametrize("name", ["fig7", "fig8"])
def test_datapath_netlists_match_golden_at_the_deepest_depth(name):
    from phongfx.config import MAX_PIPELINE

    block = get_block(name, pipeline=MAX_PIPELINE)
    result = check_netlist(block, "ecp5", count=300, seed=1, bubbles=0.2)
    assert result.vectors > 0 and result.mismatch_count == 0, result.describe()
