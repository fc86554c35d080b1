"""Standard-cell synthesis and timing (phongfx.explore.synth.asic): library checks, OpenSTA report
parsing, and real Yosys + OpenSTA runs on small blocks (width visible in area, the
area equal to the cells' library areas summed, the cache)."""

import re
from pathlib import Path

import pytest

from phongfx.core.registry import get_block
from phongfx.explore.synth import asic as asic_module
from phongfx.explore.synth import fpga as synth_module
from phongfx.explore.synth.asic import LIBRARIES, Library, parse_timing
from phongfx.explore.synth.fpga import SynthError, markdown, synth
from phongfx.sim import tools as sim_tools

# A path as OpenSTA 2.0 prints it with -fields {net} (cut short in the middle).
REPORT = """Startpoint: dut/_80843_ (rising edge-triggered flip-flop clocked by clk)
Endpoint: dut/_80834_ (rising edge-triggered flip-flop clocked by clk)
Path Group: clk
Path Type: max

Fanout    Delay     Time   Description
----------------------------------------------------------------
         0.000    0.000   clock clk (rise edge)
         0.000    0.000 ^ dut/_80843_/CLK (DFFPOSX1)
         0.184    0.184 v dut/_80843_/Q (DFFPOSX1)
    2                     dut/normalize1.squares_z[7] (net)
         0.567    9.441 ^ dut/_69973_/Y (AOI21X1)
         0.000    9.441 ^ dut/_80834_/D (DFFPOSX1)
                  9.441   data arrival time

1000.000 1000.000   clock clk (rise edge)
         0.000 1000.000   clock network delay (ideal)
        -0.195  999.805   library setup time
                999.805   data required time
----------------------------------------------------------------
                990.364   slack (MET)
"""
NETLIST = """module fig7(clk);
  DFFPOSX1 _80843_ (
    .CLK(clk),
    .D(_1_),
    .Q(\\normalize1.squares_z[7] )
  );
  DFFPOSX1 _80834_ (
    .CLK(clk),
    .D(_00730_),
    .Q(\\difference3.x2[4] )
  );
endmodule
"""


def test_parse_timing_names_registers_by_their_nets():
    assert parse_timing(REPORT, NETLIST) == {"from": "normalize1.squares_z", "to": "difference3.x2",
                                             "ns": 9.636, "setup_ns": 0.195}


def test_parse_timing_refuses_a_cut_report():
    assert parse_timing(REPORT.split("library setup time")[0]) is None
    assert parse_timing(REPORT.replace("Endpoint", "Endpoints")) is None


def test_unknown_library(tmp_path):
    with pytest.raises(ValueError, match=r"^library must be one of 'osu018', 'osu035' for asic, not 'x'$"):
        synth("shape", target="asic", device="x", workdir=tmp_path)


def test_missing_library_names_the_package(tmp_path, monkeypatch):
    monkeypatch.setitem(LIBRARIES, "osu018", Library(str(tmp_path / "none.lib"), "qflow-tech-osu018", "-"))
    with pytest.raises(SynthError, match=r"^the osu018 Liberty file is missing \(.*none\.lib\): install "
                                         r"Debian's qflow-tech-osu018 \(apt-get install qflow-tech-osu018\)$"):
        synth("shape", target="asic", workdir=tmp_path)


def test_missing_opensta_names_the_package(tmp_path, monkeypatch, asic_tools):
    real = asic_module.tool
    monkeypatch.setattr(asic_module, "tool", lambda program, install=None:
                        real("no-such-sta", install) if program == "sta" else real(program, install))
    with pytest.raises(SynthError, match=r"^no-such-sta is not installed \(OpenSTA: apt-get install opensta\)$"):
        synth("shape", target="asic", workdir=tmp_path)


def _cell_areas(path):
    """Area of every cell of a Liberty file, read here independently of Yosys."""
    text = Path(path).read_text()
    return {name: float(area) for name, area in
            re.findall(r"cell \((\w+)\) \{[^{}]*?\barea : ([\d.]+);", text)}


