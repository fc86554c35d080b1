"""Adding a standalone unit is its block's four files, one file of its method's faces, and
two registrations: one :class:`~phongfx.core.registry.Entry`, one
:class:`~phongfx.core.methods.Method`.

The unit ``toyphong`` below is conventional Phong under a new name: its config, golden
model, component and stimulus subclass or re-export conventional's (the arithmetic is not
what this test is about), and the sixth module holds the faces that differ (its sweep build
and run); the others name the shared objects of the per-pixel table units by their import
paths.  No other file names it, and yet the datapath tools, the sweeps, the compiler with its
certificate, the input contract and the renderer all take it: what they do with a unit they
ask of its registry entries, never of its name.
"""

import sys
import textwrap
import types
from pathlib import Path

import numpy as np
import pytest

from phongfx.core.methods import METHODS, Method
from phongfx.core.registry import REGISTRY, Entry, get_block
from phongfx.sim.harness import check

ROOT = Path(__file__).resolve().parents[2]

#: The six modules of the toy unit, dependencies first.
SOURCES = {
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

PARAMS = {"vec_frac": 15, "rsqrt_addr": 9, "table_addr": 8, "n": 16}
RANGES = {"vec_frac": (6, 18), "rsqrt_addr": (2, 16), "table_addr": (1, 14), "n": (1, 8000)}


@pytest.fixture
def toyphong(monkeypatch):
    for name, source in SOURCES.items():
        module = types.ModuleType(name)
        monkeypatch.setitem(sys.modules, name, module)
        exec(compile(textwrap.dedent(source), f"<{name}>", "exec"), module.__dict__)
    # the two registrations: the block, then the method and its faces
    monkeypatch.setitem(REGISTRY, "toyphong", Entry(
        "toyphong", "toyphong_config:ToyPhongConfig", "toyphong_golden:toyphong", "toyphong_hdl:ToyPhong",
        "toyphong_stimulus:stimulus", "toyphong_stimulus:extremes"))
    monkeypatch.setitem(METHODS, "toyphong", Method("toyphong", "toyphong", PARAMS, RANGES, {
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
    from phongfx.core.methods import METHODS as SWEEPABLE
    from phongfx.explore.sweep.spec import load_spec
    from phongfx.render import mesh
    from phongfx.render.frames import frame_spans, unit_picture
    from phongfx.scene.file import load_scene
    from phongfx.scene.span_inputs import inputs

    # the block: golden and hardware agree, cycle by cycle, and compute conventional's numbers
    raw = toyphong.stimulus(count=40, seed=5)
    assert check(toyphong, raw, backend="amaranth").ok
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
    spec = SWEEPABLE["toyphong"]
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
