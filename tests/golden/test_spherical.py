import math

import numpy as np
import pytest

from phongfx.config import SphericalConfig
from phongfx.core.format import Format
from phongfx.core.registry import get_block
from phongfx.golden.fixed import Fixed
from phongfx.golden.spherical import interpolate, rom_angles, rom_bound, rom_contents
from phongfx.golden.spherical_setup import quantize_setup, solve_a, span_setup
from phongfx.papers.szirmay import PAPER_TABLE1


def loop(config, raw):
    """The unit as a plain Python loop over pixels: registers, wrap, ROM read, product."""
    theta, rom = config.fmt("theta"), config.fmt("rom")
    shift, modulus = theta.width - config.addr_bits, 1 << theta.width
    tables = {name: rom_contents(config.addr_bits, rom, name).tolist() for name in ("cos2", "cos")}
    state = {"t": 0, "s": 0, "c": [0], "td": 0, "sd": 0, "cd": [0, 0, 0]}
    drop = config.fmt("c").frac_bits + rom.frac_bits - config.fmt("out").frac_bits
    spec, diff = [], []
    for i in range(len(raw["init"])):
        if raw["init"][i]:
            state = {"t": int(raw["b"][i]), "s": int(raw["s"][i]), "c": [int(raw["c"][i])],
                     "td": int(raw["bd"][i]), "sd": int(raw["sd"][i]), "cd": [int(v) for v in raw["cd"][i]]}
        else:
            for t, s in (("t", "s"), ("td", "sd")):
                wrapped = (state[t] + state[s]) % modulus
                state[t] = wrapped - modulus if wrapped >= modulus // 2 else wrapped
        words = [tables[f][(state[t] % modulus) >> shift] for f, t in (("cos2", "t"), ("cos", "td"))]
        # round half up of the exact product, as quantize does with ``drop`` fraction bits
        product = [(c * words[0] + (1 << (drop - 1))) >> drop for c in state["c"]]
        spec.append(min(product[0], config.fmt("out").max_raw))
        diff.append([min((c * words[1] + (1 << (drop - 1))) >> drop, config.fmt("out").max_raw)
                     for c in state["cd"]])
    return np.array(spec), np.array(diff)


def with_leading_steps(block, count, seed):
    # pixels before any init: the golden model must keep the reset state (θ = 0, C = 0)
    raw = block.stimulus(count=count, seed=seed)
    lead = {name: value[-5:] for name, value in raw.items()}
    lead["init"] = np.zeros(5, dtype=np.int64)
    return {name: np.concatenate([lead[name], raw[name]]) for name in raw}


@pytest.mark.parametrize("changes", [
    {}, dict(theta="S0.15", addr_bits=10, rom="0.10", c="1.15", out="1.15"),
    dict(theta="S0.7", addr_bits=4, rom="0.4", c="1.8", out="0.6", rounding="round_half_up"),
])
def test_golden_matches_python_loop(changes):
    block = get_block("spherical", **changes)
    raw = with_leading_steps(block, 500, 3)
    out = block.golden(raw)
    spec, diff = loop(block.config, raw)
    assert np.array_equal(out["spec"], spec)
    assert np.array_equal(out["diff"], diff)
    assert not np.any(out["spec"][:5]) and not np.any(out["diff"][:5])


@pytest.mark.parametrize("addr_bits,data_bits", [(3, 3), (4, 4), (6, 6), (6, 10), (10, 6), (10, 10)])
@pytest.mark.parametrize("function", ["cos2", "cos"])
def test_rom_within_bound_of_function(addr_bits, data_bits, function):
    rom = Format(0, data_bits)
    code = np.arange(-(1 << 15), 1 << 15)
    theta = code * math.pi / (1 << 15)
    word = rom_contents(addr_bits, rom, function)[(code >> (16 - addr_bits)) & ((1 << addr_bits) - 1)]
    exact = np.where(np.abs(theta) <= math.pi / 2, np.cos(theta) ** (2 if function == "cos2" else 1), 0)
    assert np.max(np.abs(word * rom.lsb - np.maximum(exact, 0))) <= rom_bound(addr_bits, rom)


