"""Scanline setup of the Euler and Gouraud units, Hast, Barrera & Bengtsson §2.1–3.2.

Host-side, float first, then quantized to the unit's formats
(:mod:`phongfx.golden.euler`, :mod:`phongfx.golden.gouraud`).  A span of ``length``
pixels runs from unit normal ``N_a`` (first pixel) to ``N_b`` (last pixel), so it takes
``n = length - 1`` steps: ``N = k·x + N_a``, ``k = (N_b - N_a)/n``, ``x = 0..n``.
For the diffuse term with unit light ``L`` (equations 2–4, 10–17):

* ``p = A·x + B``, ``A = k·L``, ``B = p_a = N_a·L``; ``q = C·x² + D·x + 1``,
  ``C = k·k``, ``D = 2k·N_a``; the exact intensity is Duff's ``p/√q`` (equation 4);
* ``dq_a = D`` and ``dq_b = -dq_a`` (equation 22, in place of ``2nC + D``);
* ``di_a = A - p_a·dq_a/2``, ``di_b = A - p_b·dq_b/2`` (equations 10, 11), and
  ``ds = (di_b - di_a)/n``;
* uncorrected Euler: ``s_0 = di_a`` (equations 12, 13), which ends at
  ``p_n = p_a + n·di_a + (n² - n)/2·ds`` (equation 14), off by ``ε = p_n - p_b``
  (equation 15);
* corrected Euler: ``t_0 = di_a - dε``, ``dε = ε/n`` (equations 16, 17; the paper's
  ``N`` is ``n``), which ends exactly at ``p_b``.

One pixel (``n = 0``) has ``t_0 = ds = 0``.  Gouraud: ``p_0 = p_a``, ``dp = (p_b - p_a)/n``.

Bounds for unit normals and light: ``|A| <= 2/n``, ``|dq_a| <= 4/n``, so ``|di| <= 4/n``,
``|ds| <= 8/n²``, ``|t_0| = |(p_b - p_a)/n - (n - 1)/2·ds| <= 6/n``, and the curve sags
at most ``n²/8·|ds| <= 1`` off its chord: ``|p| <= 2``.  The default formats
(``p`` ``S1.30``, ``t`` and ``ds`` ``S3.30``) hold all of it; :func:`quantize_setup`
raises if a load or the float curve ever leaves its format.
"""

import numpy as np

from phongfx.config import EulerConfig

from .fixed import Fixed

__all__ = ["span_setup", "span_setups", "curves_at", "duff_curve", "normalized_curve", "euler_curve",
           "gouraud_curve", "quantize_setup", "quantize_gouraud", "random_spans", "stability",
           "min_frac_bits"]


_SETUP_KEYS = ("A", "B", "C", "D", "p_a", "p_b", "dq_a", "dq_b", "di_a", "di_b", "ds", "eps", "deps", "t0")


def span_setups(na, nb, light, length):
    """Float setup of many spans at once (module docstring): ``na``, ``nb`` ``(S, 3)`` unit
    end normals, ``light`` ``(3,)`` or ``(S, 3)``, ``length`` ``(S,)`` pixels.  Returns a
    dict of ``(S,)`` arrays: ``n`` (int64) and the paper's ``A, B, C, D, p_a, p_b, dq_a,
    dq_b, di_a, di_b, ds, eps, deps, t0``; one-pixel spans have all steps exactly 0."""
    na, nb = np.atleast_2d(np.asarray(na, dtype=np.float64)), np.atleast_2d(np.asarray(nb, dtype=np.float64))
    light = np.broadcast_to(np.asarray(light, dtype=np.float64), na.shape)
    length = np.atleast_1d(np.asarray(length))
    if length.dtype.kind not in "iu":
        raise ValueError(f"length must be integers, not dtype {length.dtype}")
    if np.any(length < 1):
        raise ValueError(f"length must be a positive integer, not {int(length[length < 1][0])}")
    n = length.astype(np.int64) - 1
    many = n > 0
    steps = np.where(many, n, 1).astype(np.float64)[:, None]

    def dot(u, v):
        return u[:, 0] * v[:, 0] + u[:, 1] * v[:, 1] + u[:, 2] * v[:, 2]

    p_a, p_b = dot(na, light), dot(nb, light)
    k = np.where(many[:, None], (nb - na) / steps, 0.0)
    nf = steps[:, 0]
    A, C, D = dot(k, light), dot(k, k), 2 * dot(k, na)
    dq_a, dq_b = D, -D
    di_a, di_b = A - p_a / 2 * dq_a, A - p_b / 2 * dq_b
    ds = (di_b - di_a) / nf
    eps = np.where(many, p_a + nf * di_a + (nf * nf - nf) / 2 * ds - p_b, 0.0)
    deps = eps / nf
    return {"n": n, "p_a": p_a, "p_b": p_b, "B": p_a, "A": A, "C": C, "D": D, "dq_a": dq_a,
            "dq_b": dq_b, "di_a": di_a, "di_b": di_b, "ds": ds, "eps": eps, "deps": deps,
            "t0": di_a - deps}


