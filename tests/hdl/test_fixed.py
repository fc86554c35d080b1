"""The Amaranth twin against the golden model, exhaustively over small formats.

Each test builds one combinational module holding every expression under test, then one
testbench walks all input codes (``ctx.set`` / ``ctx.get``) and the results are compared
with :mod:`phongfx.golden.fixed` on the same codes, code by code.
"""

import itertools
import random

import numpy as np
import pytest
from amaranth.hdl import Module, Signal
from amaranth.sim import Simulator

from phongfx.core.format import OVERFLOWS, ROUNDINGS, Format
from phongfx.golden.fixed import Fixed, quantize_raw
from phongfx.hdl.fixed import FixedValue, FixedVector, quantize


def simulate(inputs, outputs, vectors):
    """Drive ``inputs`` (Signals) with each tuple of ``vectors``; read every output Value.

    Returns ``{name: [value per vector]}`` and ``{name: shape}``; outputs are read
    through Signals of their own shape, so signed results come back negative.
    """
    m = Module()
    probes = {}
    for name, value in outputs.items():
        probe = Signal(value.shape(), name=f"probe_{len(probes)}")
        m.d.comb += probe.eq(value)
        probes[name] = probe
    results = {name: [] for name in outputs}

    async def testbench(ctx):
        for vector in vectors:
            for signal, code in zip(inputs, vector):
                ctx.set(signal, int(code))
            for name, probe in probes.items():
                results[name].append(ctx.get(probe))

    sim = Simulator(m)
    sim.add_testbench(testbench)
    sim.run()
    return results, {name: value.shape() for name, value in outputs.items()}


def all_codes(fmt):
    return list(range(fmt.min_raw, fmt.max_raw + 1))


def small_formats(max_width, min_width=1):
    return [Format(n, m, s) for s in (False, True) for n in range(max_width + 1)
            for m in range(max_width + 1) if min_width <= n + m + s <= max_width]


def seeded_pairs(count, seed, frm_width, to_width):
    rng = random.Random(seed)
    frms, tos = small_formats(frm_width), small_formats(to_width)
    return [(rng.choice(frms), rng.choice(tos)) for _ in range(count)]


def name(pair):
    return f"{pair[0]}->{pair[1]}"


# -- quantize -------------------------------------------------------------------------------

QUANTIZE_PAIRS = [tuple(Format.parse(f) for f in pair) for pair in [
    ("S2.3", "S1.1"),   # drop 2, signed to signed, overflow both ways
    ("S2.3", "1.1"),    # signed to unsigned: negatives saturate to 0 / wrap
    ("2.3", "S0.1"),    # unsigned to narrower signed
    ("0.4", "1.0"),     # drop every fraction bit: rounding reads past the top
    ("0.3", "2.0"),     # drop == width of an unsigned input
    ("S0.4", "S1.0"),   # drop == all but the sign
    ("S0.5", "S0.0"),   # down to one bit
    ("S1.2", "S2.4"),   # more fraction bits: exact, wider
    ("2.2", "S0.4"),    # more fraction bits and narrower
    ("2.0", "S4.0"),    # unsigned into a wider signed format
    ("S1.0", "3.0"),    # signed into a wider unsigned format
    ("S1.1", "S3.1"),   # sign extension
    ("3.3", "3.3"),     # identity
    ("S2.3", "S2.3"),
    ("S3.2", "2.2"),
    ("0.6", "0.2"),
    ("6.0", "S1.0"),
    ("S5.0", "0.3"),
]] + seeded_pairs(16, seed=20240607, frm_width=6, to_width=6)


@pytest.mark.parametrize("pair", QUANTIZE_PAIRS, ids=name)
def test_quantize_equals_golden_on_every_code(pair):
    frm, to = pair
    a = Signal(frm.shape())
    outputs = {(r, o): quantize(a, frm, to, r, o) for r in ROUNDINGS for o in OVERFLOWS}
    codes = all_codes(frm)
    got, shapes = simulate([a], outputs, [(c,) for c in codes])
    for (rounding, overflow), values in got.items():
        assert shapes[rounding, overflow] == to.shape(), (rounding, overflow)
        # "error" declares overflow impossible: the hardware keeps the low bits, as wrap does
        golden = quantize_raw(codes, frm, to, rounding, "wrap" if overflow == "error" else overflow)
        mismatches = [(c, v, int(g)) for c, v, g in zip(codes, values, golden) if v != g]
        assert not mismatches, f"{frm}->{to} {rounding}/{overflow}: (code, hdl, golden) {mismatches[:8]}"
    # and where golden "error" accepts a code, it agrees with the hardware
    for rounding in ROUNDINGS:
        rounded = quantize_raw(codes, frm, Format(16, to.frac_bits, True), rounding, "error")
        inside = [c for c, r in zip(codes, rounded) if to.min_raw <= r <= to.max_raw]
        if inside:
            golden = quantize_raw(inside, frm, to, rounding, "error")
            hdl = [v for c, v in zip(codes, got[rounding, "error"]) if c in inside]
            assert hdl == golden.tolist()


