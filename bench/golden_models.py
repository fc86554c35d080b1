"""Rival models of the Figure 7 datapath, for :mod:`bench.golden`.

The first two compute what :func:`phongfx.golden.datapath.datapath` computes for a Figure 7
configuration (Lyon 1993, Figures 7a–d: LIRP ``N' = (1-a)N0 + aN1``, normalizer
``g2 = 1 + (y + y²)/2`` with ``y = 1 - N'·N'``, reflect ``R = 2(N·V)N - V``,
``D = R - L``, ``2x = n·D·D``, shape ``f_k``; and the diffuse term ``max(N·L, 0)``),
with the same formats, rounding and saturation, so their outputs are bit-identical:

* :func:`fig7_apytypes` with ``apytypes`` arrays (C++, exact fixed-point growth);
* :func:`fig7_loop` one pixel at a time on plain Python ints, as in Lyon's appendix.

The third, :func:`fig7_float`, is the same formula in float64 with nothing quantized: not
bit-identical, but the speed a bit-exact model is held against (it does the same array
passes, without the roundings and range checks).

Unsigned formats are held by apytypes as signed ones with the same top (one more
integer bit for the sign); nothing on this path quantizes a negative value into
an unsigned format (``z``, ``y²``, ``g``, ``D·D``, ``2x``, ``t`` are non-negative,
and the diffuse clamp at 0 commutes with the monotone rounding), so the bottoms
never differ.
"""

import numpy as np

__all__ = ["fig7_apytypes", "fig7_loop", "fig7_float"]


def _check(config):
    if (config.specular != "fig7" or config.any_local
            or config.normalize.order != 2):
        raise ValueError("the rival models cover Figure 7 with lights and viewer at infinity "
                         "and the g2 normalizer only")


def fig7_apytypes(config, raw):
    """Figure 7 on raw input codes with apytypes; returns raw output codes like the golden model."""
    import apytypes as apy

    _check(config)
    array = apy.APyFixedArray
    one = apy.APyFixed.from_float(1.0, int_bits=2, frac_bits=0)

    def load(codes, fmt):
        # raw·lsb is exact in float64 for formats up to 53 bits
        return array.from_array(np.asarray(codes, dtype=np.float64) * fmt.lsb,
                                int_bits=fmt.int_bits + 1, frac_bits=fmt.frac_bits)

    def cast(value, fmt, rounding):
        mode = apy.QuantizationMode.RND if rounding == "round_half_up" else apy.QuantizationMode.TRN
        return value.cast(int_bits=fmt.int_bits + 1, frac_bits=fmt.frac_bits, quantization=mode,
                          overflow=apy.OverflowMode.SAT)

    def codes(value, fmt):
        return np.rint(value.to_numpy() * (1 << fmt.frac_bits)).astype(np.int64)

    def vector(name, fmt):
        return [load(raw[name][:, i], fmt) for i in range(3)]

    def dot(u, v):
        return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]

    lc, nc, rc, dc, sc = config.lirp, config.normalize, config.reflect, config.difference, config.shape
    a = load(raw["a"], config.inputs["a"][0])
    b = one - a
    n0, n1 = vector("n0", config.inputs["n0"][0]), vector("n1", config.inputs["n1"][0])
    p = [cast(n0[i] * b + n1[i] * a, lc.fmt("out"), lc.rounding) for i in range(3)]
    y = one - cast(dot(p, p), nc.fmt("z"), nc.rounding)
    half = y + cast(y * y, nc.fmt("y2"), nc.rounding)
    g = cast(one + (half >> 1), nc.fmt("g"), nc.rounding)
    normal = [cast(p[i] * g, nc.fmt("out"), nc.rounding) for i in range(3)]
    view = vector("v", config.inputs["v"][0])
    twice = cast(dot(normal, view), rc.fmt("dot"), rc.rounding) << 1
    r = [cast(normal[i] * twice - view[i], rc.fmt("out"), rc.rounding) for i in range(3)]
    shininess = load(raw["n"], config.inputs["n"][0])
    out = {}
    for index in range(config.lights):
        light = vector(f"l{index}", config.inputs[f"l{index}"][0])
        d = [cast(r[i] - light[i], dc.fmt("d"), dc.rounding) for i in range(3)]
        x2 = cast(shininess * cast(dot(d, d), dc.fmt("dd"), dc.rounding), dc.fmt("x2"), dc.rounding)
        v = x2 >> (sc.k + 1)
        whole = v.cast(int_bits=v.int_bits, frac_bits=0, quantization=apy.QuantizationMode.TRN)
        t = cast(one - (v - whole), sc.fmt("t"), sc.rounding)
        for _ in range(sc.k):
            t = cast(t * t, sc.fmt("t"), sc.rounding)
        out[f"spec{index}"] = np.where(whole.to_numpy() >= 1, 0, codes(t, sc.fmt("t")))
        lit = cast(dot(normal, light), config.diffuse.fmt("out"), config.diffuse.rounding)
        out[f"diff{index}"] = np.maximum(codes(lit, config.diffuse.fmt("out")), 0)
    return out


