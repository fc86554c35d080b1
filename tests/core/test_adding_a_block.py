"""Adding a block is four source modules named after it, their tests, and one registry entry;
adding a method (a specular unit of the datapath, or a standalone unit) is its faces and one
method entry more.

This test adds a block ``toy`` (an exact dot product ``N·L``, one register) the way the
README's "Adding a block" says, without touching any other file: its config, golden,
hdl and stimulus modules are made from source text under the names the registry's
naming rule gives them (``phongfx.config.toy``, ``phongfx.golden.toy``,
``phongfx.hdl.toy``, ``phongfx.sim.stimulus.toy``), and one :class:`Entry` goes into
``REGISTRY``.  Then the command line lists, emits and checks it, and the extremes table
runs its rows, golden against RTL, like any other block's.
"""

import re
import sys
import textwrap
import types
from pathlib import Path

import numpy as np
import pytest

from phongfx.cli import main
from phongfx.core.methods import METHODS, Method
from phongfx.core.registry import REGISTRY, Entry, get_block
from phongfx.explore.tables.extremes import run_block
from phongfx.sim.harness import check

ROOT = Path(__file__).resolve().parents[2]

SOURCES = {
    "phongfx.config.toy": '''
        from dataclasses import dataclass

        from phongfx.config.base import BlockConfig, check_format

        @dataclass(frozen=True)
        class ToyConfig(BlockConfig):
            vec: str = "S1.10"

            INPUTS = {"n": ("vec", 3), "l": ("vec", 3)}
            OUTPUTS = {"dot": ("out", 1)}

            @property
            def out(self):
                """The exact format of three products summed (the adder tree grows)."""
                product = self.fmt("vec").mul(self.fmt("vec"))
                return str(product.add(product).add(product))

            def validate(self):
                check_format("vec", self.vec, signed=True)
        ''',
    "phongfx.golden.toy": '''
        def toy(config, n, l):
            return {"dot": n.dot(l)}
        ''',
    "phongfx.hdl.toy": '''
        from phongfx.config.toy import ToyConfig
        from phongfx.hdl.block import PipelinedBlock
        from phongfx.hdl.fixed import stage

        class Toy(PipelinedBlock):
            """Latency: 1 (the sum is registered)."""

            config_class = ToyConfig
            latency = 1

            def datapath(self, m, i):
                return {"dot": stage(m, i["n"].dot(i["l"]), "dot")}
        ''',
    "phongfx.sim.stimulus.toy": '''
        import numpy as np

        from phongfx.sim.stimulus import AXES, codes, random_codes, rng
        from phongfx.sim.stimulus.extreme import Extreme, exactly

        def stimulus(config, count=1000, seed=0):
            vec, g = config.fmt("vec"), rng(seed)
            return {"n": random_codes(vec, (count, 3), g), "l": random_codes(vec, (count, 3), g)}

        def extremes(block_name):
            return (Extreme(block_name, "N = L on the axes", "1.0 exactly",
                            lambda c: {"n": codes(AXES, c.vec), "l": codes(AXES, c.vec)},
                            exactly("dot", 1.0)),)
        ''',
}


@pytest.fixture
def toy(monkeypatch):
    for name, source in SOURCES.items():  # dependencies first: the order of SOURCES
        module = types.ModuleType(name)
        monkeypatch.setitem(sys.modules, name, module)
        exec(compile(textwrap.dedent(source), f"<{name}>", "exec"), module.__dict__)
    monkeypatch.setitem(REGISTRY, "toy", Entry(  # the one entry
        "toy", "phongfx.config.toy:ToyConfig", "phongfx.golden.toy:toy", "phongfx.hdl.toy:Toy",
        "phongfx.sim.stimulus.toy:stimulus", "phongfx.sim.stimulus.toy:extremes"))
    return get_block("toy")


def test_a_new_block_is_a_block_like_any_other(toy, capsys, tmp_path):
    assert toy.latency == 1 and str(toy.config.fmt("out")) == "S5.20"
    raw = toy.stimulus(count=100, seed=3)
    assert (toy.golden(raw)["dot"] == (raw["n"] * raw["l"]).sum(axis=-1)).all()
    assert check(toy, raw, backend="amaranth").ok

    assert main(["blocks"]) == 0
    assert re.search(r"^toy +latency +1 ", capsys.readouterr().out, re.M)
    assert main(["verilog", "toy", "-o", str(tmp_path / "toy.v")]) == 0
    assert "module toy(" in (tmp_path / "toy.v").read_text()
    assert main(["sim", "toy", "--backend", "amaranth", "--vectors", "20"]) == 0
    assert "0 mismatching cycle(s)" in capsys.readouterr().out

    (row,), _ = run_block("toy")
    assert (row["block"], row["golden"], row["rtl"]) == ("toy", "pass", "pass")