def test_quantize_accepts_a_wider_value_and_refuses_bad_names():
    # the value is read as frm's signedness, whatever shape it comes in
    a = Signal(8)
    got, shapes = simulate([a], {"q": quantize(a[:4], "S1.2", "S1.1", "round_half_even", "saturate")},
                           [(c,) for c in range(16)])
    assert shapes["q"] == Format.parse("S1.1").shape()
    assert got["q"] == quantize_raw(np.arange(16) - 16 * (np.arange(16) >= 8), "S1.2", "S1.1",
                                    "round_half_even", "saturate").tolist()
    with pytest.raises(ValueError, match=r"^rounding must be one of truncate, round_half_up, "
                                         r"round_half_even, not 'nearest'$"):
        quantize(a, "S1.2", "S1.1", "nearest", "wrap")
    with pytest.raises(ValueError, match=r"^overflow must be one of saturate, wrap, error, "
                                         r"not 'clamp'$"):
        quantize(a, "S1.2", "S1.1", "truncate", "clamp")


# -- FixedValue operators -------------------------------------------------------------------

OPERAND_PAIRS = [tuple(Format.parse(f) for f in pair) for pair in [
    ("S1.2", "S0.3"), ("2.1", "S1.1"), ("1.2", "0.3"), ("S2.0", "2.0"), ("0.3", "S0.0"),
    ("S0.0", "S0.0"), ("3.0", "0.3"), ("S1.1", "1.2"), ("1.0", "1.0"), ("0.4", "S3.0"),
    ("4.0", "S0.3"), ("S0.3", "4.0"),
]] + seeded_pairs(10, seed=7, frm_width=4, to_width=4)

SHIFTS = range(-3, 4)


def _constants(fmt):
    """Numbers a comparison may use with ``fmt``: exactly representable, in range and out."""
    step = fmt.lsb
    return sorted({fmt.min_raw * step, fmt.max_raw * step, 0.0, step, -step, 1.0, -1.0,
                   (fmt.max_raw + 1) * step, (fmt.min_raw - 1) * step, 8.0, -8.0})


@pytest.mark.parametrize("pair", OPERAND_PAIRS, ids=name)
def test_fixed_value_operators_equal_golden_on_every_code_pair(pair):
    fa, fb = pair
    a_sig, b_sig = Signal(fa.shape()), Signal(fb.shape())
    a, b = FixedValue(a_sig, fa), FixedValue(b_sig, fb)
    exprs = {"a+b": a + b, "a-b": a - b, "a*b": a * b, "b*a": b * a, "-a": -a, "b-a": b - a}
    exprs.update({f"a<<{k}": a.shift(k) for k in SHIFTS})
    exprs["a<<2op"], exprs["a>>1op"] = a << 2, a >> 1
    compares = {"a>=b": a >= b, "a<b": a < b, "b>=a": b >= a, "b<a": b < a}
    constants = _constants(fa)
    compares.update({f"a>={c}": a >= c for c in constants})
    compares.update({f"a<{c}": a < c for c in constants})

    pairs = list(itertools.product(all_codes(fa), all_codes(fb)))
    ga = Fixed([p[0] for p in pairs], fa)
    gb = Fixed([p[1] for p in pairs], fb)
    golden = {"a+b": ga + gb, "a-b": ga - gb, "a*b": ga * gb, "b*a": gb * ga, "-a": -ga,
              "b-a": gb - ga, "a<<2op": ga << 2, "a>>1op": ga >> 1}
    golden.update({f"a<<{k}": ga.shift(k) for k in SHIFTS})
    golden_compares = {"a>=b": ga >= gb, "a<b": ga < gb, "b>=a": gb >= ga, "b<a": gb < ga}
    golden_compares.update({f"a>={c}": ga >= c for c in constants})
    golden_compares.update({f"a<{c}": ga < c for c in constants})

    outputs = {key: x.value for key, x in exprs.items()} | compares
    got, shapes = simulate([a_sig, b_sig], outputs, pairs)
    for key, x in exprs.items():
        assert x.fmt == golden[key].fmt, key
        assert shapes[key] == x.fmt.shape(), key
        want = golden[key].raw.tolist()
        bad = [(p, g, w) for p, g, w in zip(pairs, got[key], want) if g != w]
        assert not bad, f"{fa} {key} {fb}: (codes, hdl, golden) {bad[:8]}"
    for key in compares:
        assert shapes[key].width == 1, key
        want = [int(w) for w in golden_compares[key]]
        bad = [(p, g, w) for p, g, w in zip(pairs, got[key], want) if g != w]
        assert not bad, f"{fa} {key} {fb}: (codes, hdl, golden) {bad[:8]}"


