"""``phongfx tables extremes``: every block at the extremes of its inputs (GitHub issue 6, §2).

One row per (block, extreme input class): exactly ±1.0, zero-length interpolated
vectors at 180°, n = 1 and 8000, m = 1 and 63, |D| = 2, R = L, grazing light,
V = −L, spans of 1 and 2048 pixels, ROM address wrap, smallest and largest divisor,
all-ones and all-zeros codes — those that apply to the block.  Each row has

* the raw inputs, built from the block's config (:attr:`Extreme.build`);
* the documented behaviour (:attr:`Extreme.expected`: Lyon 1993 Figures 7–8 and 5,
  Schlick 1994 eq. (3), Szirmay-Kalos et al. 2000 Figure 12, Hast et al. eqs. 16–17,
  as each golden module's docstring states it), checked on the golden outputs by
  :attr:`Extreme.holds` from exact constants and closed forms in Python integers or
  Fractions, not from the model;
* golden = RTL: :func:`phongfx.sim.harness.check`, cycle by cycle, one run per block
  with every row's vectors back to back (stateful blocks: every row starts with
  ``init``), mismatches attributed to rows by vector index.

Deterministic: random directions come from a generator seeded per row.
"""

import json
import time
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from phongfx.core.registry import block_names, get_block
from phongfx.core.format import Format

__all__ = ["Extreme", "EXTREMES", "TABLES", "rows_for", "run_block", "run_table", "markdown",
           "to_json"]

#: Tables this module knows.
TABLES = ("extremes",)


@dataclass(frozen=True)
class Extreme:
    """An extreme input class of one block.

    ``build(config)`` gives raw input codes ``{port: int64 array}``; ``holds(config,
    inputs, outputs)`` a bool per vector: the golden output shows ``expected``.
    """

    block: str
    name: str
    expected: str
    build: object
    holds: object


# -- helpers ------------------------------------------------------------------------------

_AXES = np.concatenate([np.eye(3), -np.eye(3)])
_Z, _X = np.array([0.0, 0, 1]), np.array([1.0, 0, 0])


def _codes(values, fmt):
    from phongfx.sim.stimulus import codes
    return codes(np.asarray(values, dtype=np.float64), Format.parse(fmt))


def _full(fmt, code, lanes=3, count=1):
    return np.full((count, lanes) if lanes > 1 else count, code, dtype=np.int64)


def _eq(got, want):
    got = np.asarray(got)
    return np.all(np.reshape(got == want, (len(got), -1)), axis=-1)


def _round(value, fmt, rounding="round_half_up"):
    """Exact Fraction ``value`` to a raw code of ``fmt``, saturated: floored, or rounded half
    up (the two roundings the blocks' defaults use)."""
    scaled = value * fmt.one
    code = scaled.numerator // scaled.denominator
    if rounding == "round_half_up" and scaled - code >= Fraction(1, 2):
        code += 1
    return min(max(code, fmt.min_raw), fmt.max_raw)


def _wrap(code, fmt):
    """A Python int to ``fmt``'s register width, two's complement (the adders wrap)."""
    code &= (1 << fmt.width) - 1
    return code - (1 << fmt.width) if fmt.signed and code >> (fmt.width - 1) else code


def _perp():
    """Every ordered pair of perpendicular ±axes (24)."""
    first = np.repeat(_AXES, 6, axis=0)
    second = np.tile(_AXES, (6, 1))
    keep = np.abs(np.sum(first * second, axis=-1)) < 0.5
    return first[keep], second[keep]


def _unit(count, seed):
    v = np.random.default_rng(seed).normal(size=(count, 3))
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


# -- combinational blocks -----------------------------------------------------------------

def _lirp_axes(c):
    first, second = np.tile(_AXES, (6, 1)), np.repeat(_AXES, 6, axis=0)
    n0, n1 = np.tile(first, (2, 1)), np.tile(second, (2, 1))
    return {"n0": _codes(n0, c.vec), "n1": _codes(n1, c.vec),
            "a": _codes(np.repeat([0.0, 1.0], len(first)), c.a)}