def span_setup(na, nb, light, length):
    """Float setup of one span (module docstring): a dict of ``n`` and the paper's
    ``A, B, C, D, p_a, p_b, dq_a, dq_b, di_a, di_b, ds, eps, deps, t0``
    (:func:`span_setups` on one span)."""
    if not isinstance(length, (int, np.integer)) or length < 1:
        raise ValueError(f"length must be a positive integer, not {length!r}")
    many = span_setups(na, nb, light, [int(length)])
    return {"n": int(many["n"][0]), **{key: float(many[key][0]) for key in _SETUP_KEYS}}


def curves_at(setups, span, x):
    """Float intensities of pixel ``x`` (steps from the start) of span ``span`` (indices
    into :func:`span_setups` arrays), vectorized over pixels: a dict of ``phong`` (Duff's
    exact ``p/√q``, equation 4), ``euler`` (uncorrected, ``s_0 = di_a``, equations 12–14),
    ``corrected`` (``t_0``, equations 16–17) and ``gouraud`` (the chord ``p_a`` to ``p_b``)."""
    x = np.asarray(x, dtype=np.float64)
    s = {key: setups[key][span] for key in ("A", "B", "C", "D", "p_a", "p_b", "di_a", "t0", "ds")}
    n = setups["n"][span].astype(np.float64)
    bend = x * (x - 1) / 2 * s["ds"]
    return {"phong": (s["A"] * x + s["B"]) / np.sqrt(s["C"] * x * x + s["D"] * x + 1),
            "euler": s["p_a"] + x * s["di_a"] + bend,
            "corrected": s["p_a"] + x * s["t0"] + bend,
            "gouraud": s["p_a"] + x * np.divide(s["p_b"] - s["p_a"], n, out=np.zeros_like(n), where=n > 0)}


def duff_curve(setup):
    """Exact intensity ``p/√q`` at ``x = 0..n`` (equation 4)."""
    x = np.arange(setup["n"] + 1, dtype=np.float64)
    return (setup["A"] * x + setup["B"]) / np.sqrt(setup["C"] * x * x + setup["D"] * x + 1)


def normalized_curve(na, nb, light, length):
    """``N·L/|N|`` with ``N`` interpolated and normalized directly, pixel by pixel."""
    a = np.linspace(0.0, 1.0, length)[:, None] if length > 1 else np.zeros((1, 1))
    normals = (1 - a) * np.asarray(na, dtype=np.float64) + a * np.asarray(nb, dtype=np.float64)
    return normals @ np.asarray(light, dtype=np.float64) / np.linalg.norm(normals, axis=-1)


def euler_curve(setup, corrected=True):
    """Float Euler intensities at ``x = 0..n``: ``p_a + x·s_0 + x(x-1)/2·ds`` (equation 14),
    ``s_0 = t_0`` (corrected) or ``di_a`` (uncorrected)."""
    x = np.arange(setup["n"] + 1, dtype=np.float64)
    s0 = setup["t0"] if corrected else setup["di_a"]
    return setup["p_a"] + x * s0 + x * (x - 1) / 2 * setup["ds"]


def gouraud_curve(setup):
    """Float Gouraud intensities at ``x = 0..n``: the chord from ``p_a`` to ``p_b``."""
    n = setup["n"]
    return np.linspace(setup["p_a"], setup["p_b"], n + 1) if n else np.array([setup["p_a"]])


def _raw(value, fmt):
    return int(Fixed.from_float(value, fmt, "round_half_up", "error").raw)