def _quantize(value, drop, fmt, rounding):
    """``value`` (raw, ``drop`` more fraction bits than ``fmt``) rounded and saturated into ``fmt``."""
    if drop > 0:
        value = (value + (1 << (drop - 1))) >> drop if rounding == "round_half_up" else value >> drop
    elif drop < 0:
        value <<= -drop
    return fmt.min_raw if value < fmt.min_raw else fmt.max_raw if value > fmt.max_raw else value


def fig7_loop(config, raw):
    """Figure 7 one pixel at a time on Python ints (Lyon's appendix style); raw codes out."""
    _check(config)
    lc, nc, rc, dc, sc = config.lirp, config.normalize, config.reflect, config.difference, config.shape
    fa, fv, fo = config.inputs["a"][0].frac_bits, config.inputs["n0"][0].frac_bits, lc.fmt("out").frac_bits
    z_fmt, y2_fmt, g_fmt, n_fmt = nc.fmt("z"), nc.fmt("y2"), nc.fmt("g"), nc.fmt("out")
    dot_fmt, r_fmt, d_fmt, dd_fmt = rc.fmt("dot"), rc.fmt("out"), dc.fmt("d"), dc.fmt("dd")
    x2_fmt, t_fmt, diff_fmt = dc.fmt("x2"), sc.fmt("t"), config.diffuse.fmt("out")
    fvv, fl = config.inputs["v"][0].frac_bits, config.inputs["l0"][0].frac_bits
    fy = max(z_fmt.frac_bits, y2_fmt.frac_bits)
    fg = max(fy + 1, g_fmt.frac_bits)  # 1 + half/2, aligned as the golden adder aligns it
    fr = max(n_fmt.frac_bits + dot_fmt.frac_bits - 1, fvv)
    fd = max(r_fmt.frac_bits, fl)
    shift = x2_fmt.frac_bits + sc.k + 1
    rounding = nc.rounding
    columns = [raw[name].tolist() for name in ("n0", "n1", "a", "n", "v")]
    lights = [raw[f"l{i}"].tolist() for i in range(config.lights)]
    out = {f"{kind}{i}": [] for i in range(config.lights) for kind in ("spec", "diff")}
    for pixel, (n0, n1, a, n, v) in enumerate(zip(*columns)):
        b = (1 << fa) - a
        p = [_quantize(n0[i] * b + n1[i] * a, fv + fa - fo, lc.fmt("out"), lc.rounding) for i in range(3)]
        z = _quantize(p[0] * p[0] + p[1] * p[1] + p[2] * p[2], 2 * fo - z_fmt.frac_bits, z_fmt, rounding)
        y = (1 << z_fmt.frac_bits) - z
        y2 = _quantize(y * y, 2 * z_fmt.frac_bits - y2_fmt.frac_bits, y2_fmt, rounding)
        half = (y << (fy - z_fmt.frac_bits)) + (y2 << (fy - y2_fmt.frac_bits))
        g = _quantize((1 << fg) + (half << (fg - fy - 1)), fg - g_fmt.frac_bits, g_fmt, rounding)
        nn = [_quantize(p[i] * g, fo + g_fmt.frac_bits - n_fmt.frac_bits, n_fmt, rounding) for i in range(3)]
        nv = _quantize(nn[0] * v[0] + nn[1] * v[1] + nn[2] * v[2],
                       n_fmt.frac_bits + fvv - dot_fmt.frac_bits, dot_fmt, rc.rounding)
        r = [_quantize((nn[i] * nv << (fr - n_fmt.frac_bits - dot_fmt.frac_bits + 1)) - (v[i] << (fr - fvv)),
                       fr - r_fmt.frac_bits, r_fmt, rc.rounding) for i in range(3)]
        for index, light in enumerate(lights):
            l = light[pixel]
            d = [_quantize((r[i] << (fd - r_fmt.frac_bits)) - (l[i] << (fd - fl)), fd - d_fmt.frac_bits,
                           d_fmt, dc.rounding) for i in range(3)]
            dd = _quantize(d[0] * d[0] + d[1] * d[1] + d[2] * d[2], 2 * d_fmt.frac_bits - dd_fmt.frac_bits,
                           dd_fmt, dc.rounding)
            x2 = _quantize(n * dd, dd_fmt.frac_bits - x2_fmt.frac_bits, x2_fmt, dc.rounding)
            spec = 0
            if x2 < 1 << shift:  # f_k(x) = 0 once x/2^k >= 1
                t = _quantize((1 << shift) - (x2 & ((1 << shift) - 1)), shift - t_fmt.frac_bits, t_fmt, sc.rounding)
                for _ in range(sc.k):
                    t = _quantize(t * t, t_fmt.frac_bits, t_fmt, sc.rounding)
                spec = t
            lit = nn[0] * l[0] + nn[1] * l[1] + nn[2] * l[2]
            out[f"spec{index}"].append(spec)
            out[f"diff{index}"].append(0 if lit < 0 else _quantize(
                lit, n_fmt.frac_bits + fl - diff_fmt.frac_bits, diff_fmt, config.diffuse.rounding))
    return {key: np.array(value, dtype=np.int64) for key, value in out.items()}


