"""The colour blend's golden model against an exact reference of its formula in Python integers
and Fractions, on random configs and inputs, and at the extremes."""

import math
from fractions import Fraction

import numpy as np
import pytest

from phongfx.config import BlendConfig
from phongfx.core.registry import get_block
from phongfx.golden.blend import blend
from phongfx.golden.fixed import Fixed


def reference(config, raw):
    """``clip(round(A + Σ D·diff + S·gate·spec), 0, 2^bits − 1)`` per pixel, from the config's real
    values: every coefficient ``floor(value·(2^bits − 1)·2^coef_frac + 1/2)`` in Fractions."""
    levels = 2 ** config.bits - 1

    def code(value):
        return Fraction(math.floor(Fraction(value) * levels * 2 ** config.coef_frac + Fraction(1, 2)),
                        2 ** config.coef_frac)

    def rounded(x):
        floor = math.floor(x)
        if config.rounding == "truncate":
            return floor
        if config.rounding == "round_half_up":
            return floor + (x - floor >= Fraction(1, 2))
        return round(x)  # Fraction.__round__: ties to even

    diff_lsb = Fraction(1, 2 ** int(config.diff.split(".")[1])) if config.diff else None
    spec_lsb = Fraction(1, 2 ** int(config.spec.split(".")[1]))
    count = len(raw["spec0"])
    out = {name: [] for name in "rgb"}
    for row in range(count):
        material = int(raw["material"][row]) if "material" in raw else 0
        for c, name in enumerate("rgb"):
            acc = code(config.ambient[material][c])
            for i in range(config.lights):
                diff = int(raw[f"diff{i}"][row]) * diff_lsb if config.diff else 0
                spec = int(raw[f"spec{i}"][row]) * spec_lsb
                gate = diff > 0 if config.gate else True
                acc += code(config.diffuse[material][i][c]) * diff
                acc += code(config.specular[material][i][c]) * spec * gate
            out[name].append(min(max(rounded(acc), 0), levels))
    return {name: np.array(values, dtype=np.int64) for name, values in out.items()}


def random_config(g, **fixed):
    """A random valid config: 1..3 materials, 1..3 lights, random colours and widths."""
    materials, lights = int(g.integers(1, 4)), int(g.integers(1, 4))
    no_diff = g.random() < 0.2

    def rgb(scale):
        return tuple(float(v) for v in np.round(g.uniform(0, scale, 3), int(g.integers(1, 6))))

    diffuse = tuple(tuple((0.0,) * 3 if no_diff else rgb(1.0) for _ in range(lights))
                    for _ in range(materials))
    changes = dict(lights=lights, coef_frac=int(g.integers(0, 17)), bits=int(g.integers(1, 13)),
                   diff="" if no_diff else f"1.{int(g.integers(4, 13))}",
                   spec=f"{int(g.integers(0, 3))}.{int(g.integers(3, 17))}",
                   ambient=tuple(rgb(0.3) for _ in range(materials)), diffuse=diffuse,
                   specular=tuple(tuple(rgb(1.5) for _ in range(lights)) for _ in range(materials)),
                   gate=not no_diff and bool(g.random() < 0.7),
                   rounding=str(g.choice(["truncate", "round_half_up", "round_half_even"])))
    changes.update(fixed)
    return BlendConfig(**changes)


@pytest.mark.parametrize("seed", range(12))
def test_golden_equals_the_exact_reference_on_random_configs(seed):
    g = np.random.default_rng(seed)
    block = get_block("blend", config=random_config(g))
    raw = block.stimulus(count=150, seed=seed)
    got, want = block.golden(raw), reference(block.config, raw)
    for name in "rgb":
        np.testing.assert_array_equal(got[name], want[name], err_msg=f"{name} of {block.config}")


def test_golden_equals_the_exact_reference_at_the_defaults():
    block = get_block("blend")
    raw = block.stimulus(count=400, seed=3)
    want = reference(block.config, raw)
    assert all(np.array_equal(block.golden(raw)[name], want[name]) for name in "rgb")


def run(config, **raw):
    ports = {name: Fixed(np.asarray(codes, dtype=np.int64), fmt) for name, (fmt, _) in config.inputs.items()
             for codes in [raw[name]]}
    return {name: value.raw.tolist() for name, value in blend(config, **ports).items()}


COLOURED = BlendConfig(ambient=((0.1, 0.05, 0.0),), diffuse=(((0.6, 0.3, 0.1), (0.2, 0.2, 0.4)),),
                       specular=(((0.3, 0.3, 0.3), (0.5, 0.4, 0.2)),))