def quantize_setup(config, setup, compensate=False):
    """Raw ``p0``, ``t0``, ``ds`` of one span for an :class:`EulerConfig`, rounded half up.

    ``compensate=False`` rounds the paper's float ``t_0``.  ``compensate=True`` computes
    the correction after quantizing: ``t_0`` is chosen in integers so that the unit's
    end ``P0 + n·T0 + n(n-1)/2·DS`` is nearest the rounded ``p_b``, which cancels the
    ``n(n-1)/2`` growth of the rounding of ``ds`` (only ``n/2`` LSB of ``t`` remain).
    Raises :class:`~phongfx.golden.fixed.FixedOverflowError` if a value, or the float
    corrected curve, does not fit its register.
    """
    p, t, d = config.fmt("p"), config.fmt("t"), config.fmt("ds")
    Fixed.from_float(euler_curve(setup), p, "round_half_up", "error")
    raw = {"p0": _raw(setup["p_a"], p), "ds": _raw(setup["ds"], d)}
    n = setup["n"]
    if compensate and n:
        up, down = 1 << (p.frac_bits - t.frac_bits), 1 << (p.frac_bits - d.frac_bits)
        rest = _raw(setup["p_b"], p) - raw["p0"] - n * (n - 1) // 2 * raw["ds"] * down
        den = n * up
        raw["t0"] = (2 * rest + den) // (2 * den)  # round half up of rest/den
        Fixed(raw["t0"], t)  # refuses a code outside t
    else:
        raw["t0"] = _raw(setup["t0"], t)
    return raw


def quantize_gouraud(config, setup):
    """Raw ``p0``, ``dp`` of one span for a :class:`GouraudConfig`, rounded half up."""
    n = setup["n"]
    dp = (setup["p_b"] - setup["p_a"]) / n if n else 0.0
    return {"p0": _raw(setup["p_a"], config.fmt("p")), "dp": _raw(dp, config.fmt("dp"))}


def random_spans(count, max_angle, generator):
    """``count`` (N_a, N_b, L): unit normals at most ``max_angle`` radians apart, any light."""
    def unit(size):
        v = generator.normal(size=(size, 3))
        return v / np.linalg.norm(v, axis=-1, keepdims=True)
    na, light, side = unit(count), unit(count), unit(count)
    side = side - np.sum(side * na, axis=-1, keepdims=True) * na
    side /= np.linalg.norm(side, axis=-1, keepdims=True)
    angle = generator.uniform(0, max_angle, size=(count, 1))
    return na, np.cos(angle) * na + np.sin(angle) * side, light


def stability(frac_bits, length, spans=32, max_angle=np.pi / 3, seed=0, compensate=False):
    """End-of-span error of the fixed-point unit with ``F = frac_bits`` fraction bits in
    ``p`` (``S1.F``), ``t`` and ``ds`` (``S3.F``), over ``spans`` seeded random spans of
    ``length`` pixels (normals up to ``max_angle`` apart, the paper's figures use 60°).

    Returns a dict: ``end`` max ``|p_end - p_b|`` in 8-bit levels (×256) against the exact
    end value; ``level`` max ``|level_end - floor(256·p_b)|`` (clamped to 0..255);
    ``span`` max over every pixel of ``|level - floor(256·curve)|`` against the float
    corrected Euler curve (what the fixed point alone costs).
    """
    from .euler import euler
    config = EulerConfig(p=f"S1.{frac_bits}", t=f"S3.{frac_bits}", ds=f"S3.{frac_bits}")
    g = np.random.default_rng(seed)
    setups = [span_setup(a, b, l, length) for a, b, l in zip(*random_spans(spans, max_angle, g))]
    raws = [quantize_setup(config, s, compensate) for s in setups]
    init = np.zeros(length * spans, dtype=np.int64)
    init[::length] = 1
    loads = {name: np.zeros(length * spans, dtype=np.int64) for name in ("p0", "t0", "ds")}
    for index, raw in enumerate(raws):
        for name in loads:
            loads[name][index * length] = raw[name]
    out = euler(config, Fixed(init, "1.0"), Fixed(loads["p0"], config.p), Fixed(loads["t0"], config.t),
                Fixed(loads["ds"], config.ds))
    p, level = out["p"].to_float().reshape(spans, length), out["level"].raw.reshape(spans, length)
    p_b = np.array([s["p_b"] for s in setups])
    curve = np.array([euler_curve(s) for s in setups])
    return {"end": float(np.max(np.abs(p[:, -1] - p_b))) * 256,
            "level": int(np.max(np.abs(level[:, -1] - _level(p_b)))),
            "span": int(np.max(np.abs(level - _level(curve))))}


def _level(value):
    """The unit's ``level`` of a float intensity: ``floor(256·p)`` clamped to 0..255."""
    return np.clip(np.floor(256 * value), 0, 255)


def min_frac_bits(length=2048, widths=range(8, 41), **options):
    """Smallest ``F`` from which on (every wider ``F`` in ``widths`` too) the end-of-span
    8-bit level stays within ±1 of the exact one (:func:`stability` ``level <= 1``),
    or None, and the table ``{F: stability(F, length)}``."""
    table = {f: stability(f, length, **options) for f in widths}
    best = None
    for frac_bits in sorted(table, reverse=True):
        if table[frac_bits]["level"] > 1:
            break
        best = frac_bits
    return best, table