def fig7_float(config, raw):
    """Figure 7's formula on the values of the raw input codes, in float64 numpy, nothing
    quantized: LIRP, ``g2`` normalizer, reflect, and per light ``D = R - L``, ``2x = n·D·D``,
    ``f_k`` (0 once ``x/2^k >= 1``) and ``max(N·L, 0)``; float ``spec<i>``, ``diff<i>`` out.

    Written for speed, as ours is: vectors as their X, Y, Z lanes, so that no product
    broadcasts a (count, 1) column over a (count, 3) array (numpy runs such a loop three values
    at a time), and the mux to 0 a multiply."""
    _check(config)

    def load(name):
        return raw[name] * config.inputs[name][0].lsb

    def lanes(name):
        value = load(name)
        return [value[:, i] for i in range(3)]

    def dot(u, v):
        return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]

    a = load("a")
    b = 1 - a
    p = [n0 * b + n1 * a for n0, n1 in zip(lanes("n0"), lanes("n1"))]
    y = 1 - dot(p, p)
    g = 1 + (y + y * y) / 2
    normal = [c * g for c in p]
    view = lanes("v")
    twice = 2 * dot(normal, view)
    r = [twice * n - v for n, v in zip(normal, view)]
    shininess, k = load("n"), config.shape.k
    out = {}
    for index in range(config.lights):
        light = lanes(f"l{index}")
        d = [ri - li for ri, li in zip(r, light)]
        v = shininess * dot(d, d) / 2 ** (k + 1)
        t = 1 - v
        for _ in range(k):
            t = t * t
        out[f"spec{index}"] = t * (v < 1)  # 0 past 2^k: a multiply, not np.where's branches
        out[f"diff{index}"] = np.maximum(dot(normal, light), 0.0)
    return out