def _lirp_ends(c, i, o):
    # a = 0 gives N0, a = 1 gives N1, exactly (out = vec by default)
    a0 = i["a"] == 0
    return _eq(o["n"], np.where(a0[:, None], i["n0"], i["n1"]))


def _lirp_codes(c):
    vec, afmt = c.fmt("vec"), c.fmt("a")
    ends = np.array([vec.max_raw, vec.min_raw, 0, -1])
    a = np.array([0, 1, afmt.one // 2, afmt.one])
    n = np.repeat(ends, len(a))[:, None] * np.ones(3, dtype=np.int64)
    return {"n0": n, "n1": n, "a": np.tile(a, len(ends))}


def _normalize_codes(c):
    vec = c.fmt("vec")
    n = np.array([[vec.max_raw] * 3, [vec.min_raw] * 3, [vec.max_raw, vec.min_raw, 0],
                  [vec.min_raw, 0, 0], [vec.max_raw, 0, 0]], dtype=np.int64)
    return {"n": n}


def _shrinks(c, i, o):
    # z = N'·N' saturates below 2, where g ≤ 1: every lane shrinks toward 0, keeping its sign
    n, out = i["n"], o["n"]
    return np.all((np.abs(out) <= np.abs(n)) & (np.sign(out) * np.sign(n) >= 0), axis=-1)


def _corner(c, name="vec", high=True):
    fmt = c.fmt(name)
    return _full(fmt, fmt.max_raw if high else fmt.min_raw)


def _reflect_codes(c):
    vec = c.fmt("vec")
    n = np.array([[vec.max_raw] * 3, [vec.min_raw] * 3, [0] * 3], dtype=np.int64)
    return {"n": n, "v": n}


def _reflect_codes_hold(c, i, o):
    # N = V = (c, c, c): R = (2·3c² − 1)·c per lane, ±6 at the corners: saturates to the
    # end of ``out`` on the side of c, and 0 stays 0
    out = c.fmt("out")
    want = np.where(i["v"] > 0, out.max_raw, np.where(i["v"] < 0, out.min_raw, 0))
    return _eq(o["r"], want)


def _difference_rows(c, r, l, ns):
    count = len(r)
    return {"r": np.tile(_codes(r, c.vec), (len(ns), 1)), "l": np.tile(_codes(l, c.vec), (len(ns), 1)),
            "n": np.repeat(np.asarray(ns, dtype=np.int64), count)}


def _x2_exact(c, i, o):
    """2x = n·D·D (Figure 7c) with each lane of D = R − L saturated to ``d`` (so +2 becomes
    2 − 2⁻¹⁰ in S1.10, −2 stays), the rest exact, then rounded and saturated to ``x2``."""
    vec, d, x2 = c.fmt("vec"), c.fmt("d"), c.fmt("x2")
    want = []
    for r, l, n in zip(i["r"], i["l"], i["n"]):
        lanes = [_round(Fraction(int(a) - int(b), vec.one), d) for a, b in zip(r, l)]
        want.append(_round(int(n) * sum(Fraction(x, d.one) ** 2 for x in lanes), x2, c.rounding))
    return _eq(o["x2"], np.array(want))


def _root_d2(c, i, o):
    # |D_i| = 2 is rectified and saturated to 2 − 2⁻¹⁰, so x/2^k falls just short of 1:
    # at m = 1 the ideal f_1 = 0 comes out as at most 1 LSB; larger m pass the comparator
    spec = o["spec"]
    return np.where(i["m"] == 1, (spec >= 0) & (spec <= 1), spec == 0)


def _ns(c):
    return sorted({1, c.n_max})


def _ms(c):
    return sorted({1, c.m_max})


def _value(name, value):
    """Every vector's ``name`` output is exactly ``value`` (a float its format holds)."""
    def holds(c, i, o):
        fmt = c.outputs[name][0]
        return _eq(o[name], fmt.exact_raw(value))
    return holds


def _all(*checks):
    def holds(c, i, o):
        return np.all([check(c, i, o) for check in checks], axis=0)
    return holds


def _root_rows(c, r, l):
    ms = _ms(c)
    return {"r": np.tile(_codes(r, c.vec), (len(ms), 1)), "l": np.tile(_codes(l, c.vec), (len(ms), 1)),
            "m": np.repeat(np.asarray(ms, dtype=np.int64), len(r))}


def _schlick(ts, ns):
    ts, ns = np.asarray(ts, dtype=np.int64), np.asarray(ns, dtype=np.int64)
    return {"t": np.tile(ts, len(ns)), "n": np.repeat(ns, len(ts))}


def _schlick_floor(c, i, o):
    # Schlick (1994) eq. (3) S = t/(n − n·t + t), the exact quotient floored to ``out``
    one, out = c.fmt("t").one, c.fmt("out")
    want = [_round(Fraction(int(t), one) / (n - n * Fraction(int(t), one) + Fraction(int(t), one)),
                   out, c.rounding) for t, n in zip(i["t"], i["n"])]
    return _eq(o["spec"], np.array(want))


def _conv(c, normal, light, half, ns):
    rows = {k: np.tile(_codes(v, c.vec), (len(ns), 1)) for k, v in
            (("normal", normal), ("light", light), ("half", half))}
    rows["n"] = np.repeat(np.asarray(ns, dtype=np.int64), len(normal))
    return rows


# -- stateful blocks: scanlines, each starting with ``init`` ------------------------------

def _sph_span(c, length, b, s, cval, bd=None, sd=None, cd=None, seed=0):
    from phongfx.sim.stimulus.spherical import span
    return span(c, length, np.random.default_rng(seed), b=b, s=s, c=cval, bd=bd, sd=sd,
                cd=cd if cd is None else [cd] * 3)


def _sph_fresh(c, i, o):
    # θ accumulates modulo 2π (Figure 12's adder wraps): pixel X of a span equals a fresh
    # init at b + X·s (and b_d + X·s_d) wrapped to the register
    from phongfx.golden.euler import segments
    theta = c.fmt("theta")
    last, k = segments(i["init"])
    fresh = {"init": np.ones_like(i["init"]), "s": np.zeros_like(i["s"]), "sd": np.zeros_like(i["sd"]),
             "b": np.array([_wrap(int(b) + int(kk) * int(s), theta) for b, s, kk in
                            zip(i["b"][last], i["s"][last], k)]),
             "bd": np.array([_wrap(int(b) + int(kk) * int(s), theta) for b, s, kk in
                             zip(i["bd"][last], i["sd"][last], k)]),
             "c": i["c"][last], "cd": i["cd"][last]}
    want = get_block("spherical", config=c).golden(fresh)
    return _eq(o["spec"], want["spec"]) & _eq(o["diff"], want["diff"])


def _sph_peak(c, i, o):
    # θ = 0: cos²0 = cos 0 = 1 saturates the ROM word to 1 − 2^-D; out = C·(1 − 2^-D) rounded
    rom, cfmt, out = c.fmt("rom"), c.fmt("c"), c.fmt("out")
    word = Fraction(rom.max_raw, rom.one)
    spec = [_round(Fraction(int(x), cfmt.one) * word, out, c.rounding) for x in i["c"]]
    return _eq(o["spec"], np.array(spec)) & _eq(o["diff"], np.array(spec)[:, None])


def _sph_rows(c, spans):
    parts = [_sph_span(c, *args, seed=index) for index, args in enumerate(spans)]
    return {k: np.concatenate([p[k] for p in parts]) for k in parts[0]}


def _euler_span(c, length, seed=0, **loads):
    from phongfx.sim.stimulus.euler import span
    return span(c, length, np.random.default_rng(seed), **loads)


def _gouraud_span(c, length, seed=0, **loads):
    from phongfx.sim.stimulus.gouraud import span
    return span(c, length, np.random.default_rng(seed), **loads)


def _geometric(module, c, length, seed):
    from importlib import import_module
    return import_module(f"phongfx.sim.stimulus.{module}").geometric(c, length, np.random.default_rng(seed))


def _closed_form(c, i, o, steps):
    """Hast et al. eq. (14) in Python integers: ``p_k = p0 + k·t0 + k(k−1)/2·ds`` (Gouraud:
    ``p0 + k·dp``) on ``p``'s grid, wrapped like the register; ``level = floor(2^F·p)``
    clamped to ``out``."""
    from phongfx.golden.euler import segments
    p, out = c.fmt("p"), c.fmt("out")
    last, k = segments(i["init"])
    want = []
    for j, kk in zip(last, k):
        value = int(i["p0"][j]) << 0
        for order, (port, fmt) in enumerate(steps, start=1):
            coeff = kk if order == 1 else kk * (kk - 1) // 2
            value += coeff * (int(i[port][j]) << (p.frac_bits - c.fmt(fmt).frac_bits))
        want.append(_wrap(value, p))
    want = np.array(want)
    level = np.clip(want >> (p.frac_bits - out.frac_bits), out.min_raw, out.max_raw)
    return _eq(o["p"], want) & _eq(o["level"], level)


def _euler_form(c, i, o):
    return _closed_form(c, i, o, (("t0", "t"), ("ds", "ds")))


def _gouraud_form(c, i, o):
    return _closed_form(c, i, o, (("dp", "dp"),))


#: load port -> register format field, Euler and Gouraud units
_REGISTER = {"t0": "t", "ds": "ds", "dp": "dp"}


def _cat(*parts):
    return {k: np.concatenate([np.asarray(p[k]) for p in parts]) for k in parts[0]}


# -- whole datapaths ----------------------------------------------------------------------

def _top(c):
    name, _, top = c.shininess
    return top if name == "n" else top * top  # encode takes n; Figure 8 gets m = √n


def _dp(c, n0, n1, a, v, lights, ns):
    from phongfx.sim.stimulus.datapath import encode
    n0, n1 = np.atleast_2d(n0), np.atleast_2d(n1)
    parts = [encode(c, n0, n1, np.full(len(n0), a), np.full(len(n0), n), v, v, lights, lights)
             for n in ns]
    return _cat(*parts)


def _dp_out(spec, diff):
    def holds(c, i, o):
        ok = np.ones(len(o["spec0"]), dtype=bool)
        for index in range(c.lights):
            for name, value in ((f"spec{index}", spec), (f"diff{index}", diff)):
                if value is not None:
                    ok &= _eq(o[name], c.outputs[name][0].exact_raw(value))
        return ok
    return holds


def _dp_rows(block):
    spec_vl = 1.0 if block == "halfway_datapath" else 0.0
    note = ("H = (V+L)/2 = 0 gives D = 0: a full highlight, ungated by N·L < 0"
            if block == "halfway_datapath" else "|D| = 2: x ≥ 2^k")
    return [
        (block, "exactly ±1.0: N = V = L (R = L), n = 1 and n_max",
         "spec = 1.0 and diff = 1.0 exactly",
         lambda c: _cat(*(_dp(c, _Z, _Z, a, _Z, [_Z], (1, _top(c))) for a in (0.0, 1.0))),
         _dp_out(1.0, 1.0)),
        (block, "zero-length N' at 180° (N0 = −N1, a = 1/2), n_max",
         "N = 0: diff = 0; spec = 0 (x ≥ 2^k at the largest n)",
         lambda c: _dp(c, _AXES[:3], -_AXES[:3], 0.5, _Z, [_Z, _X], (_top(c),)), _dp_out(0.0, 0.0)),
        (block, "grazing light (N ⟂ L), n_max", "diff = 0, spec = 0",
         lambda c: _dp(c, _Z, _Z, 0.0, _Z, [_X, -_X[[1, 0, 2]]], (_top(c),)), _dp_out(0.0, 0.0)),
        (block, "V = −L (N = V), n_max", f"diff = 0 (N·L = −1); spec = {spec_vl:g} ({note})",
         lambda c: _dp(c, _Z, _Z, 0.0, _Z, [-_Z], (_top(c),)), _dp_out(spec_vl, 0.0)),
    ]


# -- the table ----------------------------------------------------------------------------

def _rows():
    eq_in = lambda port, out: lambda c, i, o: _eq(o[out], i[port])  # noqa: E731
    zero = lambda name: _value(name, 0.0)  # noqa: E731
    graze_r, graze_v = _perp()
    u = _unit(8, 1)
    rows = [
        ("lirp", "exactly ±1.0 (a = 0 and 1, ±axes)", "N = N0 at a = 0, N1 at a = 1, exactly",
         _lirp_axes, _lirp_ends),
        ("lirp", "zero-length at 180° (N0 = −N1, a = 1/2)", "N = 0 exactly",
         lambda c: {"n0": _codes(_AXES, c.vec), "n1": _codes(-_AXES, c.vec),
                    "a": _full(c.fmt("a"), c.fmt("a").one // 2, 1, 6)}, zero("n")),
        ("lirp", "all-ones and all-zeros codes (N0 = N1)", "N = N0 exactly for every a (no overflow)",
         _lirp_codes, eq_in("n0", "n")),
        ("normalize", "exactly ±1.0 (±axes)", "N unchanged (g(1) = 1)",
         lambda c: {"n": _codes(_AXES, c.vec)}, eq_in("n", "n")),
        ("normalize", "zero-length (all-zeros code)", "N = 0",
         lambda c: {"n": np.zeros((1, 3), dtype=np.int64)}, zero("n")),
        ("normalize", "all-ones codes (|N'| up to 2√3)",
         "z saturates below 2, g ≤ 1: each lane shrinks toward 0 keeping its sign",
         _normalize_codes, _shrinks),
        ("reflect", "exactly ±1.0, N = ±V", "R = V exactly",
         lambda c: {"n": _codes(np.concatenate([_AXES, _AXES]), c.vec),
                    "v": _codes(np.concatenate([_AXES, -_AXES]), c.vec)}, eq_in("v", "r")),
        ("reflect", "grazing (N ⟂ V)", "R = −V exactly",
         lambda c: {"n": _codes(graze_r, c.vec), "v": _codes(graze_v, c.vec)},
         lambda c, i, o: _eq(o["r"], -i["v"])),
        ("reflect", "all-ones and all-zeros codes (N = V)",
         "saturates to ±(2 − 2⁻¹⁰) on the side of V; 0 stays 0", _reflect_codes, _reflect_codes_hold),
        ("difference", "R = L (±axes and random), n = 1 and n_max", "2x = 0",
         lambda c: _difference_rows(c, np.concatenate([_AXES, u]), np.concatenate([_AXES, u]), _ns(c)),
         zero("x2")),
        ("difference", "|D| = 2 (R = −L), n = 1 and n_max", "2x = n·|D|², D = +2 saturated to 2 − 2⁻¹⁰ (−2 exact); sum saturated to 8192 − 2⁻¹²",
         lambda c: _difference_rows(c, _AXES, -_AXES, _ns(c)), _x2_exact),
        ("difference", "grazing (R ⟂ L, |D|² = 2), n = 1 and n_max", "2x = 2n exactly, saturated to 8192 − 2⁻¹²",
         lambda c: _difference_rows(c, graze_r, graze_v, _ns(c)), _x2_exact),
        ("difference", "all-ones codes (R = max, L = min), n_max", "saturates to 8192 − 2⁻¹²",
         lambda c: {"r": _corner(c), "l": _corner(c, high=False), "n": _full(c.fmt("n"), c.n_max, 1)},
         lambda c, i, o: _eq(o["x2"], c.fmt("x2").max_raw)),
        ("shape", "all-zeros code (x = 0)", "f_k(0) = 1.0 exactly",
         lambda c: {"x2": np.zeros(1, dtype=np.int64)}, _value("spec", 1.0)),
        ("shape", "x/2^k = 1 and past it, all-ones code", "0",
         lambda c: {"x2": np.concatenate([np.arange(16) + (1 << (c.k + 1 + c.fmt("x2").frac_bits)),
                                          [c.fmt("x2").max_raw]])}, zero("spec")),
        ("diffuse", "exactly ±1.0, N = L", "1.0 exactly",
         lambda c: {"n": _codes(_AXES, c.vec), "l": _codes(_AXES, c.vec)}, _value("diff", 1.0)),
        ("diffuse", "N = −L", "0 (backside test)",
         lambda c: {"n": _codes(_AXES, c.vec), "l": _codes(-_AXES, c.vec)}, zero("diff")),
        ("diffuse", "grazing light (N ⟂ L)", "0",
         lambda c: {"n": _codes(graze_r, c.vec), "l": _codes(graze_v, c.vec)}, zero("diff")),
        ("diffuse", "all-ones codes (N = L = max)", "saturates to 2 − 2⁻¹⁰",
         lambda c: {"n": _corner(c), "l": _corner(c)},
         lambda c, i, o: _eq(o["diff"], c.fmt("out").max_raw)),
        ("root", "R = L, m = 1 and m_max", "spec = 1.0 exactly",
         lambda c: _root_rows(c, np.concatenate([_AXES, u]), np.concatenate([_AXES, u])),
         _value("spec", 1.0)),
        ("root", "|D| = 2 (R = −L), m = 1 and m_max", "m_max: 0; m = 1: ≤ 2⁻¹⁵ (ideal 0: |D| saturates to 2 − 2⁻¹⁰, x/2 = 1 − 2⁻¹⁰)",
         lambda c: _root_rows(c, _AXES, -_AXES), _root_d2),
        ("root", "grazing (R ⟂ L), m = 1", "f_1(1) = (1 − 1/2)² = 1/4 exactly",
         lambda c: {"r": _codes(graze_r, c.vec), "l": _codes(graze_v, c.vec),
                    "m": np.ones(len(graze_r), dtype=np.int64)}, _value("spec", 0.25)),
        ("root", "all-ones codes (R = max, L = min), m_max", "0",
         lambda c: {"r": _corner(c), "l": _corner(c, high=False), "m": _full(c.fmt("m"), c.m_max, 1)},
         zero("spec")),
        ("halfway", "exactly ±1.0, V = L = N (peak)", "p = q = N (D = 0)",
         lambda c: {k: _codes(_AXES, c.vec) for k in "nlv"},
         lambda c, i, o: _eq(o["p"], i["n"]) & _eq(o["q"], i["n"])),
        ("halfway", "V = −L (zero-length H)", "p = q = 0",
         lambda c: {"n": _codes(np.roll(_AXES, 1, axis=0), c.vec), "l": _codes(-_AXES, c.vec),
                    "v": _codes(_AXES, c.vec)}, _all(zero("p"), zero("q"))),
        ("halfway", "grazing (V = L ⟂ N)", "p = 0, q = L",
         lambda c: {"n": _codes(graze_r, c.vec), "l": _codes(graze_v, c.vec), "v": _codes(graze_v, c.vec)},
         lambda c, i, o: _eq(o["p"], 0) & _eq(o["q"], i["l"])),
        ("schlick", "smallest divisor: t = 1.0, n = 1 … n_max", "S = 1.0 exactly",
         lambda c: _schlick([c.fmt("t").one], sorted({1, 2, c.n_max})), _value("spec", 1.0)),
        ("schlick", "n = 1 (divisor 1)", "S = t exactly",
         lambda c: _schlick([0, 1, c.fmt("t").one // 2, c.fmt("t").one - 1, c.fmt("t").one], [1]),
         lambda c, i, o: _eq(o["spec"], i["t"])),
        ("schlick", "largest divisor: t = 0, n = n_max", "0",
         lambda c: _schlick([0], [c.n_max]), zero("spec")),
        ("schlick", "all-ones codes: t = 1 − 2⁻¹⁵, 1 LSB; n = 2^j − 1, n_max",
         "floor of the exact t/(n − n·t + t)",
         lambda c: _schlick([1, c.fmt("t").one - 1],
                            [n for n in (1, 3, 255, 4095, c.n_max - 1, c.n_max) if n <= c.n_max]),
         _schlick_floor),
        ("spherical", "span of 1 pixel at θ = 0", "C·(1 − 2⁻⁶) rounded (cos² 0 = 1 saturates the ROM)",
         lambda c: _sph_rows(c, [(1, 0, 0, x, 0, 0, x) for x in (c.fmt("c").max_raw, 1, c.fmt("c").one)]),
         _sph_peak),
        ("spherical", "span of 1 pixel at θ = π/2 and −π", "0 (cos ≤ 0 past ±π/2)",
         lambda c: _sph_rows(c, [(1, q, 0, c.fmt("c").max_raw, q, 0, c.fmt("c").max_raw)
                                 for q in (1 << (c.fmt("theta").width - 2), c.fmt("theta").min_raw)]),
         _all(zero("spec"), zero("diff"))),
        ("spherical", "span of 2048 pixels (θ turns 8 times)", "pixel X = fresh init at b + X·s mod 2π",
         lambda c: _sph_rows(c, [(2048, c.fmt("theta").min_raw, (1 << c.fmt("theta").width) // 256 + 1,
                                  c.fmt("c").max_raw, 0, -3)]), _sph_fresh),
        ("spherical", "ROM address wrap at ±π (all-ones codes)", "pixel X = fresh init at b + X·s mod 2π",
         lambda c: _sph_rows(c, [(6, c.fmt("theta").max_raw - 2, 1, c.fmt("c").max_raw,
                                  c.fmt("theta").min_raw + 1, -1),
                                 (4, c.fmt("theta").max_raw, c.fmt("theta").max_raw, c.fmt("c").max_raw,
                                  c.fmt("theta").min_raw, c.fmt("theta").min_raw)]), _sph_fresh),
        ("spherical", "all-zeros codes (C = 0)", "0",
         lambda c: _sph_rows(c, [(4, 0, 5, 0, 0, 5, 0)]), _all(zero("spec"), zero("diff"))),
    ]
    for block, module, form in (("euler", "euler", _euler_form), ("gouraud", "gouraud", _gouraud_form)):
        spans = _euler_span if block == "euler" else _gouraud_span
        step = ("t0", "ds") if block == "euler" else ("dp",)
        rows += [
            (block, "span of 1 pixel, p0 at the ends and 1.0", "p = p0; level = floor(256·p0) in 0..255",
             lambda c, s=spans: _cat(*(s(c, 1, seed=j, p0=code) for j, code in enumerate(
                 (c.fmt("p").min_raw, c.fmt("p").max_raw, 0, -1, min(c.fmt("p").one, c.fmt("p").max_raw))))),
             form),
            (block, "span of 2048 pixels (geometric setup)", "closed form p0 + k·t0 + k(k−1)/2·ds, wrapped",
             lambda c, m=module: _geometric(m, c, 2048, 3), form),
            (block, "all-ones codes (registers wrap)", "closed form, wrapped modulo 2^width",
             lambda c, s=spans, st=step: s(c, 8, seed=4, p0=c.fmt("p").max_raw,
                                           **{k: c.fmt(_REGISTER[k]).max_raw for k in st}), form),
            (block, "all-zeros codes", "p = 0, level = 0",
             lambda c, s=spans, st=step: s(c, 8, seed=5, p0=0, **{k: 0 for k in st}),
             _all(zero("p"), zero("level"))),
        ]
    rows += [
        ("conventional", "zero-length N (all-zeros code), n = 1 and n_max", "diffuse = specular = 0",
         lambda c: _conv(c, [[0, 0, 0]], [_Z], [_Z], (1, c.n_max)), _all(zero("diffuse"), zero("specular"))),
        ("conventional", "exactly ±1.0: N = L = H, n = 1 and n_max", "diffuse = specular = 1.0 exactly",
         lambda c: _conv(c, _AXES, _AXES, _AXES, (1, c.n_max)),
         _all(_value("diffuse", 1.0), _value("specular", 1.0))),
        ("conventional", "N·H = −1 and grazing L (N ⟂ L), n = 1 and n_max", "diffuse = specular = 0",
         lambda c: _conv(c, graze_r, graze_v, -graze_r, (1, c.n_max)),
         _all(zero("diffuse"), zero("specular"))),
    ]
    for block in ("fig7", "fig8", "halfway_datapath"):
        rows += _dp_rows(block)
    return rows


#: Every row of the table, in order.
EXTREMES = tuple(Extreme(*row) for row in _rows())


def rows_for(block):
    """The :class:`Extreme` rows of ``block``."""
    return tuple(row for row in EXTREMES if row.block == block)


def run_block(block_name, backend="amaranth", **options):
    """Rows of one block: golden against ``expected`` per row, then one harness run of all
    rows' vectors back to back, mismatching cycles attributed to rows by vector index."""
    from phongfx.sim.harness import check
    block = get_block(block_name)
    extremes = rows_for(block_name)
    inputs, results, start = [], [], 0
    for extreme in extremes:
        raw = {k: np.asarray(v, dtype=np.int64) for k, v in extreme.build(block.config).items()}
        count = len(next(iter(raw.values())))
        try:
            holds = np.asarray(extreme.holds(block.config, raw, block.golden(raw)), dtype=bool)
            golden = "pass" if holds.all() else f"FAIL ({int((~holds).sum())}/{count})"
        except Exception as error:  # a row's verdict, not the table's end: noted in the row
            golden = f"FAIL ({type(error).__name__}: {error})"
        results.append({"block": block_name, "class": extreme.name, "expected": extreme.expected,
                        "vectors": count, "golden": golden, "first": start})
        inputs.append(raw)
        start += count
    t0 = time.perf_counter()
    result = check(block, _cat(*inputs), backend=backend, bubbles=0, max_report=start + 1, **options)
    seconds = time.perf_counter() - t0
    bad = np.array([m.index for m in result.mismatches if m.index >= 0], dtype=np.int64)
    stray = sum(m.index < 0 for m in result.mismatches)
    for row in results:
        first = row.pop("first")
        count = int(np.count_nonzero((bad >= first) & (bad < first + row["vectors"])))
        row["rtl"] = "pass" if not count and not stray else f"FAIL ({count + stray} cycles)"
        row["backend"] = backend
    return results, seconds


def run_table(name, out_dir=None, backend="amaranth"):
    """The table called ``name`` (one of :data:`TABLES`); nothing is written to ``out_dir``."""
    if name not in TABLES:
        raise ValueError(f"unknown table {name!r}; valid tables: {', '.join(TABLES)}")
    rows, seconds = [], {}
    for block in block_names():
        if rows_for(block):
            block_rows, seconds[block] = run_block(block, backend)
            rows += block_rows
    return {"source": "GitHub issue 6, §2: extreme input classes per block", "backend": backend,
            "rows": rows, "seconds": seconds}


def markdown(result):
    """One line per (block, class): expected behaviour, golden verdict, RTL verdict."""
    lines = [f"# Extremes: golden against the documented behaviour, RTL against golden "
             f"({result['backend']})", "",
             "| block | extreme class | vectors | expected | golden | RTL |", "|---|---|---|---|---|---|"]
    for r in result["rows"]:
        cells = (r["block"], r["class"], r["vectors"], r["expected"], r["golden"], r["rtl"])
        lines.append("| " + " | ".join(str(cell).replace("|", "\\|") for cell in cells) + " |")
    failed = sum(r["golden"] != "pass" or r["rtl"] != "pass" for r in result["rows"])
    lines += ["", f"{len(result['rows'])} rows over {len(result['seconds'])} blocks; "
                  f"{failed} failing.", ""]
    return "\n".join(lines)


def to_json(result):
    # the run times differ between runs; the table itself is deterministic
    stable = {k: v for k, v in result.items() if k != "seconds"}
    return json.dumps(stable, indent=2, ensure_ascii=False)
