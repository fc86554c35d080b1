"""The clock constraints shipped with a compiled core: which clock (asked, estimated or a
placeholder) and the text of the SDC, the ECP5 LPF and the iCE40 nextpnr script; OpenSTA
reads the SDC against a synthesized netlist of a shipped top."""

import re
import shutil
import subprocess

import pytest

from phongfx.core.registry import get_block
from phongfx.deliver.constraints import (PLACEHOLDER_MHZ, Clock, clock_of, ice40_clock_text, lpf_text,
                                         nextpnr_sdc_text, sdc_text, write_constraints)
from phongfx.hdl.top import port_map, top_verilog

#: The manifest's timing of a design at its own Fmax promised by the ECP5 clock proxy.
TIMING = {"fmax_mhz": 41.06, "clock_mhz": 41.06, "clock_source": "proxy", "clock_model": "ecp5-clock-proxy",
          "clock_error": 0.19, "clock_margin": 0.1, "clock_estimate_mhz": 45.62, "met": True}


def manifest(asked=None, timing=TIMING, cost_model="ecp5-proxy"):
    return {"requirement": {"max_error_levels": 1.0, "clock_mhz": asked}, "timing": timing,
            "cost_model": cost_model}


def test_the_design_s_own_clock_when_none_is_asked():
    clock = clock_of(manifest())
    assert clock.mhz == 41.06 and clock.period_ns == 24.355
    assert clock.source == ("no clock was asked: the design's own clock, its ecp5 Fmax 41.06 MHz promised by the "
                            "clock proxy (ecp5-clock-proxy: its estimate less a 10% margin, never above synthesis on "
                            "its calibration, at most 19% below) (manifest timing.clock_mhz)")


def test_the_clock_asked_wins_and_a_miss_is_said():
    assert clock_of(manifest(asked=40)).mhz == 40.0
    clock = clock_of(manifest(asked=100, timing={**TIMING, "met": False}))
    assert clock.mhz == 100.0 and clock.period_ns == 10.0
    assert clock.source.startswith("the clock asked for (phongfx compile --clock, manifest requirement.clock_mhz)")
    assert clock.source.endswith("timing will not close at the clock asked (manifest timing.met is false)")
    synthesized = clock_of(manifest(timing={"fmax_mhz": 57.3, "clock_mhz": 57.3, "clock_source": "synthesis"}))
    assert synthesized.mhz == 57.3 and "ecp5 Fmax 57.3 MHz by synthesis" in synthesized.source
    unestimated = clock_of(manifest(asked=100, timing={"fmax_mhz": None, "clock_mhz": 100, "clock_source": None},
                                    cost_model="asic-proxy"))
    assert unestimated.mhz == 100.0 and unestimated.source.endswith("; no Fmax estimate for this target")


def test_no_clock_asked_nor_estimated_gives_a_placeholder_that_says_so():
    clock = clock_of(manifest(timing={"fmax_mhz": None, "clock_mhz": None, "clock_source": None},
                              cost_model="asic-proxy"))
    assert clock.mhz == PLACEHOLDER_MHZ == 100.0
    assert clock.source.startswith("a PLACEHOLDER: no clock was asked and asic has no clock estimate")


@pytest.mark.parametrize("mhz", [0, -5, float("inf"), float("nan"), True, "100"])
def test_a_clock_must_be_positive_and_finite(mhz):
    with pytest.raises(ValueError, match=rf"clock mhz must be a positive finite number of MHz, not {re.escape(repr(mhz))}"):
        Clock(mhz, "test")


def test_the_sdc_clocks_clk_and_delays_every_other_port():
    config = get_block("fig7").config
    ports = port_map(config)
    text = sdc_text("tiny_fig7", Clock(41.06, "a test"), ports)
    assert text.startswith("# tiny_fig7_top: timing constraints in SDC")
    assert "# Clock clk: 41.06 MHz (period 24.355 ns), a test.\n" in text
    assert re.findall(r"^create_clock .*$", text, re.M) == ["create_clock -name clk -period 24.355 [get_ports clk]"]
    joined = text.replace("\\\n", " ")
    listed = {command: re.search(rf"^{command} 0 -clock clk \[get_ports \{{(.*?)\}}\]$", joined, re.M).group(1).split()
              for command in ("set_input_delay", "set_output_delay")}
    assert listed["set_input_delay"] == [p["name"] for p in ports if p["direction"] == "input"][1:]  # not clk
    assert listed["set_output_delay"] == [p["name"] for p in ports if p["direction"] == "output"]
    assert listed["set_input_delay"][:3] == ["rst", "in_valid", "out_ready"]
    assert listed["set_output_delay"][:2] == ["in_ready", "out_valid"]
    assert all(len(line) <= 96 for line in text.splitlines())


def test_the_lpf_gives_the_frequency_and_places_no_pin():
    text = lpf_text("tiny_fig7", Clock(41.06, "a test"))
    assert text.splitlines()[-1] == 'FREQUENCY PORT "clk" 41.06 MHz;'
    assert all(line.startswith("#") for line in text.splitlines()[:-1])
    assert "LOCATE" not in text.replace("No LOCATE or IOBUF line", "")


