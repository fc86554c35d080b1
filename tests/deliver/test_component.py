"""The compiled core as an Amaranth component: built from a compiled folder, simulated with
Amaranth's simulator inside a user's design, bit for bit against the golden model, under
back-pressure, at one pixel per clock and at one per two clocks (lights taking turns).

The default tier does not compile: ``two_lights.json`` holds what ``phongfx compile
scenes/two-lights.toml --methods conventional --throughput 20`` wrote in its manifest (the
design fields), and the session's folders are made from it.  The ``slow`` test compiles the
scene for real and runs its testbench's vectors and the documented example on the result.
"""

import copy
import dataclasses
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from amaranth.hdl import ClockDomain, Module, Shape
from amaranth.lib import data
from amaranth.sim import Simulator

import phongfx
from phongfx.deliver.component import ShadingCore, load_core
from phongfx.deliver.manifest import MANIFEST_VERSION

from tests.deliver.streams import TWO_LIGHTS, drive, golden_words, mismatches
from tests.docs.pages import blocks, matches

HERE = Path(__file__).resolve().parent
#: The documented example, and the output the page shows for it.
PAGE = "integration.rst"
EXAMPLE = "amaranth_example.py"


def _write(folder, manifest):
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "manifest.json").write_text(json.dumps(manifest, indent=2) + "\n")
    return folder


@pytest.fixture(scope="session")
def folders(tmp_path_factory):
    """``{interval: compiled folder}``: the two-lights design as compiled (interval 2) and at
    interval 1 (the lights side by side)."""
    root = tmp_path_factory.mktemp("compiled")
    one = copy.deepcopy(TWO_LIGHTS)
    one["config"]["interval"] = 1
    return {2: _write(root / "two", TWO_LIGHTS), 1: _write(root / "two-interval1", one)}


def _example():
    (block,) = [b for b in blocks(PAGE) if b.caption == EXAMPLE]
    shown = next(b for b in blocks(PAGE) if b.lineno > block.lineno and b.language == "text")
    return block.text, [line for line in shown.text.splitlines() if line.strip()]


# ---------------------------------------------------------------- the component's shape

def test_the_core_of_a_compiled_folder_has_the_tops_fields_as_stream_payloads(folders):
    core = phongfx.load_core(folders[2])
    assert isinstance(core, ShadingCore) and phongfx.load_core is load_core
    assert (core.name, core.latency, core.interval) == ("two_lights_conventional", 20, 2)
    vector = data.ArrayLayout(Shape(12, signed=True), 3)
    assert core.i.payload.shape() == data.StructLayout(
        {"normal": vector, "view": vector, "n": Shape(5), "c0_light": vector, "c1_light": vector})
    assert core.o.payload.shape() == data.StructLayout({"r": 8, "g": 8, "b": 8})
    assert repr(core.signature.members["i"]).startswith("In(stream.Signature(StructLayout({'normal'")
    assert core.manifest["module"] == "two_lights_conventional"
    # the same from the manifest file's path, and from the dict emit returns
    assert load_core(folders[2] / "manifest.json").config == core.config
    assert load_core(TWO_LIGHTS).config == core.config


# ---------------------------------------------------------------- simulated, bit for bit

@pytest.mark.parametrize("interval", [1, 2])
def test_random_pixels_stream_through_bit_for_bit_under_stalls_and_bubbles(folders, interval):
    """The golden model's codes of 200 random pixels and the stimulus' extremes, with ``o.ready``
    low 30 % of cycles and ``i.valid`` bubbles; every lib.stream rule held on every cycle."""
    core = load_core(folders[interval])
    raw = core.block.stimulus(count=200, seed=3)
    words, expected = golden_words(core, raw)
    run = drive(core, words, stalls=0.3, bubbles=0.2, seed=interval)
    count, rows = mismatches(core, run.words, expected)
    assert (len(run.words), count, run.breaks) == (len(words), 0, []), rows
    assert len(words) > 900 and run.stalled > 100
    gaps = np.diff(run.taken)
    assert gaps.min() == interval  # back to back where nothing stalls: one pixel per interval
    assert run.cycles >= len(words) * interval


def test_the_core_holds_while_the_sink_is_not_ready_and_drops_nothing(folders):
    """``o.ready`` low 90 % of the time: the pipeline stays full and holds, nothing is lost
    or repeated; built with the RTL overflow checks, whose flag (bit 24, above r, g, b)
    stays 0 on every pixel, as the golden model says."""
    core = load_core(folders[1], overflow=True)
    assert [name for name, _ in core.o.payload.shape()] == ["r", "g", "b", "overflow"]
    raw = core.block.stimulus(count=20, seed=4)
    words, expected = golden_words(core, raw)
    words, expected = words[:60], expected[:60]
    run = drive(core, words, stalls=0.9, bubbles=0.0, seed=5)
    assert (run.words, run.breaks) == (expected, [])
    assert run.stalled > 300


