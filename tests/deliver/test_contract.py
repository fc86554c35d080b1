"""The input contract of a compiled core (:mod:`phongfx.deliver.contract`): every input port
has a meaning, and the meaning is what the compiler's stream holds.

Designs are built from the example scenes' configs at their default widths (no compile: the
contract depends on the method, the scene and the formats, not on the search); the stream
of a frame (:func:`phongfx.explore.compile.run.frame_inputs`, what the RTL check and the
testbench drive) is checked against what each entry claims.
"""

import functools
import json
import os
import subprocess
import sys

import numpy as np
import pytest

from phongfx.deliver.contract import contract_lines, input_contract
from phongfx.explore.compile import run
from phongfx.explore.compile.analysis import analyse
from phongfx.hdl.top import header, port_map
from phongfx.scene.file import load_scene, parse_scene
from phongfx.scene.geometry import frames

from tests.docs.pages import blocks

SCENES = os.path.join(os.path.dirname(__file__), "..", "..", "scenes")
#: The example scenes with the methods the compiler chooses for them, and the others it ships.
CASES = [("lyon-balls", "fig7"), ("lyon-balls", "conventional"), ("torus", "fig7"), ("torus", "conventional"),
         ("two-lights", "fig7"), ("two-lights", "conventional"), ("local-mesh", "fig7"),
         ("local-mesh", "conventional"), ("torus", "blinn"), ("torus", "spherical"), ("two-lights", "blinn")]
RATES = {"pixel", "span end", "constant", "span setup"}

#: The two-material scene of the integration page (docs/integration.rst), which a host drives there.
TWO_MATERIALS = next(b.text for b in blocks("integration.rst") if b.caption == "duo.toml")


@functools.cache
def _design(scene, method):
    """``(spec, first frame, config, contract)`` of ``method`` at its default widths on ``scene``."""
    spec = load_scene(os.path.join(SCENES, f"{scene}.toml")) if scene != "duo" else parse_scene(TWO_MATERIALS,
                                                                                                  name="duo")
    geometries = frames(spec)
    config = run.build(method, {}, analyse(spec, geometries))
    return spec, geometries[0], config, input_contract(config, spec, method, n_scale=run.hooks(method).n_scale)


@pytest.mark.parametrize(("scene", "method"), CASES)
def test_every_input_port_has_one_meaning_and_the_manifest_form_is_json(scene, method):
    spec, _, config, contract = _design(scene, method)
    inputs = [p["name"] for p in port_map(config) if p["direction"] == "input" and p["field"] is not None]
    claimed = [port for entry in contract["inputs"] for port in entry["ports"]]
    assert sorted(claimed) == sorted(inputs)
    for entry in contract["inputs"]:
        assert len(entry["meaning"]) > 20 and entry["rate"] in RATES, entry
        assert entry["space"] in ("eye", None) and entry["normalized_by"] in ("host", "core", None)
        assert (entry["unit_vector"] is None) == (entry["lanes"] == 1 or entry["field"].endswith("cd")), entry
    assert [o["port"] for o in contract["outputs"]] == ["out_r", "out_g", "out_b"]
    assert [m["name"] for m in contract["materials"]] == list(spec.materials)
    assert json.loads(json.dumps(contract)) == contract


def _values(raw, fmt):
    return np.asarray(raw, dtype=np.float64) * fmt.lsb


@pytest.mark.parametrize(("scene", "method"), CASES)
def test_the_stream_the_compiler_feeds_is_what_the_contract_says(scene, method):
    _, geometry, config, contract = _design(scene, method)
    raw = run.frame_inputs(method, config, geometry, geometry.n)
    spans = geometry.span if run.per_pixel(method) else np.repeat(np.arange(len(geometry.spans.length)),
                                                                   geometry.spans.length)
    for entry in contract["inputs"]:
        fmt, _ = config.inputs[entry["field"]]
        value = _values(raw[entry["field"]], fmt).reshape(len(spans), -1)
        where = f"{scene}/{method}: {entry['field']}"
        if entry["rate"] == "constant":
            assert np.all(value == value[0]), where
        if entry["rate"] == "span end":  # one value per span, on its every pixel
            first = np.r_[0, np.flatnonzero(np.diff(spans)) + 1]
            assert np.array_equal(value, np.repeat(value[first], np.diff(np.r_[first, len(spans)]), 0)), where
        if entry["rate"] == "span setup":  # loaded on a span's first pixel (init = 1), zero elsewhere
            assert not np.any(value[raw["init"] == 0]) and np.any(value[raw["init"] == 1]), where
        if entry["lanes"] == 3 and entry["unit_vector"] is not None:
            length = np.linalg.norm(value, axis=-1)
            slack = 2 * fmt.lsb
            if entry["unit_vector"]:
                assert np.all(np.abs(length - 1) <= slack), (where, length.min(), length.max())
            elif entry["quantity"] == "N'":  # an interpolated normal falls short of 1 inside a span
                assert length.min() < 1 - slack and length.max() <= 1 + slack, where
        if entry["field"] == "a":
            assert value.min() == 0 and value.max() == 1, where
        if entry["field"] == "init":
            assert set(np.unique(value)) == {0.0, 1.0}, where