def test_fixed_value_quantize_const_where():
    fa = Format.parse("S2.3")
    a_sig, sel = Signal(fa.shape()), Signal()
    a = FixedValue(a_sig, fa)
    one = FixedValue.const(1, fa)
    q = a.quantize("S1.1", "round_half_even", "saturate")
    assert q.fmt == Format.parse("S1.1")
    w = a.where(sel, one)
    codes = [(c, s) for c in all_codes(fa) for s in (0, 1)]
    got, _ = simulate([a_sig, sel], {"q": q.value, "w": w.value, "one": one.value}, codes)
    ga = Fixed([c for c, _ in codes], fa)
    assert got["q"] == ga.quantize("S1.1", "round_half_even", "saturate").raw.tolist()
    assert got["w"] == [c if s else 8 for c, s in codes]
    assert set(got["one"]) == {8}
    assert FixedValue(5, "2.2").value.shape() == Format.parse("2.2").shape()
    with pytest.raises(ValueError, match=r"^constant 0\.3 is not exactly representable in S2\.3$"):
        FixedValue.const(0.3, fa)
    with pytest.raises(ValueError, match=r"^comparison constant 0\.1 is not exactly representable "
                                         r"in S2\.3$"):
        a >= 0.1
    with pytest.raises(ValueError, match=r"^where: both sides must have the same format, "
                                         r"not S2\.3 and 2\.3$"):
        a.where(sel, FixedValue(0, "2.3"))


# -- FixedVector ----------------------------------------------------------------------------

@pytest.mark.parametrize("fa, fb", [("S1.2", "S0.3"), ("2.1", "S1.1"), ("1.2", "0.3")])
def test_fixed_vector_equals_golden(fa, fb):
    fa, fb = Format.parse(fa), Format.parse(fb)
    rng = np.random.default_rng(11)
    n = 200
    va = rng.integers(fa.min_raw, fa.max_raw + 1, size=(n, 3))
    vb = rng.integers(fb.min_raw, fb.max_raw + 1, size=(n, 3))
    va[:4], vb[:4] = fa.min_raw, fb.max_raw  # corners
    va[4:8], vb[4:8] = fa.max_raw, fb.min_raw
    sig_a = [Signal(fa.shape()) for _ in range(3)]
    sig_b = [Signal(fb.shape()) for _ in range(3)]
    scalar_sig = Signal(fb.shape())
    a = FixedVector(FixedValue(s, fa) for s in sig_a)
    b = FixedVector.from_array(sig_b, fb)
    scalar = FixedValue(scalar_sig, fb)
    exprs = {"a+a": a + a, "a-a": a - a, "a*b": a * b, "a*s": a * scalar, "s*a": scalar * a,
             "a<<2": a.shift(2), "q": a.quantize("S0.1", "round_half_up", "saturate")}
    scalars = {"sum": a.sum(), "dot": a.dot(b)}
    outputs = {f"{key}{i}": x[i].value for key, x in exprs.items() for i in range(3)}
    outputs.update({key: x.value for key, x in scalars.items()})
    scal = vb[:, 0]
    got, shapes = simulate(sig_a + sig_b + [scalar_sig], outputs,
                           [tuple(va[k]) + tuple(vb[k]) + (scal[k],) for k in range(n)])
    ga, gb, gs = Fixed(va, fa), Fixed(vb, fb), Fixed(scal[:, None], fb)
    golden = {"a+a": ga + ga, "a-a": ga - ga, "a*b": ga * gb, "a*s": ga * gs, "s*a": gs * ga,
              "a<<2": ga.shift(2), "q": ga.quantize("S0.1", "round_half_up", "saturate")}
    for key, x in exprs.items():
        assert x.fmt == golden[key].fmt, key
        assert len(x.values()) == 3 and list(x)[0] is x[0]
        for i in range(3):
            assert got[f"{key}{i}"] == golden[key].raw[:, i].tolist(), (key, i)
            assert shapes[f"{key}{i}"] == x.fmt.shape()
    for key, gold in {"sum": ga.sum(), "dot": ga.dot(gb)}.items():
        assert scalars[key].fmt == gold.fmt, key
        assert shapes[key] == gold.fmt.shape()
        assert got[key] == gold.raw.tolist(), key


def test_fixed_vector_needs_three_of_one_format():
    with pytest.raises(ValueError, match=r"^a FixedVector needs three FixedValue of one format$"):
        FixedVector([FixedValue(0, "1.2")] * 2)
    with pytest.raises(ValueError, match=r"^a FixedVector needs three FixedValue of one format$"):
        FixedVector([FixedValue(0, "1.2"), FixedValue(0, "1.2"), FixedValue(0, "S1.2")])
