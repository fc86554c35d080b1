"""The exhaustive certificate: the normal codes it lists and the bound it measures."""

import numpy as np
import pytest

from phongfx.certify.exhaustive import applicable, count_codes, exhaustive, normal_codes
from phongfx.config import fig7_config
from phongfx.core.format import Format
from phongfx.explore.compile import run as runs
from phongfx.explore.compile.analysis import analyse
from phongfx.golden.fixed import Fixed
from phongfx.golden.shader import shader
from phongfx.scene.domain import domain
from phongfx.scene.file import parse_scene
from phongfx.scene.geometry import frames
from phongfx.sim.stimulus import codes as encode_codes

BALL = """
name = "ball"
[camera]
at = "infinity"
direction = [0, 0, 1]
[[lights]]
direction = [1, 1, 1]
[materials.ball]
kd = 0.6
ks = 0.4
[[objects]]
type = "lyon_spheres"
material = "ball"
radius = 8
shininess = [16]
span = SPAN
[output]
bits = 8
[requirement]
max_error_levels = 5.0
against = "phong"
"""


def ball(span=0):
    return parse_scene(BALL.replace("SPAN", str(span)))


def per_pixel(spec=None):
    """The domain of exact per-pixel normals facing the viewer, one material of n = 16."""
    return domain(spec or ball())


def listed(fmt, view=(0, 0, 1), cos_min=0.0):
    return np.concatenate(list(normal_codes(fmt, view, cos_min, chunk=4096)))


def test_every_rounded_unit_normal_is_listed():
    fmt = Format.parse("S1.5")
    every = {tuple(c) for c in listed(fmt)}
    g = np.random.default_rng(3)
    v = g.normal(size=(200_000, 3))
    v /= np.linalg.norm(v, axis=-1, keepdims=True)
    v[:, 2] = np.abs(v[:, 2])
    # grazing normals too: the rim is where a z cell is longest
    rim = v.copy()
    rim[:, 2] *= 1e-3
    rim /= np.linalg.norm(rim, axis=-1, keepdims=True)
    sent = encode_codes(np.concatenate([v, rim]), fmt)
    missing = {tuple(c) for c in sent} - every
    assert not missing


def test_listed_codes_are_roundings_of_unit_vectors():
    # every listed code's cell (±1/2 LSB per component) reaches the unit sphere
    fmt = Format.parse("S1.6")
    values = listed(fmt, cos_min=-1.0) / fmt.one
    length = np.linalg.norm(values, axis=-1)
    slack = np.sqrt(3) * 0.5 / fmt.one
    assert np.all(np.abs(length - 1) <= slack)
    assert len(values) == count_codes(fmt) - len(np.unique(values[values[:, 2] == 0], axis=0))
    assert len(np.unique(values, axis=0)) == len(values)


def test_viewer_test_keeps_the_facing_side():
    fmt = Format.parse("S1.5")
    facing = listed(fmt, view=(1, 0, 0), cos_min=0.5) / fmt.one
    assert facing[:, 0].min() >= 0.5 - np.sqrt(3) * 0.5 / fmt.one
    assert len(facing) < len(listed(fmt, view=(1, 0, 0), cos_min=0.0))


def test_count_at_ten_bits():
    # about the surface of the sphere times 3/2 (the mean of |x| + |y| + |z|) in LSB²
    count = count_codes("S1.10")
    assert abs(count - 4 * np.pi * 1024 ** 2 * 1.5) / count < 0.02


def test_bound_is_the_worst_code_replayed():
    spec = ball()
    params = {"vec_frac": 7, "k": 4}
    cert = exhaustive("fig7", params, spec, per_pixel())
    assert cert.method == "exhaustive" and cert.certified
    assert 4.0 < cert.bound_levels < 5.0
    assert cert.parts["codes"] == len(listed(Format.parse("S1.7")))
    # the witness, through the whole shader's golden model on its own
    worst = cert.parts["witness"]
    assert worst["unrounded"] <= cert.bound_levels
    assert worst["error_levels"] == cert.parts["max_error_levels"] == 5
    config = runs.build("fig7", params, analyse(spec, frames(spec)))
    code = np.array([worst["point"]["normal_code"]])
    assert worst["codes"]["n0"] == worst["codes"]["n1"] == code[0].tolist()
    light = encode_codes(np.array([[1, 1, 1]]) / np.sqrt(3), config.units[0].normalize.fmt("out"))
    view = encode_codes(np.array([[0.0, 0, 1]]), config.units[0].normalize.fmt("out"))
    ports = {"n0": code, "n1": code, "a": np.zeros(1, dtype=np.int64), "v": view, "l0": light}
    out = shader(config, **{name: Fixed(ports[name], fmt) for name, (fmt, _) in config.inputs.items()})
    assert {c: int(out[c].raw[0]) for c in "rgb"} == worst["outputs"]
    assert max(abs(worst["outputs"][c] - r) for c, r in zip("rgb", worst["reference_levels"])) == 5


def test_a_worse_quantize_raises_the_bound():
    spec = ball()
    good = exhaustive("fig7", {"vec_frac": 7, "k": 4}, spec, per_pixel())
    worse = exhaustive("fig7", {"vec_frac": 7, "k": 4, "shape_t_frac": 6}, spec, per_pixel())
    assert good.certified and not worse.certified
    assert worse.bound_levels > good.bound_levels + 5
    assert "misses the requirement" in worse.why


def test_not_enumerable():
    spec = ball(span=4)
    cert = exhaustive("fig7", {"vec_frac": 7}, spec, per_pixel(spec))
    assert not cert.certified and cert.bound_levels is None
    assert "spans" in cert.why
    point = parse_scene(BALL.replace("SPAN", "0").replace("direction = [1, 1, 1]", "position = [3, 3, 3]"))
    assert "point light" in applicable("fig7", point, per_pixel(point))
    assert "spherical" in applicable("spherical", ball(), per_pixel())


def test_too_many_codes():
    cert = exhaustive("fig7", {"vec_frac": 7}, ball(), per_pixel(), max_codes=1000)
    assert not cert.certified and "exceed the 1,000" in cert.why


def test_conventional_normal_format():
    from phongfx.certify.exhaustive import normal_format
    spec = ball()
    config = runs.build("conventional", {}, analyse(spec, frames(spec)))
    assert normal_format("conventional", config) == Format.parse(config.units[0].vec)
    assert normal_format("fig7", runs.build("fig7", {}, analyse(spec, frames(spec)))) == \
        Format.parse(fig7_config().lirp.vec)