def _paragraphs(comment):
    """The paragraphs of a header comment, each wrapped line joined back (how it is wrapped is not pinned)."""
    out = []
    for line in comment.splitlines():
        text = line.removeprefix("//").removeprefix(" ")
        if text.startswith(" ") and out:
            out[-1] += " " + text.strip()
        else:
            out.append(text)
    return out


def test_two_lights_header_names_every_input_the_material_and_the_rounding():
    _, _, config, contract = _design("two-lights", "fig7")
    text = header(port_map(config), "two_lights_fig7", 18, contract=contract_lines(contract))
    section = _paragraphs(text[text.index("// Contract:"):])
    assert section == contract_lines(contract)
    assert section[0] == "Contract: what the host feeds the core (fig7, compiled for the scene two-lights)."
    for vector in ("n0", "n1", "v", "l0", "l1"):
        assert any(p.startswith(f"in_{vector}_{{x,y,z}} (S1.10): ") for p in section), vector
    assert ("in_l1_{x,y,z} (S1.10): L1, the unit vector toward light 1, a directional light along (-0.6667, "
            "0.3333, 0.6667): the same on every pixel [eye space; unit; constant; normalized by the host].") in section
    assert any(p.startswith("in_a (1.10): a, the pixel's place in its span: k/(length-1) for its k-th pixel")
               for p in section)
    assert any(p.startswith("Material 0 = shiny: kd 0.6, ks 0.4, ka 0, colour (1, 1, 1), n 16; blend codes (7.8)")
               for p in section)
    assert "No shininess port: n = 16 is built into the hardware (the scene has one n)." in section
    (outputs,) = [p for p in section if p.startswith("out_r, out_g, out_b (8.0): ")]
    assert ("round half up of A_c + sum over lights i of (diff_i*D_ic + spec_i*S_ic * [diff_i > 0]), saturated "
            "at 255") in outputs


def test_a_point_light_is_normalized_by_the_host_at_span_ends_or_by_the_core_per_pixel():
    fig7 = {e["field"]: e for e in _design("local-mesh", "fig7")[3]["inputs"]}
    assert (fig7["l0_0"]["rate"], fig7["l0_0"]["normalized_by"], fig7["l0_0"]["unit_vector"]) == (
        "span end", "host", True)
    assert fig7["l0_0"]["meaning"] == (
        "the unit vector from the surface point at the first pixel of the pixel's span toward light 0, a point "
        "light at (2, 2, 3) (scene units); the host normalizes it, the core interpolates it with a and "
        "normalizes per pixel")
    conventional = {e["field"]: e for e in _design("local-mesh", "conventional")[3]["inputs"]}
    light = conventional["light"]
    assert (light["quantity"], light["rate"], light["normalized_by"], light["unit_vector"]) == (
        "L0", "pixel", "core", False)
    assert light["meaning"] == (
        "the unit vector from the pixel's surface point toward light 0, a point light at (2, 2, 3) (scene units), "
        "which the core normalizes again: any length up to 1 gives its direction, but the error measured and "
        "certified is for unit length (a shorter vector's codes round relatively coarser)")
    assert conventional["view"]["quantity"] == "V" and conventional["n"]["meaning"] == (
        "the pixel's shininess n itself (Phong's (R.V)^n): an integer 1..32")


def test_blinn_is_fed_four_n_and_the_spherical_unit_a_setup_per_span():
    blinn = {e["field"]: e for e in _design("two-lights", "blinn")[3]["inputs"]}
    assert blinn["n"]["meaning"].startswith("n' = 4*n, 4 times the pixel's shininess n (Lyon 1993, appendix")
    assert blinn["n"]["light"] is None and blinn["c1_half"]["light"] == 1
    assert blinn["c1_half"]["quantity"] == "H1"
    contract = _design("torus", "spherical")[3]
    assert contract["stream"].startswith("one vector per pixel of every span, hidden pixels included")
    spherical = {e["field"]: e for e in contract["inputs"]}
    assert spherical["init"]["meaning"].startswith("1 on the first pixel of a span, which loads b, s, c, bd, sd, cd")
    assert {spherical[name]["rate"] for name in ("b", "s", "c", "bd", "sd", "cd")} == {"span setup"}


