"""Bad input at the command line never ends in a traceback, only in one clear line.

A hypothesis fuzz over argument lists and ``--set field=value`` configs for ``sim``,
``verilog``, ``render mesh``, ``synth``, ``sweep`` and ``tables`` proves that
:func:`phongfx.cli.main` returns 0, 1 or 2 without raising, that exit code 2 comes
with exactly one ``phongfx: error:`` line on stderr, and that a refused run leaves
nothing in the output folder it was given.  Directed cases pin the messages of the
errors the fuzz found (a sub-config set as a value, file-system errors, usage errors,
frames too large for memory).
"""

import dataclasses
import os
import pathlib
import re

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import phongfx.explore.synth.fpga as synth_module
import phongfx.sim.harness as harness
from phongfx.cli import main
from phongfx.core.registry import block_names, get_block

FUZZ = settings(max_examples=120, deadline=None, derandomize=True,
                suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
SMALL_BLOCKS = ("lirp", "normalize", "reflect", "difference", "shape", "diffuse", "spherical",
                "euler", "gouraud", "schlick")


class _Result:
    ok, cycles_per_second = True, 1.0

    def describe(self):
        return "0 mismatching cycle(s)"


def _golden_only_check(block, *, count, seed, **options):
    """Stand-in for the cycle-by-cycle check: the golden model on the block's vectors.

    Exercises everything a config reaches short of the simulator (vector generation,
    every quantize of the golden model) in milliseconds."""
    raw = block.stimulus(count=min(count, 16), seed=seed)
    block.golden({name: np.asarray(codes)[:256] for name, codes in raw.items()})
    return _Result()


def _fake_synth(name, **options):
    return {"block": name, "target": options["target"], "device": "45k", "lut4": 1, "ff": 1,
            "carry": 0, "dsp": 0, "bram_bits": 0, "fmax_mhz": 100.0, "pixels_per_second": 1e8,
            "latency": 1, "latency_ns": 10.0}


@pytest.fixture
def cheap(monkeypatch):
    monkeypatch.setattr(harness, "check", _golden_only_check)
    monkeypatch.setattr(synth_module, "synth", _fake_synth)


def _field_paths(config, prefix=""):
    for field in dataclasses.fields(config):
        value = getattr(config, field.name)
        yield prefix + field.name
        if dataclasses.is_dataclass(value):
            yield from _field_paths(value, f"{prefix}{field.name}.")


_FIELDS = sorted({path for name in block_names() for path in _field_paths(get_block(name).config)})
_INT64 = 2 ** 63
values = st.one_of(
    st.sampled_from(["S-1.3", "1.99", "x", "", "S1.10", "1.10", "S0.0", "0.0", "S64.0", "0.63",
                     "13.0", "S1.62", "true", "True", "1e3", "nan", "fig7", "fig9", "truncate",
                     "saturate", "S1.10.2", "S", ".", "=", " 3"]),
    st.builds(lambda s, i, f: f"{s}{i}.{f}", st.sampled_from(["", "S", "s", "U"]),
              st.integers(-3, 80), st.integers(-3, 80)),
    st.integers(-2 * _INT64, 2 * _INT64).map(str),
    st.sampled_from([-1, 0, 1, 2, 8, 63, 64, 8000, 8191, 8192, _INT64 - 1, _INT64, 10 ** 30]).map(str),
    st.text(alphabet="abS0123456789.-_= ", max_size=8),
)
names = st.one_of(st.sampled_from(_FIELDS), st.text(alphabet="abkmnt_.", min_size=0, max_size=8))
settings_list = st.lists(st.builds(lambda f, v: f"{f}={v}", names, values), min_size=1, max_size=3)
with_sets = st.builds(lambda sets: [arg for s in sets for arg in ("--set", s)], settings_list)


def _get(config, path):
    for part in path.split("."):
        config = getattr(config, part)
    return config


def _near(config, path):
    """Values close to the current one of ``path``: mostly valid, sometimes just past a bound."""
    value = _get(config, path)
    if isinstance(value, bool):
        return st.sampled_from(["True", "False"])
    if isinstance(value, int):
        return st.integers(-3, 3).map(lambda step: str(value + step))
    match = re.fullmatch(r"(S?)(\d+)\.(\d+)", str(value))
    if match:
        sign, whole, frac = match.group(1), int(match.group(2)), int(match.group(3))
        return st.builds(lambda i, f: f"{sign}{max(whole + i, 0)}.{max(frac + f, 0)}",
                         st.integers(-2, 2), st.integers(-3, 4))
    return values


@st.composite
def near_valid(draw, block):
    """``--set`` arguments that move one or two fields of ``block``'s config a little."""
    config = get_block(block).config
    paths = [p for p in _field_paths(config) if not dataclasses.is_dataclass(_get(config, p))]
    chosen = draw(st.lists(st.sampled_from(paths), min_size=1, max_size=2, unique=True))
    return [arg for path in chosen for arg in ("--set", f"{path}={draw(_near(config, path))}")]


def _run(argv, capsys, out_dir):
    """``main(argv)``: the exit code, checked against the stderr contract and the output folder."""
    code = main(argv)
    err = capsys.readouterr().err
    assert code in (0, 1, 2), (argv, code)
    assert "Traceback" not in err and (code == 2) == ("phongfx: error: " in err), (argv, code, err)
    if code == 2:
        lines = [line for line in err.splitlines() if line.startswith("phongfx: error: ")]
        # one line and nothing else (no usage above it), saying something
        assert err == lines[0] + "\n" and len(lines[0]) > 20, (argv, err)
        assert not out_dir.exists() or not any(out_dir.iterdir()), (argv, list(out_dir.iterdir()))
    return code


@FUZZ
@given(block=st.sampled_from(block_names()), sets=with_sets,
       extra=st.sampled_from([[], ["--vectors", "-1"], ["--seed", "-3"], ["--bubbles", "1"],
                              ["--bubbles", "nan"], ["--vectors", "x"], ["--backend", "nope"]]))
def test_fuzz_sim_configs(block, sets, extra, cheap, capsys, tmp_path):
    _run(["sim", block, *sets, *extra], capsys, tmp_path / "none")


@settings(FUZZ, max_examples=150)
@given(data=st.data(), block=st.sampled_from(block_names()))
def test_fuzz_sim_near_valid_configs(data, block, cheap, capsys, tmp_path):
    # mostly accepted configs: their vectors and golden model must run or refuse cleanly
    _run(["sim", block, *data.draw(near_valid(block))], capsys, tmp_path / "none")


@settings(FUZZ, max_examples=40)
@given(data=st.data(), block=st.sampled_from(SMALL_BLOCKS))
def test_fuzz_verilog_near_valid_configs(data, block, capsys, tmp_path_factory):
    out = tmp_path_factory.mktemp("v") / "out"
    code = _run(["verilog", block, *data.draw(near_valid(block)), "-o", str(out / "x.v")], capsys, out)
    assert (code == 0) == (out / "x.v").exists()


@settings(FUZZ, max_examples=60)
@given(block=st.sampled_from(SMALL_BLOCKS), sets=with_sets)
def test_fuzz_verilog_configs(block, sets, capsys, tmp_path_factory):
    out = tmp_path_factory.mktemp("v") / "out"
    code = _run(["verilog", block, *sets, "-o", str(out / "x.v")], capsys, out)
    assert (code == 0) == (out / "x.v").exists()


@FUZZ
@given(block=st.sampled_from(block_names()), sets=st.one_of(st.just([]), with_sets),
       extra=st.sampled_from([[], ["--freq", "-1"], ["--freq", "nan"], ["--target", "nope"],
                              ["--seed", "x"], ["--device", "1k"]]))
def test_fuzz_synth_configs(block, sets, extra, cheap, capsys, tmp_path):
    _run(["synth", block, *sets, *extra, "--quiet", "--workdir", str(tmp_path / "w")],
         capsys, tmp_path / "none")


big = ["-3", "0", "1", "7", "x", "1.5", str(_INT64), str(10 ** 8)]
mesh_args = st.lists(st.one_of(
    st.tuples(st.sampled_from(["--polygons", "--n", "--addr-bits", "--rom-bits", "--size", "--frame"]),
              st.sampled_from(big)),
    # a valid huge sphere would be slow, not wrong: only refusals for its resolution
    st.tuples(st.sampled_from(["--stacks", "--slices"]), st.sampled_from(["-3", "0", "1", "x", "1.5"])),
    st.tuples(st.sampled_from(["--method", "--mesh", "--figure"]),
              st.sampled_from(["nope", "", "phong", "sphere", "16"]))), min_size=1, max_size=3)


@settings(FUZZ, max_examples=80)
@given(args=mesh_args)
def test_fuzz_render_mesh(args, capsys, tmp_path_factory):
    out = tmp_path_factory.mktemp("m") / "out"
    # a tiny frame unless the fuzz overrides it: the point is the refusals
    _run(["render", "mesh", "--size", "8", "--polygons", "18", *[a for pair in args for a in pair],
          "--out", str(out)], capsys, out)


toml_text = st.one_of(
    st.sampled_from(['x = [\n', '[[grid]]\nmethod = \n', '[[grid]\n', 'scenes = "torus"\n',
                     '[[grid]]\nmethod = "fig9"\n', '[[grid]]\nmethod = "fig7"\nvec_frac = []\n',
                     '[[grid]]\nmethod = "fig7"\nvec_frac = [-1]\n', '[[grid]]\nmethod = "fig7"\nvec_frac = [99]\n',
                     '[[grid]]\nmethod = "fig7"\nnope = [1]\n', 'grid = 3\n', '[synth]\ntarget = "x"\n',
                     '\x00', '[[points]]\nmethod = 7\n', 'scenes = []\n[[grid]]\nmethod = "fig7"\n']),
    st.text(alphabet='[]="\n =.,abcdefgimnoprstv0123456789', max_size=40))


@settings(FUZZ, max_examples=100)
@given(text=toml_text)
def test_fuzz_sweep_specs(text, capsys, tmp_path_factory):
    folder = tmp_path_factory.mktemp("s")
    spec = folder / "spec.toml"
    spec.write_text(text)
    out = folder / "out"
    code = _run(["sweep", str(spec), "--out", str(out), "--workers", "1", "--quiet"], capsys, out)
    assert code == 2  # none of these specs holds a runnable point


@settings(FUZZ, max_examples=20)
@given(args=st.lists(st.sampled_from(["nope", "", "lyon", "--json", "--out", "-x", "cost9"]), max_size=3))
def test_fuzz_tables_names(args, capsys, tmp_path_factory):
    if any(a in ("lyon",) for a in args):
        args = [a for a in args if a != "lyon"] + ["nope"]  # a real table is slow; only refusals here
    _run(["tables", *args], capsys, tmp_path_factory.mktemp("t") / "none")


@pytest.mark.parametrize("argv, message", [
    (["sim", "fig7", "--set", "shape=1"],
     r"phongfx: error: --set shape: shape is a ShapeConfig; set one of its fields instead: "
     r"shape\.x2, shape\.k, shape\.t, shape\.rounding, shape\.pipeline\n"),
    (["render", "--set", "lirp=S1.10", "--out", "OUT"],
     r"phongfx: error: --set lirp: lirp is a LirpConfig; set one of its fields instead: lirp\.vec, .*\n"),
    # accepted by LirpConfig, but 1.0 (a unit span end) does not fit S0.10: the golden model raises
    (["sim", "lirp", "--set", "out=S0.10", "--vectors", "10"],
     r"phongfx: error: --set out=S0\.10: lirp N': \d+ value\(s\) overflow format S0\.10 \(range "
     r"-1\.0\.\.0\.9990234375\); first offending value 1\.0 \(raw 1024\); widen that format\n"),
    # valid fields whose intermediates outgrow int64: named by the setting, not the intermediate
    (["sim", "fig8", "--set", "normalize.z=1.40", "--vectors", "1"],
     r"phongfx: error: --set normalize\.z=1\.40: format S3\.80 is 84 bits wide; .*\n"),
    (["verilog", "fig8", "--set", "root.t=1.62", "-o", "OUT"],
     r"phongfx: error: --set root\.t=1\.62: format 2\.124 is 126 bits wide; .*\n"),
    (["sim", "shape", "--seed", "-1"], r"phongfx: error: --seed must be a non-negative integer, not -1\n"),
    (["sim", "shape", "--set", "t=S-1.3"],
     r"phongfx: error: t: format must look like 'n\.m' \(unsigned\) or 'Sn\.m' \(signed\), not 'S-1\.3'\n"),
    (["sim", "lirp", "--set", "vec=S1.70"], r"phongfx: error: vec: format S1\.70 is 72 bits wide; .*\n"),
    (["render", "mesh", "--size", "100000000", "--out", "OUT"],
     r"phongfx: error: --size must be an integer in 1\.\.8192, not 100000000\n"),
    (["sim", "shape", "--vectors", "x"], r"phongfx: error: sim: argument --vectors: "
                                         r"invalid int value: 'x' \(see phongfx sim --help\)\n"),
    (["verilog", "nosuch", "-o", "OUT"], r"phongfx: error: verilog: argument name: invalid choice: 'nosuch' "
                                         r"\(choose from .*'shader'\) \(see phongfx verilog --help\)\n"),
    (["frobnicate"], r"phongfx: error: argument command: invalid choice: 'frobnicate' .* "
                     r"\(see phongfx --help\)\n"),
    (["sweep", "MISSING", "--out", "OUT"], r"phongfx: error: sweep spec .*missing\.toml: no such file\n"),
    (["sweep", "DIR", "--out", "OUT"], r"phongfx: error: .*: Is a directory\n"),
])
def test_directed_refusals(argv, message, capsys, tmp_path):
    subs = {"OUT": str(tmp_path / "out"), "MISSING": str(tmp_path / "missing.toml"), "DIR": str(tmp_path)}
    assert main([subs.get(a, a) for a in argv]) == 2
    err = capsys.readouterr().err
    assert re.fullmatch(message, err, flags=re.S), err
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("argv, message", [
    (["--stalls", "1.5"], "--stalls must be a probability in [0, 1) (at 1 nothing would move), not 1.5"),
    (["--stalls", "-0.1"], "--stalls must be a probability in [0, 1) (at 1 nothing would move), not -0.1"),
    (["--stalls", "nan"], "--stalls must be a probability in [0, 1) (at 1 nothing would move), not nan"),
    (["--bubbles", "1"], "--bubbles must be a probability in [0, 1) (at 1 nothing would move), not 1"),
    (["--reset-at", "-2"], "--reset-at must be a cycle number, 0 or more, not -2"),
    (["--vectors", "-5"], "--vectors must be a non-negative integer, not -5"),
])
def test_sim_ranges_fail_before_any_build(argv, message, capsys, monkeypatch):
    def no_build(*args, **kwargs):
        raise AssertionError("a simulator was started for an argument out of range")
    monkeypatch.setattr(harness, "check", no_build)
    assert main(["sim", "shape", *argv]) == 2
    assert capsys.readouterr().err == f"phongfx: error: {message}\n"


@pytest.mark.parametrize("argv", [
    ["verilog", "shape", "-o", "FILE/x.v"],
    ["tables", "schlick", "--out", "FILE/plots"],
    ["render", "mesh", "--size", "8", "--polygons", "18", "--out", "FILE/mesh"],
    ["sweep", "SPEC", "--out", "FILE/sweep", "--workers", "1", "--quiet"],
    ["report", "--out", "FILE/report", "--tables", "schlick", "--quick"],
])
def test_output_folder_under_a_file_is_refused(argv, capsys, tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("not a folder")
    spec = tmp_path / "spec.toml"
    spec.write_text('scenes = ["torus"]\n[[grid]]\nmethod = "fig7"\nvec_frac = [8]\n')
    argv = [str(spec) if a == "SPEC" else a for a in argv]
    assert main([a.replace("FILE", str(blocker)) for a in argv]) == 2
    err = capsys.readouterr().err
    assert re.fullmatch(rf"phongfx: error: {re.escape(str(blocker))}.*: (Not a directory|File exists)\n", err), err
    assert blocker.read_text() == "not a folder"


def test_verilog_onto_a_folder_is_refused_and_leaves_no_temporary(capsys, tmp_path):
    (tmp_path / "x.v").mkdir()
    assert main(["verilog", "shape", "-o", str(tmp_path / "x.v")]) == 2
    assert capsys.readouterr().err == f"phongfx: error: {tmp_path / 'x.v'}: Is a directory\n"
    assert [p.name for p in tmp_path.iterdir()] == ["x.v"]


def test_unwritable_output_folder_is_refused_naming_the_target(capsys, tmp_path):
    # root ignores directory permissions: /proc takes no new files from anyone
    folder = tmp_path / "ro" if os.geteuid() else pathlib.Path("/proc")
    if os.geteuid():
        folder.mkdir()
        folder.chmod(0o500)
    target = folder / "phongfx-x.v"
    try:
        assert main(["verilog", "shape", "-o", str(target)]) == 2
        err = capsys.readouterr().err
        assert re.fullmatch(rf"phongfx: error: {re.escape(str(target))}: [^\n]+\n", err), err
        assert not target.exists() and not any(p.name.startswith(".phongfx-x.v") for p in folder.iterdir())
    finally:
        if os.geteuid():
            folder.chmod(0o700)


def test_help_returns_0_instead_of_raising(capsys):
    assert main(["--help"]) == 0
    assert capsys.readouterr().out.startswith("usage: phongfx")


def test_a_failed_synthesis_is_one_error_and_exit_1(monkeypatch, capsys):
    def failing(name, **options):
        raise synth_module.SynthError("design does not fit on LFE5U-25F: needs MULT18X18D 39/28; "
                                      "log /x/nextpnr.log:\nlast line")
    monkeypatch.setattr(synth_module, "synth", failing)
    assert main(["synth", "fig7", "--quiet"]) == 1
    err = capsys.readouterr().err
    assert err == ("phongfx: error: synthesis failed: design does not fit on LFE5U-25F: needs "
                   "MULT18X18D 39/28; log /x/nextpnr.log:\nlast line\n")