def test_rom_layout():
    words = rom_contents(6, "0.6")
    angles = rom_angles(6)
    assert words.shape == (64,) and angles[0] == math.pi / 64 and angles[32] == -math.pi + math.pi / 64
    # cell c mirrors cell -1-c (unsigned address 63-c): the centres are symmetric about 0
    assert np.array_equal(words[:32], words[32:][::-1])
    # zero outside [-π/2, π/2) (addresses 16..47); cell 15 is cos²(31π/64) < 2^-7: 0 too
    assert not np.any(words[15:49]) and np.all(words[:15] > 0)
    assert words[0] == words[63] == 63  # cos²(π/64) rounds to 1.0: saturated
    assert np.all(np.diff(words[:16]) <= 0)
    assert rom_contents(6, "0.6", "cos")[:2].tolist() == [63, 63]  # 64·cos(π/64) = 63.8: saturated


def test_interpolator_wraps_like_the_register():
    theta = Format(0, 11, True)
    raw = interpolate(theta, np.array([1, 0, 0, 1, 0]), np.array([2046, 9, 9, -2048, 9]),
                      np.array([1, 9, 9, -1, 9]))
    assert raw.tolist() == [2046, 2047, -2048, -2048, 2047]


def test_table1_matches_paper():
    for n, a in PAPER_TABLE1.items():
        assert abs(solve_a(n) - a) <= 1e-4, n
    assert solve_a(2) == pytest.approx(1.0, abs=1e-12)
    assert 0.5 < solve_a(1) < 1 and solve_a(8000) > solve_a(500)


def test_solve_a_refuses_nonpositive_n():
    with pytest.raises(ValueError, match=r"^n must be positive, not 0$"):
        solve_a(0)


def slerp(u1, u2, t):
    gamma = math.acos(np.dot(u1, u2))
    return (np.sin((1 - t) * gamma)[:, None] * u1 + np.sin(t * gamma)[:, None] * u2) / math.sin(gamma)


def test_setup_matches_equation_15():
    # H fixed (v1 = v2): the paper's interpolation is the plain slerp of N dotted with H
    g = np.random.default_rng(11)
    for _ in range(20):
        u = g.normal(size=(3, 3))
        u1, u2, h = u / np.linalg.norm(u, axis=1, keepdims=True)
        d = span_setup(u1, u2, h, h, 10, 9)
        t = np.linspace(0, 1, 9)
        np.testing.assert_allclose(d["A"] * np.cos(t * d["gamma"] - d["phi"]), slerp(u1, u2, t) @ h, atol=1e-12)
        np.testing.assert_allclose(d["s"] * np.arange(9) + d["b"], d["a"] * (t * d["gamma"] - d["phi"]))


def test_setup_end_values_with_moving_h():
    # v turning too: cos θ(0) = u1·v1 and cos θ(1) = u2·v2 (equation 15 at t = 0, 1)
    g = np.random.default_rng(12)
    u = g.normal(size=(4, 3))
    u1, u2, v1, v2 = u / np.linalg.norm(u, axis=1, keepdims=True)
    d = span_setup(u1, u2, v1, v2, 2, 5)
    assert d["A"] * math.cos(-d["phi"]) == pytest.approx(u1 @ v1)
    assert d["A"] * math.cos(d["gamma"] - d["phi"]) == pytest.approx(u2 @ v2)


@pytest.mark.parametrize("gamma", [0.0, 1e-12, math.pi - 1e-12])
def test_setup_degenerate_spans_stay_finite(gamma):
    u1, u2 = np.array([0, 0, 1.0]), np.array([math.sin(gamma), 0, math.cos(gamma)])
    d = span_setup(u1, u2, u1, u1, 500, 1)
    assert all(math.isfinite(v) for v in d.values()) and d["s"] == 0


