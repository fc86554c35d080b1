"""Any Liberty file (phongfx.explore.synth.liberty): its facts read from the file itself, the
cells the mapper must not use, and the errors that name the file and what is missing; the
command line's --liberty checks before any work."""

import pytest

from phongfx.cli.commands import target_device
from phongfx.explore.synth.asic import LIBRARIES, library_name
from phongfx.explore.synth.fpga import SynthError, synth
from phongfx.explore.synth.liberty import LibertyError, dont_use, read_liberty

TINY = """library (tiny_lib) {
  time_unit : "1ps";
  nom_process : 1;
  nom_voltage : 0.9;
  nom_temperature : 85;
  cell (INV) {
    area : 1.0;
    pin (A) { direction : input; }
    pin (Y) { direction : output; function : "!A"; }
  }
%s}
"""
FLOP = """  cell (DFQ) {
    area : 4.0;
    ff (IQ, IQN) { next_state : "D"; clocked_on : "CK"; }
  }
  cell (FILLER1) { area : 0.5; }
"""


def test_sg13g2_typical_facts(sg13g2):
    facts = read_liberty(sg13g2 / "sg13g2_stdcell_typ_1p20V_25C.lib")
    assert (facts.name, facts.corner, facts.time_unit_ns) == ("sg13g2_stdcell_typ_1p20V_25C",
                                                             "1.20 V, 25 °C, process 1", 1.0)
    assert len(facts.cells) == 84
    assert facts.sequential[:3] == ("sg13g2_dfrbp_1", "sg13g2_dfrbp_2", "sg13g2_dfrbpq_1")
    assert len(facts.sequential) == 14  # 4 flip-flops, 5 latches, 5 scan flip-flops
    assert dont_use(facts) == (
        "sg13g2_antennanp", "sg13g2_decap_4", "sg13g2_decap_8", "sg13g2_dlygate4sd1_1", "sg13g2_dlygate4sd2_1",
        "sg13g2_dlygate4sd3_1", "sg13g2_fill_1", "sg13g2_fill_2", "sg13g2_fill_4", "sg13g2_fill_8",
        "sg13g2_lgcp_1", "sg13g2_sdfbbp_1", "sg13g2_sighold", "sg13g2_slgcp_1", "sg13g2_tiehi", "sg13g2_tielo")
    # the file's own dont_use marks are among them
    assert facts.dont_use == ("sg13g2_antennanp", "sg13g2_decap_4", "sg13g2_decap_8", "sg13g2_fill_1",
                              "sg13g2_fill_2", "sg13g2_fill_4", "sg13g2_fill_8", "sg13g2_lgcp_1", "sg13g2_sdfbbp_1",
                              "sg13g2_sighold", "sg13g2_slgcp_1")


def test_sg13g2_corners(sg13g2):
    corners = [read_liberty(sg13g2 / f"sg13g2_stdcell_{c}.lib").corner
               for c in ("slow_1p08V_125C", "fast_1p32V_m40C")]
    assert corners == ["1.08 V, 125 °C, process 1", "1.32 V, -40 °C, process 1"]
    assert library_name(sg13g2 / "sg13g2_stdcell_slow_1p08V_125C.lib") == "sg13g2_stdcell_slow_1p08V_125C"


def test_osu018_keeps_its_name_and_every_cell():
    assert library_name("osu018") == "osu018" and library_name(None) == "osu018"
    path = LIBRARIES["osu018"].path
    try:
        facts = read_liberty(path)
    except LibertyError:
        pytest.skip("the OSU cells are not installed")
    assert facts.sequential == ("DFFNEGX1", "DFFPOSX1", "DFFSR", "LATCH") and dont_use(facts) == ()


def test_any_liberty_file_its_own_facts(tmp_path):
    path = tmp_path / "tiny.lib"
    path.write_text(TINY % FLOP)
    facts = read_liberty(path)
    assert (facts.name, facts.corner, facts.time_unit_ns) == ("tiny_lib", "0.90 V, 85 °C, process 1", 1e-3)
    assert (facts.cells, facts.sequential, dont_use(facts)) == (("INV", "DFQ", "FILLER1"), ("DFQ",), ("FILLER1",))
    assert facts.buffer is None  # an inverter is no buffer: mapped without buffering


BUFFERS = """  cell (BUF4) {
    area : 3.0;
    pin (A) { direction : input; capacitance : 0.004; }
    pin (Y) { direction : output; function : "A"; }
  }
  cell (BUF1) {
    area : 2.0;
    pin ("A") { direction : "input"; capacitance : 0.001; }
    pin ("Y") { direction : "output"; function : "(A)"; }
  }
  cell (AND2) {
    area : 1.5;
    pin (A) { direction : input; capacitance : 0.001; }
    pin (B) { direction : input; capacitance : 0.001; }
    pin (Y) { direction : output; function : "A"; }
  }
"""