# ---------------------------------------------------------------- a specular unit
#
# A specular unit of Lyon's datapath is one entry of the method registry
# (phongfx.core.methods.METHODS) and one of the block registry, naming its faces: what the
# config knows of it (a SpecularUnit: links, shininess port, sweep parameters), its golden
# model and its hardware inside the datapath; the sweep run, the compiler hooks and the mesh
# shading of every datapath serve it as they are, and its float form is one string.  The toy
# unit below is Phong with n = 1 (max(R·L, 0)): the reflected R of Figure 7 and Lambert's
# block on (R, L), with no shininess port.  A real new unit writes its three faces in the
# files of its own block (config/NAME.py, golden/NAME.py, hdl/NAME.py); here they are made
# from source text, like the toy block's.

UNIT_SOURCES = {
    "toyspec_config": '''
        from phongfx.config.base import SpecularUnit
        from phongfx.config.datapath import DatapathConfig

        class ReflectedLambert(SpecularUnit):
            parts = ("reflect",)  # and diffuse, which every datapath has

            def links(self, c):
                return [("normalize.out", c.normalize.out, "reflect.vec", c.reflect.vec),
                        ("reflect.out", c.reflect.out, "diffuse.vec", c.diffuse.vec)]

            def shininess_const(self, c):
                return 1

            def applied_n(self, c, n):
                return n * 0 + 1.0

            def spec_format(self, c):
                return c.diffuse.fmt("out")

            def fit(self, config, n_hi, n_const):
                return config

        UNIT = ReflectedLambert()

        def toy_datapath_config(**changes):
            return DatapathConfig(specular="toy", **changes)
        ''',
    "toyspec_golden": '''
        from phongfx.golden.diffuse import diffuse
        from phongfx.golden.reflect import reflect

        def toy(config, normal, view, lights, shininess):
            r = reflect(config.reflect, normal, view)["r"]
            return [diffuse(config.diffuse, r, light)["diff"] for light in lights]
        ''',
    "toyspec_hdl": '''
        from phongfx.hdl.datapath import ReflectedUnit
        from phongfx.hdl.diffuse import Diffuse
        from phongfx.hdl.reflect import Reflect

        class ToyUnit(ReflectedUnit):
            spec_port = "diff"

            def __init__(self, c):
                super().__init__(c, [Reflect(c.reflect)], [[Diffuse(c.diffuse)] for _ in range(c.lights)])

            def first(self, m, shared, valid, normal, view, light, side):
                r_valid, inputs = super().first(m, shared, valid, normal, view, light, side)
                return r_valid, {"n": inputs["r"], "l": inputs["l"]}  # Lambert's block on (R, L)
        ''',
}


@pytest.fixture
def toy_unit(monkeypatch):
    for name, source in UNIT_SOURCES.items():
        module = types.ModuleType(name)
        monkeypatch.setitem(sys.modules, name, module)
        exec(compile(textwrap.dedent(source), f"<{name}>", "exec"), module.__dict__)
    datapath = "phongfx.sim.stimulus.datapath"
    monkeypatch.setitem(REGISTRY, "toy_datapath", Entry(  # the block: the datapath with the toy unit
        "toy_datapath", "toyspec_config:toy_datapath_config", "phongfx.golden.datapath:datapath",
        "phongfx.hdl.datapath:Datapath", f"{datapath}:stimulus", f"{datapath}:extremes"))
    monkeypatch.setitem(METHODS, "toy", Method(  # the method: its search space, faces and float form
        "toy", "toy_datapath", {"vec_frac": 10, "n": 16, "lights": 2},
        {"vec_frac": (4, 16), "n": (1, 8000), "lights": (1, 8)},
        {"unit": "toyspec_config:UNIT", "golden": "toyspec_golden:toy", "component": "toyspec_hdl:ToyUnit",
         "run": "phongfx.explore.methods:run_datapath", "compile": "phongfx.explore.compile.units:DATAPATH",
         "shade": "phongfx.render.mesh:shade_datapath"}, float_form="phong"))
    return get_block("toy_datapath")