@pytest.mark.parametrize("interval", [1, 2])
def test_a_reset_drops_what_is_in_flight_and_the_core_starts_again(folders, interval):
    """``rst`` (the ``sync`` domain's) for one edge with pixels in flight and the sink stalled:
    no output is valid after it, ``i.ready`` is high, and the next pixels come out right."""
    core = load_core(folders[interval])
    words, expected = golden_words(core, core.block.stimulus(count=10, seed=6))
    seen = {}
    top = Module()  # the user's design: its own sync domain, whose reset the bench drives
    top.domains.sync = domain = ClockDomain("sync")
    top.submodules.core = core

    async def bench(ctx):
        ctx.set(core.o.ready, 0)
        for word in words[:6]:  # into the pipeline, none taken out
            ctx.set(core.i.payload.as_value(), word)
            ctx.set(core.i.valid, 1)
            await ctx.tick().until(core.i.ready)
        ctx.set(core.i.valid, 0)
        for _ in range(core.latency * interval):
            await ctx.tick()
        seen["before"] = ctx.get(core.o.valid)
        ctx.set(domain.rst, 1)
        await ctx.tick()
        ctx.set(domain.rst, 0)
        seen["after"] = (ctx.get(core.o.valid), ctx.get(core.i.ready))
        ctx.set(core.o.ready, 1)
        got = []
        for word in words[6:9]:
            ctx.set(core.i.payload.as_value(), word)
            ctx.set(core.i.valid, 1)
            await ctx.tick().until(core.i.ready)
        ctx.set(core.i.valid, 0)
        while len(got) < 3:
            _, _, valid, word = await ctx.tick().sample(core.o.valid, core.o.payload.as_value())
            if valid:
                got.append(word)
        seen["got"] = got

    sim = Simulator(top)
    sim.add_clock(1e-8)
    sim.add_testbench(bench)
    sim.run()
    assert seen == {"before": 1, "after": (0, 1), "got": expected[6:9]}


# ---------------------------------------------------------------- the documented example

def test_the_documented_example_runs_in_a_users_design_and_prints_what_the_page_shows(folders, tmp_path):
    code, shown = _example()
    script = tmp_path / EXAMPLE
    script.write_text(code + "\n")
    run = subprocess.run([sys.executable, str(script), str(folders[2])], capture_output=True, text=True,
                         timeout=300, cwd=tmp_path)
    assert run.returncode == 0, run.stderr[-3000:]
    missing = [line for line in shown if not matches(line, run.stdout)]
    assert not missing, f"missing {missing}\nin\n{run.stdout}"
    assert list(tmp_path.iterdir()) == [script]  # it writes nothing


# ---------------------------------------------------------------- a real compile (slow)

@pytest.fixture(scope="session")
def compiled(tmp_path_factory):
    """The two-lights scene compiled as ``two_lights.json`` was, with its testbench."""
    folder = tmp_path_factory.mktemp("real") / "two"
    run = subprocess.run([sys.executable, "-m", "phongfx.cli", "compile", "scenes/two-lights.toml", "-o", str(folder),
                          "--methods", "conventional", "--throughput", "20", "--testbench", "--no-check", "--quiet"],
                         cwd=HERE.parents[1], capture_output=True, text=True, timeout=1800)
    assert run.returncode == 0, run.stdout[-2000:] + run.stderr[-3000:]
    return folder


@pytest.mark.slow
def test_a_real_compile_gives_the_stored_design_and_passes_its_testbench_vectors_in_amaranth(compiled):
    manifest = json.loads((compiled / "manifest.json").read_text())
    assert {k: manifest[k] for k in TWO_LIGHTS} == TWO_LIGHTS  # the fast tier's data is current
    core = load_core(compiled)
    # one design: the shipped Verilog is the top of this core's block, after its header
    from phongfx.hdl.top import Top, shipped_verilog
    shipped = (compiled / manifest["top"]["file"]).read_text()
    assert shipped.endswith(shipped_verilog(Top(core.block.component(), core.name), core.name))
    bench = compiled / "testbench"
    words = [int(line, 16) for line in (bench / f"{core.name}_in.memh").read_text().split()]
    expected = [int(line, 16) for line in (bench / f"{core.name}_expected.memh").read_text().split()]
    run = drive(core, words, stalls=0.3, bubbles=0.2, seed=7)
    count, rows = mismatches(core, run.words, expected)
    assert (len(run.words), count, run.breaks) == (len(expected), 0, []), rows
    assert len(expected) == manifest["testbench"]["vectors"] > 5000
    code, shown = _example()
    run = subprocess.run([sys.executable, "-c", code, str(compiled)], capture_output=True, text=True, timeout=300)
    assert run.returncode == 0 and all(matches(line, run.stdout) for line in shown), run.stdout + run.stderr


# ---------------------------------------------------------------- from Python

def test_a_compile_in_python_gives_the_core_of_its_manifest_and_of_its_folder(tmp_path):
    """``compile_scene`` and ``emit`` on a small torus (its domain sampled sparsely): the
    manifest dict ``emit`` returns, the folder it wrote and the chosen design's config give
    one core, which shades like the golden model."""
    from phongfx.explore.compile.architecture import config_of
    from phongfx.compiler.compile import compile_scene
    from phongfx.compiler.request import CompileRequest
    from phongfx.explore.compile.emit import emit
    from phongfx.scene.file import parse_scene
    from tests.compiler.test_compile import TORUS

    compiled = compile_scene(CompileRequest(parse_scene(TORUS.format(error=1.0, against="phong"), name="tiny"),
                                            methods=["conventional"]))
    data = emit(compiled, tmp_path / "tiny", check=False)
    core = load_core(data)
    assert data["manifest_version"] == MANIFEST_VERSION and core.manifest is data
    assert core.config == load_core(tmp_path / "tiny").config == config_of(compiled.best, compiled.analysis)
    assert (core.name, core.latency, core.interval) == ("tiny_conventional", data["top"]["latency"], 1)
    words, expected = golden_words(core, core.block.stimulus(count=50, seed=2))
    run = drive(core, words, seed=3)
    assert (run.words, run.breaks) == (expected, [])


def test_a_config_gives_the_core_directly(folders):
    core = load_core(folders[1])
    again = ShadingCore(core.config, name="mine")
    assert (again.name, again.latency, again.interval, again.manifest) == ("mine", core.latency, 1, None)
    assert again.config == dataclasses.replace(core.config)
    with pytest.raises(ValueError, match=r"name must be an identifier \(the compiled module's\), not '1x'"):
        ShadingCore(core.config, name="1x")