def test_the_smallest_buffer_is_what_abc_buffers_with(tmp_path):
    path = tmp_path / "buffers.lib"
    path.write_text(TINY % (FLOP + BUFFERS))
    assert read_liberty(path).buffer == ("BUF1", 0.001)  # the smaller; AND2 has two inputs
    path.write_text(TINY % (FLOP + BUFFERS.replace("BUF1", "dlybuf1")))
    assert read_liberty(path).buffer == ("BUF4", 0.004)  # a delay cell is not for synthesis
    try:
        osu018 = read_liberty(LIBRARIES["osu018"].path)
    except LibertyError:
        pytest.skip("the OSU cells are not installed")
    assert osu018.buffer == ("BUFX2", 0.00933171)


@pytest.mark.parametrize("text, message", [
    (None, "Liberty file {path} does not exist"),
    ("module top; endmodule\n", "{path} is not a Liberty file: no 'library (NAME) {{' group in its first 20,000 "
                                "characters"),
    (TINY % "", "{path} (tiny_lib) has no usable flip-flop cell: no cell with an 'ff' or 'latch' group outside "
                "the dont_use ones (none)"),
    (TINY.replace('  time_unit : "1ps";\n', "") % FLOP, "{path} gives no library-level time_unit"),
    (TINY.replace("1ps", "3ps") % FLOP, "{path}: time_unit must be one of 1ps, 10ps, 100ps, 1ns, 10ns, 1us, "
                                        "not '3ps'"),
    (TINY.replace("nom_voltage : 0.9", "nom_voltage : high") % FLOP, "{path}: nom_voltage must be a number, "
                                                                     "not 'high'"),
])
def test_bad_files_are_named_with_what_is_missing(tmp_path, text, message):
    path = tmp_path / "cells.lib"
    if text is not None:
        path.write_text(text)
    with pytest.raises(LibertyError) as error:
        read_liberty(path)
    assert str(error.value).startswith(message.format(path=path))


def test_synth_refuses_a_bad_file_before_any_work(tmp_path):
    with pytest.raises(SynthError, match=f"^Liberty file {tmp_path}/none.lib does not exist$"):
        synth("shape", target="asic", device=str(tmp_path / "none.lib"))


def test_command_line_liberty_checks(tmp_path, sg13g2):
    typical = str(sg13g2 / "sg13g2_stdcell_typ_1p20V_25C.lib")
    assert target_device("asic", None, None, typical) == typical
    with pytest.raises(ValueError, match="^--liberty applies to --target asic only, not to 'ecp5'"):
        target_device("ecp5", None, None, typical)
    with pytest.raises(ValueError, match=f"^--liberty '{typical}' and --library 'osu018' both name the cells; "
                                         f"give one$"):
        target_device("asic", None, "osu018", typical)
    with pytest.raises(LibertyError, match=f"^Liberty file {tmp_path}/x.lib does not exist$"):
        target_device("asic", None, None, str(tmp_path / "x.lib"))


def test_the_proxies_refuse_an_uncalibrated_library(tmp_path):
    from phongfx.core.registry import get_block
    from phongfx.explore.synth.clock import proxy_clock
    from phongfx.explore.synth.proxy import proxy_area

    path = tmp_path / "tiny.lib"
    path.write_text(TINY % FLOP)
    block = get_block("shape")
    with pytest.raises(ValueError, match=r"^library must be one of 'osu018', .*, not 'tiny_lib' \(Liberty file "
                                         rf"{tmp_path}/tiny.lib\): fit its area proxy with `phongfx tables proxy "
                                         r"--liberty FILE --refit`$"):
        proxy_area(block, str(path))
    with pytest.raises(ValueError, match=r"^device must be one of osu018.* for the asic clock proxy, not 'tiny_lib': "
                                         r"fit it with `phongfx tables clock --liberty FILE --refit`$"):
        proxy_clock(block, "asic", str(path))


@pytest.mark.parametrize("table, options", [
    ("clock", {"device": "{typ}"}),
    ("proxy", {"library": "{typ}"}),
    ("cost", {"target": "asic", "device": "{typ}"}),
])
def test_tables_take_a_liberty_file(monkeypatch, capsys, sg13g2, table, options):
    import importlib

    from phongfx.cli import main

    typ = str(sg13g2 / "sg13g2_stdcell_typ_1p20V_25C.lib")
    module = importlib.import_module(f"phongfx.explore.tables.{table}")
    seen = {}
    monkeypatch.setattr(module, "run_table", lambda name, out_dir=None, **given: seen.update(given) or {})
    monkeypatch.setattr(module, "to_json", lambda result: "{}")
    assert main(["tables", table, "--liberty", typ, "--json"]) == 0
    assert seen == {k: v.format(typ=typ) for k, v in options.items()}