def test_a_new_specular_unit_is_selectable_everywhere(toy_unit, tmp_path):
    from phongfx.compiler.compile import compile_scene
    from phongfx.compiler.request import CompileRequest, check_methods
    from phongfx.config import DatapathConfig
    from phongfx.core.methods import specular_units
    from phongfx.explore.evaluate import SCENES
    from phongfx.explore.sweep.spec import load_spec
    from phongfx.render import mesh
    from phongfx.scene.file import load_scene

    # the datapath: config, golden model and hardware agree, cycle by cycle
    assert "toy" in specular_units() and DatapathConfig(specular="toy").used == (
        "lirp", "normalize", "reflect", "diffuse")
    config = toy_unit.config
    assert config.shininess is None and str(config.outputs["spec0"][0]) == "1.10"
    with pytest.raises(ValueError, match="reflect.out .* must equal diffuse.vec"):
        DatapathConfig(specular="toy", reflect=config.reflect.replace(out="S1.11"))
    raw = toy_unit.stimulus(count=60, seed=2)
    out = toy_unit.golden(raw)
    assert (out["spec0"] >= 0).all() and out["spec0"].max() == 1 << 10  # R = L somewhere: 1.0
    assert check(toy_unit, raw, backend="amaranth").ok
    # the front (LIRP, normalizer), then R and Lambert's block on (R, L)
    assert toy_unit.latency == sum(get_block(name).latency for name in ("lirp", "normalize", "reflect", "diffuse"))

    # the sweeps: a sweep spec accepts it and its run measures it against Phong
    points = load_spec({"scenes": ["torus"], "grid": [{"method": "toy", "vec_frac": [8, 12]}]})["points"]
    assert [(p["method"], p["params"]["vec_frac"]) for p in points] == [("toy", 8), ("toy", 12)]
    spec = METHODS["toy"]
    fixed, refs, terms = spec.run(spec, spec.config({"vec_frac": 12}), spec.resolve({}), SCENES["torus"])
    assert np.abs(fixed - refs["self"]).max() < 0.01  # R·L in 12 bits against float R·L
    assert terms["diff"][1] == terms["spec"][1]

    # the compiler: its method list accepts it and it is searched like fig7
    assert check_methods(["toy"]) == ["toy"]
    compiled = compile_scene(CompileRequest(load_scene(ROOT / "scenes" / "torus.toml"), methods=["toy"],
                                            samples=2000, final_samples=10000))
    assert list(compiled.results) == ["toy"]

    # the renderer: render mesh's method list has it and shades with it
    assert "toy" in mesh.SHADED and "toy" in mesh.SHADED_UNITS
    spans = mesh.meshes.rasterize(mesh.build_mesh("torus", polygons=200), mesh.meshes.rotation(10), 32, 32)
    diffuse, specular = mesh.shade(spans, "toy")
    assert diffuse.shape == specular.shape == (spans.visible.shape[0],) and specular.max() > 0.9


# ---------------------------------------------------------------- a standalone unit
#
# A standalone unit is its block's four files, one file of its method's faces, and two
# registrations: one Entry, one Method.  The unit ``toyphong`` below is conventional Phong under
# a new name: its config, golden model, component and stimulus subclass or re-export
# conventional's (the arithmetic is not what this test is about), and the sixth module holds the
# faces that differ (its sweep build and run); the others name the shared objects of the
# per-pixel table units by their import paths.  No other file names it, and yet the block tools,
# the renderer, the sweeps, the compiler with its certificate and the input contract all take
# it: what they do with a unit they ask of its registry entries, never of its name.

#: The six modules of the toy unit, dependencies first.
STANDALONE_SOURCES = {
    "toyphong_config": '''
        from dataclasses import dataclass

        from phongfx.config import ConventionalConfig

        @dataclass(frozen=True)
        class ToyPhongConfig(ConventionalConfig):
            """Conventional Phong's formats and tables, as a block of its own."""
        ''',
    "toyphong_golden": '''
        from phongfx.golden.conventional import conventional

        def toyphong(config, normal, light, view, n):
            return conventional(config, normal, light, view, n)
        ''',
    "toyphong_hdl": '''
        from phongfx.hdl.conventional import Conventional
        from toyphong_config import ToyPhongConfig

        class ToyPhong(Conventional):
            config_class = ToyPhongConfig
        ''',
    "toyphong_stimulus": '''
        from phongfx.sim.stimulus.conventional import extremes, stimulus
        ''',
    "toyphong_method": '''
        from phongfx.core.registry import get_block
        from phongfx.explore.methods import run_conventional

        def build(p):
            base = get_block("toyphong").config
            return base.replace(**base.frac_changes(vec=p["vec_frac"]), rsqrt_addr=p["rsqrt_addr"],
                                log_addr=p["table_addr"], exp_addr=p["table_addr"])

        def run(spec, config, p, scene):
            return run_conventional(spec, config, p, scene)
        ''',
}

TOY_PARAMS = {"vec_frac": 15, "rsqrt_addr": 9, "table_addr": 8, "n": 16}
TOY_RANGES = {"vec_frac": (6, 18), "rsqrt_addr": (2, 16), "table_addr": (1, 14), "n": (1, 8000)}