def test_the_material_port_maps_each_index_to_its_name_and_constants():
    _, geometry, config, contract = _design("duo", "conventional")
    (entry,) = [e for e in contract["inputs"] if e["field"] == "material"]
    assert entry["ports"] == ["in_material"]
    assert entry["meaning"] == "the index of the pixel's material in the scene file's order: 0 = red, 1 = blue"
    red, blue = contract["materials"]
    assert (blue["index"], blue["name"], blue["kd"], blue["ks"], blue["ka"], blue["colour"], blue["n"]) == (
        1, "blue", 0.5, 0.5, 0.1, [0.2, 0.4, 1.0], 16)
    assert blue["codes"]["ambient"] == [round(0.1 * c * 255 * 256) for c in (0.2, 0.4, 1.0)]
    assert red["objects"] == ["torus"] and blue["objects"] == ["sphere"]
    assert set(np.unique(run.frame_inputs("conventional", config, geometry, geometry.n)["material"])) == {0, 1}
    lines = contract_lines(contract)
    assert "Material 1 = blue: kd 0.5, ks 0.5, ka 0.1, colour (0.2, 0.4, 1), n 16; blend codes (7.8) ambient " \
           "[1306, 2611, 6528]" in "\n".join(lines)


def test_only_a_compiled_shader_with_a_shipped_unit_has_a_contract():
    spec, _, config, _ = _design("torus", "fig7")
    with pytest.raises(ValueError, match=r"^config must be a ShaderConfig \(a compiled shader\), not DatapathConfig$"):
        input_contract(config.units[0], spec, "fig7", n_scale=1)
    schlick = run.build("schlick", {}, analyse(spec, frames(spec)[:1]))
    with pytest.raises(ValueError, match=r"^method must be one the compiler ships \(fig7, fig8, halfway, "
                                         r"spherical, blinn, conventional\), not 'schlick'$"):
        input_contract(schlick, spec, "schlick", n_scale=1)


def test_the_layer_loads_its_modules_only_when_a_name_is_asked_for():
    code = ("import sys, phongfx.deliver as d\nassert 'phongfx.deliver.contract' not in sys.modules\n"
            "assert d.input_contract.__module__ == 'phongfx.deliver.contract'\nprint(sorted(d.__all__))")
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert run.returncode == 0, run.stderr
    assert {"contract_lines", "input_contract"} <= set(eval(run.stdout))  # the other modules add theirs


def _unit(v):
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def _host(quantity, geometry):
    """What a host computes for ``quantity`` at every visible pixel, read off the contract's words."""
    g, a = geometry, geometry.a[:, None]

    def lirp(start, end):  # the contract's (1-a)*X0 + a*X1
        return (1 - a) * start + a * end

    fixed = {"N0": g.n0, "N1": g.n1, "a": g.a, "n": g.n, "n'": 4 * g.n, "V": g.viewer, "V0": g.v0, "V1": g.v1,
             "N'": lirp(g.n0, g.n1), "material": g.material}
    if quantity in fixed:
        return fixed[quantity]
    kind, light, end = quantity[0], int(quantity[1]), quantity[2:]
    if kind == "H":
        return _unit(g.light[light] + g.viewer)
    return {"": g.light[light], "_0": g.l0[light], "_1": g.l1[light]}[end]


@pytest.mark.parametrize(("scene", "method"), [case for case in CASES if case[1] != "spherical"])
def test_a_host_that_follows_the_contract_feeds_the_codes_the_compiler_streams(scene, method):
    _, geometry, config, contract = _design(scene, method)
    stream = run.frame_inputs(method, config, geometry, geometry.n)
    for entry in contract["inputs"]:
        fmt, _ = config.inputs[entry["field"]]
        value = np.asarray(_host(entry["quantity"], geometry), dtype=np.float64)
        if entry["lanes"] == 1 and fmt.frac_bits == 0:  # n, n', material: integers as they are
            codes = np.rint(value).astype(np.int64)
        else:  # the contract's rule: floor(x * 2^m + 1/2), saturated
            codes = np.clip(np.floor(value * 2.0 ** fmt.frac_bits + 0.5), fmt.min_raw, fmt.max_raw)
        assert np.array_equal(codes, stream[entry["field"]]), f"{scene}/{method}: {entry['field']}"


def test_units_taking_the_lights_in_turn_keep_one_set_of_ports_per_light():
    spec, _, config, contract = _design("two-lights", "conventional")
    assert contract["notes"][-1] == "One unit per light: c<i>_ ports feed light i's; unprefixed ones feed every light."
    turns = run.build("conventional", {}, analyse(spec, frames(spec)[:1]), {"interval": 2})
    shared = input_contract(turns, spec, "conventional", n_scale=1)
    assert [e["field"] for e in shared["inputs"]] == [e["field"] for e in contract["inputs"]]
    assert shared["notes"][-1] == ("One unit per light (the core's units take the lights in turn, 2 clocks per "
                                   "pixel): c<i>_ ports feed light i's; unprefixed ones feed every light.")