def test_smoke_shape_osu018(monkeypatch, asic_tools):
    """Figure 7d, k = 1: one squarer; a narrower t is a smaller squarer, visibly."""
    wide = synth("shape", config=get_block("shape", k=1).config, target="asic")
    areas = _cell_areas(LIBRARIES["osu018"].path)
    assert len(areas) == 32
    assert wide["area_um2"] == pytest.approx(sum(areas[c] * n for c, n in wide["cells"].items()))
    assert wide["ff"] == sum(n for c, n in wide["cells"].items() if c.startswith("DFF"))
    assert wide["latency"] == 2 and wide["library"] == "osu018" and wide["target"] == "asic"
    assert wide["fmax_mhz"] == pytest.approx(1000 / wide["critical_path"]["ns"])
    assert wide["area_delay"] == pytest.approx(wide["area_um2"] * wide["critical_path"]["ns"])
    assert wide["met"] is (wide["fmax_mhz"] >= 150)
    narrow_config = get_block("shape", k=1, t="1.7").config
    narrow = synth("shape", config=narrow_config, target="asic")
    # a squarer's area goes with the square of its width: 16 bits against 8
    assert 2.5 < wide["area_um2"] / narrow["area_um2"] < 5
    assert "| shape | osu018 |" in markdown([wide])

    def fail(*args):
        raise AssertionError("a tool ran on a cache hit")
    for module in (asic_module, sim_tools):
        monkeypatch.setattr(module, "run", fail)
    again = synth("shape", config=get_block("shape", k=1).config, target="asic", freq=500)
    assert again["cached"] is True and again["freq"] == 500 and again["met"] is (again["fmax_mhz"] >= 500)
    assert again["area_um2"] == wide["area_um2"]


def _loads(netlist):
    """Per net of a mapped netlist, the cell inputs it drives (outputs named Y, Q, YS, YC)."""
    pins = re.findall(r"\.(\w+)\(([^()]*)\)", netlist)
    counts = {}
    for pin, net in pins:
        if pin not in ("Y", "Q", "YS", "YC") and net.strip():
            counts[net.strip()] = counts.get(net.strip(), 0) + 1
    return counts


def test_mapping_buffers_as_a_library_cell_drives():
    facts = asic_module.library_facts("osu018")
    script, files = asic_module.mapping(facts)
    assert files == {"abc.constr": "set_driving_cell BUFX2\nset_load 0.0373268\n"}
    assert script == "dfflibmap -liberty cells.lib\nabc -constr abc.constr -liberty cells.lib\n"


def test_no_net_but_the_clock_drives_dozens_of_cells(asic_tools):
    """ABC buffers and sizes: the reset, which reaches every register of the block (44
    unbuffered), and every other net drive at most a handful of cells."""
    result = synth("shape", target="asic")
    loads = _loads((Path(result["directory"]) / "netlist.v").read_text())
    assert loads.pop("clk") > 50  # the clock is ideal: left to clock-tree synthesis
    assert max(loads.values()) <= 16
    assert result["cells"]["BUFX2"] > 10


def test_osu035_is_larger_and_slower(asic_tools):
    config = get_block("shape", k=1, t="1.7").config
    small = synth("shape", config=config, target="asic", device="osu018")
    large = synth("shape", config=config, target="asic", device="osu035")
    # the OSU cells are drawn to scalable rules: every osu035 cell is 4 times its osu018 twin
    assert large["area_um2"] / small["area_um2"] == pytest.approx(4, rel=0.02)
    assert large["fmax_mhz"] < small["fmax_mhz"]


def test_ecp5_flow_is_untouched_by_the_library_option(tmp_path):
    with pytest.raises(ValueError, match=r"^device must be one of '25k', '45k', '85k' for ecp5, "
                                         r"not 'osu018'$"):
        synth("shape", target="ecp5", device="osu018", workdir=tmp_path)
    assert synth_module.ALL_TARGETS == ("ecp5", "ice40", "asic")