def test_the_ice40_script_adds_the_clock_when_nextpnr_runs_it():
    clocks = []

    class Context:  # what nextpnr passes as ctx to a --pre-pack script
        def addClock(self, net, mhz):  # noqa: N802 (nextpnr's name)
            clocks.append((net, mhz))

    exec(ice40_clock_text("tiny_fig7", Clock(123.4, "a test")), {"ctx": Context()})
    assert clocks == [("clk", 123.4)]


def test_the_nextpnr_sdc_holds_the_clock_alone():
    text = nextpnr_sdc_text("tiny_fig7", Clock(41.06, "a test"))
    assert [line for line in text.splitlines() if not line.startswith("#")] == [
        "create_clock -name clk -period 24.355 [get_ports clk]"]


def test_the_files_are_written_under_constraints(tmp_path):
    files = write_constraints(tmp_path, "m", Clock(50, "a test"), port_map(get_block("lirp").config))
    assert files == {"sdc": "constraints/m.sdc", "lpf": "constraints/m.lpf", "ice40": "constraints/m_ice40_clock.py",
                     "nextpnr": "constraints/m_nextpnr.sdc"}
    assert sorted(p.name for p in (tmp_path / "constraints").iterdir()) == [
        "m.lpf", "m.sdc", "m_ice40_clock.py", "m_nextpnr.sdc"]
    assert "create_clock -name clk -period 20 [get_ports clk]" in (tmp_path / files["sdc"]).read_text()


@pytest.mark.needs_yosys
@pytest.mark.needs_sta
def test_opensta_reads_the_sdc_against_a_synthesized_top(tmp_path):
    """The SDC's port names are the netlist's: OpenSTA links, applies the clock and the
    delays without a warning, and times the top at the period written."""
    from phongfx.explore.synth.asic import library_file
    from phongfx.explore.synth.toolrun import SynthError, run_yosys

    if shutil.which("sta") is None:
        pytest.skip("OpenSTA is not installed; apt-get install opensta")
    try:
        shutil.copyfile(library_file("osu018"), tmp_path / "cells.lib")
    except SynthError as missing:
        pytest.skip(str(missing))
    block = get_block("lirp")
    (tmp_path / "lirp_top.v").write_text(top_verilog(block.component(), "lirp"))
    (tmp_path / "synth.ys").write_text(  # OpenSTA 2.0 needs one-bit nets and gates as cells
        "read_verilog lirp_top.v\nsynth -flatten -top lirp_top\ndfflibmap -liberty cells.lib\n"
        "abc -liberty cells.lib\nopt_clean -purge\nsplitnets\nopt_clean -purge\n"
        "write_verilog -noattr -noexpr netlist.v\n")
    run_yosys(tmp_path, "synth.ys", outputs=("netlist.v",))
    (tmp_path / "lirp.sdc").write_text(sdc_text("lirp", Clock(250, "a test"), port_map(block.config)))
    (tmp_path / "sta.tcl").write_text("read_liberty cells.lib\nread_verilog netlist.v\nlink_design lirp_top\n"
                                      "read_sdc lirp.sdc\nreport_checks -path_delay max -digits 3\n"
                                      "report_clock_properties\nexit\n")
    ran = subprocess.run(["sta", "-no_init", "-no_splash", "sta.tcl"], cwd=tmp_path, capture_output=True, text=True,
                         timeout=120)
    out = ran.stdout + ran.stderr
    assert ran.returncode == 0 and not re.search(r"^(Warning|Error)", out, re.M), out
    assert re.search(r"^clk\s+4\.00\s+0\.00\s+2\.00$", out, re.M), out  # period, rising and falling edge
    assert "data required time" in out and "slack" in out


@pytest.mark.needs_yosys
@pytest.mark.slow
@pytest.mark.parametrize("arch, synth, options", [
    ("ecp5", "synth_ecp5", ["--25k", "--package", "CABGA381", "--lpf", "constraints/lirp.lpf",
                            "--lpf-allow-unconstrained"]),
    ("ice40", "synth_ice40", ["--hx8k", "--package", "ct256", "--sdc", "constraints/lirp_nextpnr.sdc",
                              "--pcf-allow-unconstrained"]),
])
def test_nextpnr_takes_the_clock_from_the_lpf_and_the_clock_only_sdc(tmp_path, arch, synth, options):
    from phongfx.explore.synth.toolrun import run, run_yosys, tool

    block = get_block("lirp")
    (tmp_path / "lirp_top.v").write_text(top_verilog(block.component(), "lirp"))
    write_constraints(tmp_path, "lirp", Clock(77.7, "a test"), port_map(block.config))
    (tmp_path / "synth.ys").write_text(f"read_verilog lirp_top.v\n{synth} -top lirp_top -json netlist.json\n")
    run_yosys(tmp_path, "synth.ys", outputs=("netlist.json",))
    code = run([tool(f"yowasp-nextpnr-{arch}"), "--json", "netlist.json", *options], tmp_path, "nextpnr.log")
    log = (tmp_path / "nextpnr.log.out").read_text()
    assert code == 0, log[-3000:]
    assert "Info: constraining clock net 'clk' to 77.70 MHz" in log