def test_all_inputs_at_their_top_codes_saturate():
    top = dict(diff0=[2047], diff1=[2047], spec0=[65535], spec1=[65535])
    assert run(BlendConfig(), **top) == {"r": [255], "g": [255], "b": [255]}
    assert run(COLOURED, **top) == {"r": [255], "g": [255], "b": [255]}
    assert run(BlendConfig(bits=12), **top) == {name: [4095] for name in "rgb"}


def test_zero_inputs_give_the_ambient_alone():
    zero = dict(diff0=[0], diff1=[0], spec0=[0], spec1=[0])
    # 0.1·255 = 25.5 -> 26 (half up), 0.05·255 = 12.75 -> 13, 0
    assert run(COLOURED, **zero) == {"r": [26], "g": [13], "b": [0]}
    assert run(COLOURED.replace(rounding="truncate"), **zero) == {"r": [25], "g": [12], "b": [0]}


def test_the_backside_test_gates_the_specular_term():
    behind = dict(diff0=[0], diff1=[0], spec0=[32768], spec1=[32768])  # spec = 1.0, N·L <= 0
    assert run(BlendConfig(), **behind) == {name: [0] for name in "rgb"}
    # without the gate the highlight gets through: 2 lights × 0.5 × 255 = 255
    assert run(BlendConfig(gate=False), **behind) == {name: [255] for name in "rgb"}
    # the smallest lit diff (1 LSB) opens it: 2 × (127.5 + 127.5/1024) -> 255 saturated; one light 128
    lit = dict(diff0=[1], diff1=[0], spec0=[32768], spec1=[32768])
    assert run(BlendConfig(), **lit) == {name: [128] for name in "rgb"}


def test_one_light_exactly_at_one():
    # diff = spec = 1.0 on light 0 only, in levels: r 25.5 + 153 + 76.5 = 255, g 12.75 + 76.5 + 76.5 =
    # 165.75 -> 166, b 0 + 25.5 + 76.5 = 102
    got = run(COLOURED, diff0=[1024], diff1=[0], spec0=[32768], spec1=[0])
    assert got == {"r": [255], "g": [166], "b": [102]}


def test_coefficients_that_round_to_zero_add_nothing():
    # at coef_frac = 0 a coefficient below 1/510 (half a level) is 0: its light is invisible
    config = BlendConfig(coef_frac=0, ambient=((0.002, 0.002, 0.002),), diffuse=(((0.001,) * 3, (0.5,) * 3),),
                         specular=(((0.0019,) * 3, (0.0,) * 3),))
    a, d, s = config.coefficients(0)
    assert a == (1, 1, 1) and d == ((0, 0, 0), (128, 128, 128)) and s == ((0, 0, 0), (0, 0, 0))
    got = run(config, diff0=[1024], diff1=[0], spec0=[65535], spec1=[65535])
    assert got == {name: [1] for name in "rgb"}  # ambient 0.51 -> 1; light 0's terms are 0
    assert run(config, diff0=[0], diff1=[1024], spec0=[0], spec1=[0]) == {name: [129] for name in "rgb"}


def test_materials_select_their_coefficients_and_bad_codes_are_refused():
    config = BlendConfig(ambient=((1, 0, 0), (0, 1, 0), (0, 0, 1)), diffuse=(((0,) * 3,) * 2,) * 3,
                         specular=(((0,) * 3,) * 2,) * 3)
    zeros = [0, 0, 0]
    got = run(config, diff0=zeros, diff1=zeros, spec0=zeros, spec1=zeros, material=[0, 1, 2])
    assert got == {"r": [255, 0, 0], "g": [0, 255, 0], "b": [0, 0, 255]}
    ports = {name: Fixed([0, 3], fmt) for name, (fmt, _) in config.inputs.items()}
    message = r"^material must be in 0\.\.2; 1 value\(s\) are not, first 3 \(raw 3\)$"
    with pytest.raises(ValueError, match=message):
        blend(config, **ports)


def test_no_diffuse_input():
    config = BlendConfig(diff="", gate=False, diffuse=(((0,) * 3,) * 2,), ambient=((0.25, 0.25, 0.25),))
    # 0.25·255 = 63.75; + 2 × 0.5·255·0.5 = 127.5: 191.25 -> 191
    assert run(config, spec0=[16384], spec1=[16384]) == {name: [191] for name in "rgb"}