def test_specular_follows_float_span():
    # setup then the unit: C·cos²θ within the ROM bound plus the angle's rounding
    # (θ to 2^-11·π, s accumulated over 16 pixels) and one output rounding
    config = SphericalConfig()
    u1, u2 = np.array([0, 0, 1.0]), np.array([math.sin(0.4), 0, math.cos(0.4)])
    h = np.array([math.sin(0.15), 0, math.cos(0.15)])
    d = span_setup(u1, u2, h, h, 20, 16)
    q = quantize_setup(config, d)
    pixels = np.arange(16)
    raw = {"init": (pixels == 0).astype(int), "b": np.full(16, q["b"]), "s": np.full(16, q["s"]),
           "c": np.full(16, q["c"]), "bd": np.zeros(16, int), "sd": np.zeros(16, int),
           "cd": np.zeros((16, 3), int)}
    spec = get_block("spherical").golden(raw)["spec"] * 2.0 ** -11
    theta = d["b"] + d["s"] * pixels
    exact = np.where(np.abs(theta) <= math.pi / 2, np.cos(theta) ** 2, 0)
    angle = (0.5 + 16 * 0.5) * math.pi * 2.0 ** -11
    assert np.max(np.abs(spec - exact)) <= rom_bound(6, "0.6") + angle + 2.0 ** -11


def test_config_errors_name_the_field():
    with pytest.raises(ValueError, match=r"^theta must be a fraction-only format \(S0\.m, units of π\), "
                                         r"not S1\.11$"):
        SphericalConfig(theta="S1.11")
    with pytest.raises(ValueError, match=r"^theta must be a signed format \(Sn\.m\), not 0\.12$"):
        SphericalConfig(theta="0.12")
    with pytest.raises(ValueError, match=r"^addr_bits must be an integer in 2\.\.12, not 13$"):
        SphericalConfig(addr_bits=13)
    with pytest.raises(ValueError, match=r"^rom must be a fraction-only format \(0\.m\), not 1\.5$"):
        SphericalConfig(rom="1.5")
    assert SphericalConfig().out_overflow == "error"
    assert SphericalConfig(out="0.11").out_overflow == "saturate"


def test_golden_refuses_nothing_it_should_ignore():
    # junk on non-init pixels is ignored: changing it changes nothing
    block = get_block("spherical")
    raw = block.stimulus(count=100, seed=4)
    other = {name: value.copy() for name, value in raw.items()}
    steps = raw["init"] == 0
    for name in ("b", "s", "bd", "sd"):
        other[name][steps] = Fixed.from_float(np.zeros(np.count_nonzero(steps)), "S0.11").raw
    other["c"][steps] = 0
    other["cd"][steps] = 0
    first, second = block.golden(raw), block.golden(other)
    assert all(np.array_equal(first[name], second[name]) for name in first)


def test_a_span_outside_the_lobe_is_loaded_dark_because_the_register_wraps():
    # N turns from 100° to 140° away from H: cos²(a·x) is 0 all along for n = 20
    h = np.array([0.0, 0.0, 1.0])
    u1, u2 = (np.array([math.sin(math.radians(d)), 0.0, math.cos(math.radians(d))]) for d in (100, 140))
    d = span_setup(u1, u2, h, h, 20, 64)
    assert d["dark"] and d["C"] == 0.0
    # loaded with its true C instead, the wrapped angle reads lit cells again
    block = get_block("spherical")
    raw = quantize_setup(block.config, {**d, "C": d["A"] ** 20 + 0.5})
    stream = {name: np.zeros(64, dtype=np.int64) for name in ("init", "b", "s", "c", "bd", "sd")}
    stream["cd"] = np.zeros((64, 3), dtype=np.int64)
    stream["init"][0] = 1
    for name in ("b", "s", "c"):
        stream[name][0] = raw[name]
    spec = block.golden(stream)["spec"]
    assert spec.max() > 0
