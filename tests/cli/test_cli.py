import json
import os
import re
import subprocess
import sys

import pytest

from phongfx.cli import apply_settings, main
from phongfx.config import fig7_config
from phongfx.core.registry import get_block


def test_blocks_lists_every_block(capsys):
    assert main(["blocks"]) == 0
    out = capsys.readouterr().out
    for name in ("lirp", "normalize", "reflect", "difference", "shape", "diffuse", "fig7"):
        assert f"\n{name} " in "\n" + out


def test_blocks_lines_fit_the_terminal_and_long_and_json_give_everything(capsys, monkeypatch):
    import json

    from phongfx.core.registry import block_names

    import sys

    monkeypatch.setenv("COLUMNS", "70")  # a pipe takes the full width whatever COLUMNS says
    assert main(["blocks"]) == 0
    piped = capsys.readouterr().out
    monkeypatch.setattr(sys.stdout, "isatty", lambda: True)
    monkeypatch.setenv("COLUMNS", "300")  # a wide terminal: still at most 100
    assert main(["blocks"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert max(map(len, lines)) <= 100 and len(lines) < 60  # fig7's repr alone was 1,312 characters
    assert lines[0] == "lirp             latency   2  vec=S1.10 a=1.10 out=S1.10 rounding=round_half_up pipeline=0"
    assert "normalize=NormalizeConfig(…)" in "\n".join(lines)
    assert piped.splitlines() == lines
    monkeypatch.setenv("COLUMNS", "70")
    assert main(["blocks"]) == 0
    assert max(map(len, capsys.readouterr().out.splitlines())) <= 70

    assert main(["blocks", "--long"]) == 0
    long = capsys.readouterr().out.splitlines()
    assert "    normalize.vec=S1.10" in long and "    units.0.specular=fig7" in long
    assert main(["blocks", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert [b["name"] for b in data] == list(block_names())
    fig7 = next(b for b in data if b["name"] == "fig7")
    assert fig7["latency"] == 17 and fig7["config"]["normalize"]["vec"] == "S1.10"


def test_verilog_writes_a_module(tmp_path):
    path = tmp_path / "shape.v"
    assert main(["verilog", "shape", "--set", "k=1", "-o", str(path)]) == 0
    text = path.read_text()
    assert "module shape(" in text and "o__payload" in text


@pytest.mark.needs_verilator
def test_sim_passes_and_reports(capsys):
    assert main(["sim", "lirp", "--vectors", "50", "--bubbles", "0.1"]) == 0
    assert "0 mismatching cycle(s)" in capsys.readouterr().out


@pytest.mark.needs_verilator
@pytest.mark.needs_yosys
def test_sim_of_the_ecp5_netlist_and_of_the_dsp_mapped_rtl(capsys):
    assert main(["sim", "lirp", "--set", "pipeline=3", "--netlist", "ecp5", "--vectors", "50"]) == 0
    out = capsys.readouterr().out
    assert "lirp on ecp5 netlist (45k, verilator-fast): " in out and "0 mismatching cycle(s)" in out
    assert main(["sim", "lirp", "--set", "pipeline=1", "--dsp", "ecp5", "--vectors", "50"]) == 0
    assert "0 mismatching cycle(s)" in capsys.readouterr().out


@pytest.mark.parametrize("argv, message", [
    (["--device", "45k"], "--device chooses the synthesis of --netlist; add --netlist ecp5|ice40"),
    (["--netlist", "ecp5", "--dsp", "ecp5"], "--netlist already maps the products as synthesis does; drop --dsp"),
    (["--netlist", "ice40", "--backend", "amaranth"],
     "--netlist is simulated by the verilator-fast back end, not amaranth"),
    (["--dsp", "ecp5", "--backend", "amaranth"],
     "--dsp instantiates DSP primitives, which only the Verilator back ends simulate"),
    (["--netlist", "ecp5", "--device", "up5k"], "device must be one of '25k', '45k', '85k' for ecp5, not 'up5k'"),
])
def test_sim_netlist_options_are_checked(argv, message, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(["sim", "lirp", "--vectors", "5", *argv]) == 2
    assert capsys.readouterr().err.endswith(f"phongfx: error: {message}\n")


def test_vcd_is_written(tmp_path):
    path = tmp_path / "lirp.vcd"
    assert main(["sim", "lirp", "--vectors", "5", "--backend", "amaranth", "--vcd", str(path)]) == 0
    assert path.read_text().startswith("$")


@pytest.mark.parametrize("argv, message", [
    (["sim", "shape", "--set", "k=11"], r"phongfx: error: k must be an integer in 0\.\.10, not 11\n"),
    (["sim", "shape", "--set", "q=1"], r"phongfx: error: --set q: ShapeConfig has no field 'q'; fields: x2, k, t, rounding, pipeline\n"),
    (["sim", "shape", "--set", "k=two"], r"phongfx: error: --set k: k must be an integer, not 'two'\n"),
    (["render", "--radius", "2", "--out", "OUT"], r"phongfx: error: radius must be an integer in 4\.\.4096, not 2\n"),
    (["sim", "fig7", "--set", "vec_frac=40"], r"phongfx: error: vec_frac must be an integer in 1\.\.23, not 40\n"),
    (["sim", "fig7", "--set", "vec_frac=ten"], r"phongfx: error: --set vec_frac: vec_frac must be an integer, not 'ten'\n"),
    (["sim", "fig7", "--set", "vecfrac=1"], r"phongfx: error: --set vecfrac: DatapathConfig has no field 'vecfrac'; "
                                            r"fields: .*, pipeline; derived settings: vec_frac\n"),
    (["sim", "shape", "--set", "vec_frac=12"], r"phongfx: error: --set vec_frac: ShapeConfig has no field 'vec_frac'; .*\n"),
])
def test_bad_input_exits_2_with_the_field_named(argv, message, capsys, tmp_path):
    argv = [str(tmp_path / "out") if a == "OUT" else a for a in argv]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert __import__("re").fullmatch(message, err), err
    assert not (tmp_path / "out").exists()  # nothing half-written


def test_one_vector_width_sets_every_connected_format():
    # set before or after the fields, the width lands on every connected vector format
    for settings in (["vec_frac=12", "shape.k=1"], ["shape.k=1", "vec_frac=12"]):
        config = apply_settings(fig7_config(), settings)
        assert config == fig7_config().replace(vec_frac=12).replace(shape=config.shape)
        assert config.shape.k == 1 and config.vec_frac == 12
        assert {config.lirp.out, config.normalize.vec, config.normalize.out, config.reflect.vec,
                config.reflect.out, config.difference.vec, config.diffuse.vec} == {"S1.12"}
        assert (config.normalize.z, config.reflect.dot, config.difference.dd) == ("1.14", "S1.14", "2.24")


def test_bool_settings_parse_true_and_false():
    config = apply_settings(get_block("conventional").config, ["local_light=true", "local_viewer=False"])
    assert config.local_light is True and config.local_viewer is False
    assert apply_settings(fig7_config(), ["local_viewer=TRUE", "lights=1"]).local_viewer is True
    with pytest.raises(ValueError, match=r"^--set local_light: local_light must be true or false, "
                                         r"not 'yes'$"):
        apply_settings(config, ["local_light=yes"])


def test_bool_setting_on_the_command_line(capsys):
    # the local light's normalizer is built and checked against the golden model
    argv = ["sim", "conventional", "--set", "local_light=true", "--vectors", "20", "--backend", "amaranth"]
    assert main(argv) == 0
    assert main(["sim", "conventional", "--set", "local_light=1"]) == 2
    err = capsys.readouterr().err
    assert err.endswith("phongfx: error: --set local_light: local_light must be true or false, not '1'\n")


def test_nested_settings():
    config = apply_settings(fig7_config(), ["shape.k=1", "lights=1", "shape.t=1.12"])
    assert (config.shape.k, config.lights, config.shape.t) == (1, 1, "1.12")


def test_console_script_exit_code():
    # the installed entry point, as a user runs it
    proc = subprocess.run([os.path.join(os.path.dirname(sys.executable), "phongfx"), "sim", "fig7",
                           "--set", "lights=0"], capture_output=True, text=True)
    assert proc.returncode == 2 and proc.stderr.startswith("phongfx: error: lights must be")


def test_tables_schlick_prints_figure1(tmp_path, capsys):
    assert main(["tables", "schlick", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert out.startswith("# Figure 1, measured")
    assert "| 1 | 0.00000 |" in out and "| 64 | 0.199" in out
    assert (tmp_path / "figure1.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.parametrize("argv, message", [
    (["render", "mesh", "--method", "nope", "--out", "OUT"],
     r"phongfx: error: method must be one of phong, gouraud-float, euler-float, corrected-euler, cosn, "
     r"cos2, spherical, euler, gouraud, blinn, conventional, not 'nope'\n"),
    (["render", "frames", "--units", "euler", "nope", "--out", "OUT"],
     r"phongfx: error: unit must be one of spherical, euler, gouraud, schlick, blinn, conventional, "
     r"not 'nope'\n"),
])
def test_render_targets_refuse_bad_names_and_write_nothing(argv, message, capsys, tmp_path):
    argv = [str(tmp_path / "out") if a == "OUT" else a for a in argv]
    assert main(argv) == 2
    assert __import__("re").fullmatch(message, capsys.readouterr().err)
    assert not (tmp_path / "out").exists()


def test_render_mesh_writes_a_png_and_reports_its_error(tmp_path, capsys):
    assert main(["render", "mesh", "--method", "corrected-euler", "--polygons", "288", "--size", "64",
                 "--out", str(tmp_path)]) == 0
    summary = __import__("json").loads(capsys.readouterr().out)
    assert (tmp_path / "torus288-corrected-euler-n20-f0.png").stat().st_size > 0
    assert summary["pixels"] > 1000 and summary["error_8bit"]["diffuse"]["max"] < 2


def _accepted_names():
    from phongfx.explore.synth.asic import LIBRARIES
    from phongfx.core.methods import METHODS as COMPILE_METHODS
    from phongfx.explore.synth.fpga import ALL_TARGETS
    from phongfx.explore.tables import TABLES
    from phongfx.render.mesh import RENAMED, SHADED
    from phongfx.scene.span_inputs import units
    return [(["render", "mesh", "--help"], [*SHADED, *RENAMED]), (["render", "frames", "--help"], units()),
            (["render", "--help"], ["frames"]), (["tables", "--help"], TABLES), (["--help"], TABLES),
            (["synth", "--help"], [*ALL_TARGETS, *LIBRARIES]), (["compile", "--help"], COMPILE_METHODS)]


def test_help_names_every_accepted_value(capsys, monkeypatch):
    """The hand-written lists had lost extremes, cos2, euler-unit, gouraud-unit and conventional."""
    monkeypatch.setenv("COLUMNS", "2000")  # one line per option: no name split at its hyphen
    for argv, names in _accepted_names():
        assert main(argv) == 0
        text = capsys.readouterr().out
        missing = [name for name in names if not re.search(rf"(?<![\w-]){re.escape(name)}(?![\w-])", text)]
        assert not missing, f"phongfx {' '.join(argv)} does not name {missing}"


def test_render_out_applies_to_its_targets(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)  # where the target's own default would have written
    out = tmp_path / "chosen"
    assert main(["render", "--out", str(out), "mesh", "--polygons", "288", "--size", "16"]) == 0
    assert sorted(p.name for p in out.iterdir()) == ["torus288-phong-n20-f0.png", "torus288-phong-n20-f0_error.png"]
    assert not (tmp_path / "build").exists()


@pytest.mark.parametrize("argv, message", [
    (["render", "--out", "A", "mesh", "--out", "B"], "render --out A and render mesh --out B disagree; give one"),
    (["render", "--set", "shape.k=1", "mesh"], "render --set applies to Lyon's scene, not to render mesh; drop it"),
    (["render", "--radius", "6", "frames"], "render --radius applies to Lyon's scene, not to render frames; drop it"),
    (["render", "--speed-sample", "10", "mesh"],
     "render --speed-sample applies to Lyon's scene, not to render mesh; drop it"),
    (["render", "--speed-sample", "-1"], "speed sample must be a non-negative integer, not -1"),
    (["render", "--backend", "amaranth", "mesh"],
     "render --backend applies to Lyon's scene and frames (mesh runs no RTL), not to render mesh; drop it"),
    (["render", "--backend", "amaranth", "frames", "--backend", "verilator"],
     "render --backend amaranth and render frames --backend verilator disagree; give one"),
])
def test_render_options_a_target_would_ignore_are_refused(argv, message, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(argv) == 2
    assert capsys.readouterr().err == f"phongfx: error: {message}\n"
    assert list(tmp_path.iterdir()) == []


def test_render_mesh_former_unit_name_works_with_a_note(tmp_path, capsys):
    assert main(["render", "mesh", "--method", "gouraud-unit", "--polygons", "288", "--size", "16",
                 "--out", str(tmp_path)]) == 0
    captured = capsys.readouterr()
    assert captured.err == ("phongfx: note: --method gouraud-unit is now called gouraud (the fixed-point unit, "
                            "named as in compile; the float gouraud is gouraud-float)\n")
    assert json.loads(captured.out)["method"] == "gouraud"


@pytest.mark.needs_verilator
def test_render_frames_checks_the_rtl(tmp_path, capsys):
    assert main(["render", "frames", "--units", "gouraud", "--size", "32", "--quiet",
                 "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "| gouraud |" in out and "Total mismatches 0" in out
    assert (tmp_path / "frames.json").exists()


def test_synth_prints_the_table_and_refuses_a_bad_target(monkeypatch, capsys):
    import phongfx.explore.synth.fpga as synth_module
    calls = []

    def fake(name, **options):
        calls.append((name, options["target"], options["freq"], options["config"].k))
        return {"block": name, "target": options["target"], "device": "45k", "lut4": 17, "ff": 35,
                "carry": 22, "dsp": 1, "bram_bits": 0, "fmax_mhz": 114.7, "pixels_per_second": 114.7e6,
                "latency": 2, "latency_ns": 17.4}
    monkeypatch.setattr(synth_module, "synth", fake)
    assert main(["synth", "shape", "--set", "k=1", "--freq", "200", "--quiet"]) == 0
    assert calls == [("shape", "ecp5", 200.0, 1)]
    assert "| shape | ecp5 | 45k | 17 | 35 | 22 | 1 |" in capsys.readouterr().out
    monkeypatch.undo()
    assert main(["synth", "shape", "--target", "nope", "--quiet"]) == 2
    assert capsys.readouterr().err == "phongfx: error: target must be one of 'ecp5', 'ice40', 'asic', not 'nope'\n"


def test_synth_asic_prints_area_and_json(capsys, asic_tools):
    # the per-user cache: the same synthesis as test_asic's osu035 run, done once
    assert main(["synth", "shape", "--set", "t=1.7", "--target", "asic", "--library", "osu035", "--quiet"]) == 0
    text = capsys.readouterr().out
    assert text.startswith("| block | library | area µm² | cells | FF | Fmax MHz |")
    assert "| shape | osu035 |" in text and "worst path" in text
    assert main(["synth", "shape", "--set", "t=1.7", "--target", "asic", "--device", "osu035", "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert result["cached"] is True and result["library"] == "osu035" and result["area_um2"] > 0
    assert result["fmax_mhz"] == pytest.approx(1000 / result["critical_path"]["ns"])


@pytest.mark.parametrize("argv, message", [
    (["--library", "osu018"], "--library applies to --target asic only, not to 'ecp5' (use --device for an "
                              "FPGA part)"),
    (["--target", "asic", "--library", "osu018", "--device", "osu035"],
     "--device 'osu035' and --library 'osu018' disagree; give one"),
    (["--target", "asic", "--library", "tsmc7"], "library must be one of 'osu018', 'osu035' for asic, not 'tsmc7'"),
])
def test_synth_bad_library_options(argv, message, capsys, tmp_path):
    assert main(["synth", "shape", *argv, "--quiet", "--workdir", str(tmp_path)]) == 2
    assert capsys.readouterr().err == f"phongfx: error: {message}\n"
    assert not any(tmp_path.iterdir())


def test_sweep_writes_csv_plot_and_summary_and_resumes(tmp_path, capsys):
    spec = tmp_path / "spec.toml"
    spec.write_text('scenes = ["torus"]\n[[grid]]\nmethod = "fig7"\nvec_frac = [8, 10]\n')
    out = tmp_path / "out"
    assert main(["sweep", str(spec), "--out", str(out), "--workers", "1", "--quiet"]) == 0
    assert "2 point(s) run (2 ok, 0 failed), 0 already done, of 2" in capsys.readouterr().out
    assert {p.name for p in out.iterdir()} >= {"points.jsonl", "points.csv", "pareto.png", "summary.md"}
    assert "torus.self.max" in (out / "summary.md").read_text()
    assert main(["sweep", str(spec), "--out", str(out), "--workers", "1", "--quiet"]) == 0
    assert "0 point(s) run (0 ok, 0 failed), 2 already done, of 2" in capsys.readouterr().out


def test_sweep_refuses_a_bad_spec_with_exit_2(tmp_path, capsys):
    spec = tmp_path / "spec.toml"
    spec.write_text('[[grid]]\nmethod = "fig9"\n')
    assert main(["sweep", str(spec), "--out", str(tmp_path / "out"), "--quiet"]) == 2
    assert capsys.readouterr().err.startswith("phongfx: error: ")
    assert not (tmp_path / "out").exists()


def test_verilog_top_writes_the_named_port_top(tmp_path):
    path = tmp_path / "lirp_top.v"
    assert main(["verilog", "lirp", "--top", "-o", str(path)]) == 0
    text = path.read_text()
    assert text.startswith("// lirp_top: ") and "module lirp_top(" in text
    assert "input  in_n0_x     12  S1.10" in text and "out_overflow" not in text


@pytest.mark.needs_iverilog
def test_testbench_writes_and_passes_under_icarus(tmp_path, capsys):
    import re

    out = tmp_path / "tb"
    assert main(["testbench", "diffuse", "-o", str(out), "--count", "5", "--seed", "3", "--run", "icarus",
                 "--quiet"]) == 0
    text = capsys.readouterr().out
    files = "diffuse_top.v, tb_diffuse.v, diffuse_in.memh, diffuse_expected.memh, run.sh, README.txt"
    assert text.startswith(f"wrote {out}: {files} (")
    assert re.search(r"^icarus \([0-9.]+ s\):\n  PASS \d+ vectors, \d+ cycles", text, re.M), text


@pytest.mark.parametrize("argv, message", [
    (["--count", "-1"], "--count must be an integer in 0..1000000, not -1"),
    (["--seed", "-2"], "--seed must be a non-negative integer, not -2"),
    (["--stall", "1"], "--stall must be a probability in 0..0.95, not 1.0"),
    (["--bubbles", "nan"], "--bubbles must be a probability in 0..0.95, not nan"),
    (["--set", "k=11"], "k must be an integer in 0..10, not 11"),
    (["--set", "q=1"], "--set q: ShapeConfig has no field 'q'; fields: x2, k, t, rounding, pipeline"),
])
def test_testbench_bad_input_exits_2_and_writes_nothing(argv, message, capsys, tmp_path):
    assert main(["testbench", "shape", "-o", str(tmp_path / "out"), "--quiet", *argv]) == 2
    assert capsys.readouterr().err == f"phongfx: error: {message}\n"
    assert list(tmp_path.iterdir()) == []


def test_testbench_refuses_a_missing_simulator_before_writing(capsys, tmp_path, monkeypatch):
    import shutil

    monkeypatch.setattr(shutil, "which", lambda tool: None)
    assert main(["testbench", "lirp", "-o", str(tmp_path / "out"), "--run", "both", "--quiet"]) == 2
    assert capsys.readouterr().err == ("phongfx: error: iverilog: Icarus Verilog is not installed (iverilog, "
                                       "vvp not on PATH); install it with: apt-get install iverilog\n")
    assert list(tmp_path.iterdir()) == []


def test_testbench_into_a_file_is_refused(capsys, tmp_path):
    path = tmp_path / "file"
    path.write_text("")
    assert main(["testbench", "diffuse", "-o", str(path), "--count", "0", "--quiet"]) == 2
    assert capsys.readouterr().err == f"phongfx: error: {path}: Not a directory\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["file"]