@pytest.fixture
def toyphong(monkeypatch):
    for name, source in STANDALONE_SOURCES.items():
        module = types.ModuleType(name)
        monkeypatch.setitem(sys.modules, name, module)
        exec(compile(textwrap.dedent(source), f"<{name}>", "exec"), module.__dict__)
    # the two registrations: the block, then the method and its faces
    monkeypatch.setitem(REGISTRY, "toyphong", Entry(
        "toyphong", "toyphong_config:ToyPhongConfig", "toyphong_golden:toyphong", "toyphong_hdl:ToyPhong",
        "toyphong_stimulus:stimulus", "toyphong_stimulus:extremes"))
    monkeypatch.setitem(METHODS, "toyphong", Method("toyphong", "toyphong", TOY_PARAMS, TOY_RANGES, {
        "inputs": "phongfx.scene.span_inputs:conventional_inputs",
        "shade": "phongfx.render.mesh:shade_conventional",
        "contract": "phongfx.deliver.contract:per_pixel_entry",
        "build": "toyphong_method:build",
        "run": "toyphong_method:run",
        "compile": "phongfx.explore.compile.units:CONVENTIONAL",
        "certify": "phongfx.certify.table_units:CONVENTIONAL_BOUND"}))
    return get_block("toyphong")


def test_a_new_standalone_unit_is_seen_everywhere(toyphong, tmp_path):
    from phongfx.certify.bound import shader_config
    from phongfx.certify.bounding import bounding
    from phongfx.compiler.compile import compile_scene
    from phongfx.compiler.request import CompileRequest, check_methods
    from phongfx.deliver.contract import input_contract
    from phongfx.explore.compile import run as runs
    from phongfx.explore.evaluate import SCENES
    from phongfx.explore.sweep.spec import load_spec
    from phongfx.render import mesh
    from phongfx.render.frames import frame_spans, unit_picture
    from phongfx.scene.file import load_scene
    from phongfx.scene.span_inputs import inputs

    # the block: golden and hardware agree, cycle by cycle, and compute conventional's numbers
    raw = toyphong.stimulus(count=40, seed=5)
    assert check(toyphong, raw, backend="amaranth").ok
    assert main(["verilog", "toyphong", "-o", str(tmp_path / "toyphong.v")]) == 0
    assert "module toyphong(" in (tmp_path / "toyphong.v").read_text()
    same = get_block("conventional").golden(raw)
    assert all((toyphong.golden(raw)[port] == same[port]).all() for port in same)

    # the renderer: its stream, its picture and render mesh's shading
    spans = frame_spans("torus", 200, 48, 48, 0)
    out = toyphong.golden(inputs("toyphong", spans, [0.3, 0.4, 1.0], n=16))
    picture = unit_picture(spans, out, toyphong.config)
    assert picture.shape == (48, 48) and 0.5 < picture.max() <= 1.0
    assert "toyphong" in mesh.SHADED
    diffuse, specular = mesh.shade(spans, "toyphong")
    assert specular.max() > 0.5 and diffuse.max() > 0.5

    # the sweeps: a spec takes it and its run measures it against Phong
    points = load_spec({"scenes": ["torus"], "grid": [{"method": "toyphong", "vec_frac": [10, 12]}]})["points"]
    assert [(p["method"], p["params"]["vec_frac"]) for p in points] == [("toyphong", 10), ("toyphong", 12)]
    spec = METHODS["toyphong"]
    config = spec.config({"vec_frac": 12})
    assert type(config).__name__ == "ToyPhongConfig" and str(config.fmt("vec")).endswith(".12")
    fixed, refs, _ = spec.run(spec, config, spec.resolve({}), SCENES["torus"])
    assert 0 < np.abs(fixed - refs["phong"]).max() < 0.05

    # the compiler: it searches the unit, certifies its design and writes its input contract
    assert check_methods(["toyphong"]) == ["toyphong"]
    scene = load_scene(ROOT / "scenes" / "torus.toml")
    compiled = compile_scene(CompileRequest(scene, methods=["toyphong"], samples=2000, final_samples=10000,
                                            certify="search"))
    result = compiled.results["toyphong"]
    assert list(compiled.results) == ["toyphong"] and result["feasible"] and compiled.chosen == "toyphong"
    assert bounding("toyphong").name == compiled.certificate.method == "interval+tables"
    assert compiled.certificate.certified and 0 < compiled.certificate.bound_levels < 1.5  # conventional's 1.454
    shader = shader_config("toyphong", result["params"], scene)
    assert shader.unit == "toyphong"
    contract = input_contract(shader, scene, "toyphong", n_scale=runs.hooks("toyphong").n_scale)
    assert [entry["quantity"] for entry in contract["inputs"]][:1] == ["N'"]
