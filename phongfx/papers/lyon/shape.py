"""Lyon's shape-function claims, measured: Figure 3 (``f_k`` against ``cos^n``, the low-n
zero crossings) and the length-error sensitivity section (Apple TR #43, 1993).
Each builder returns ``(section, plot data)`` for :mod:`phongfx.papers.lyon.tables`.
"""

import math

import numpy as np

from phongfx.core.registry import get_block
from phongfx.papers.claims import first, row, within

from .common import K, alpha_of_x, f_k, fixed_shape, fixed_x2, rot_y, rotation, x_of_alpha

__all__ = ["figure3", "sensitivity"]


def figure3():
    n = 100
    q = rotation()
    light = q @ np.array([0.0, 0.0, 1.0])
    # dense grid (1e-5 rad) for the fixed-point crossings; every 500th point is plotted
    alpha = np.linspace(0.0, 0.4, 40001)
    r = rot_y(alpha) @ q.T
    x2 = fixed_x2(r, light, n)
    x = x_of_alpha(alpha, n)
    cosn = np.cos(alpha) ** n
    flt = {k: f_k(x, k) for k in K}
    fixed = {k: fixed_shape(x2, k) for k in K}

    half_cos = math.acos(0.5 ** (1.0 / n))
    stats = []
    for k in K:
        err = flt[k] - cosn
        worst = int(np.argmax(np.abs(err)))
        x_half = 2.0 ** k * (1.0 - 0.5 ** (1.0 / 2 ** k))
        half_float = float(alpha_of_x(x_half, n))
        half_fixed = first(alpha, fixed[k] <= 0.5)
        stats.append({
            "shape": f"f{k}",
            "max_abs_error_vs_cos_n": float(np.abs(err).max()),
            "at_alpha_deg": math.degrees(alpha[worst]),
            "signed_error_there": float(err[worst]),
            "mean_abs_error_vs_cos_n": float(np.abs(err).mean()),
            "fixed_max_abs_error_vs_float_fk": float(np.abs(fixed[k] - flt[k]).max()),
            "fixed_max_abs_error_vs_cos_n": float(np.abs(fixed[k] - cosn).max()),
            "half_alpha_deg_float": math.degrees(half_float),
            "half_alpha_deg_fixed": None if half_fixed is None else math.degrees(half_fixed),
            "half_ratio_to_cos_n": half_float / half_cos,
        })
    stats.append({"shape": "cos^n", "half_alpha_deg_float": math.degrees(half_cos)})

    # claims at the nominal radius 1/√n, where x ≈ 1/2
    nominal = 1.0 / math.sqrt(n)
    at = int(np.argmin(np.abs(alpha - nominal)))
    rows = [
        row("cos^n α at the nominal radius α = 1/√n = 0.1 rad (n = 100)", math.exp(-0.5),
             float(np.cos(nominal) ** n), None, paper_text="≈ exp(−1/2) = 0.6065",
             criterion="±0.002", holds_float=within(float(np.cos(nominal) ** n), math.exp(-0.5), 0.002),
             note="no cos^n datapath in fixed point"),
        row("f0 at the nominal radius (x ≈ 1/2)", 0.5, float(f_k(x_of_alpha(nominal, n), 0)),
             float(fixed[0][at]), criterion="±0.002 float, ±0.01 fixed",
             holds_float=within(float(f_k(x_of_alpha(nominal, n), 0)), 0.5, 0.002),
             holds_fixed=within(float(fixed[0][at]), 0.5, 0.01)),
        row("|D| = 2 sin(α/2) at α = π/2", 1.41, 2 * math.sin(math.pi / 4), None,
             paper_text="about 1.41", criterion="±0.005",
             holds_float=within(2 * math.sin(math.pi / 4), 1.41, 0.005)),
        row("n = 100: α vs |D| at cos^n's half-height, relative", 0.0,
             1.0 - 2 * math.sin(half_cos / 2) / half_cos, None, fmt="{:.4%}",
             paper_text="negligible (\"we don't need to correct\")", criterion="< 0.1 %",
             holds_float=bool(1.0 - 2 * math.sin(half_cos / 2) / half_cos < 1e-3)),
    ]
    for s in stats[:3]:
        rows.append(row(f"{s['shape']}: α where it falls to 1/2 (cos^n: {math.degrees(half_cos):.3f}°)",
                         None, s["half_alpha_deg_float"], s["half_alpha_deg_fixed"], fmt="{:.3f}°",
                         paper_text="—", criterion="fixed within 0.1° of float",
                         holds_fixed=within(s["half_alpha_deg_fixed"], s["half_alpha_deg_float"], 0.1),
                         note=f"{s['half_ratio_to_cos_n']:.3f} × cos^n's"))

    # low-n zero crossings in the text after Figure 3.  In fixed point the zero is where
    # Figure 7d's comparator fires (x >= 2^k); the output code can reach 0 earlier, when
    # t^(2^k) drops under half an LSB of t: reported in the note.
    wide = np.linspace(0.0, math.pi, 36001)  # 0.005° steps
    x2_lsb = get_block("difference").config.fmt("x2").lsb
    vec_lsb = get_block("difference").config.fmt("vec").lsb
    for n_low, k, paper_deg in ((4, 1, 60.0), (4, 2, 90.0), (1, 1, 180.0), (1, 2, None)):
        x2w = fixed_x2(rot_y(wide) @ q.T, light, n_low)
        spec = fixed_shape(x2w, k)
        zero_float = alpha_of_x(2.0 ** k, n_low)
        zero_float = None if np.isnan(zero_float) else math.degrees(float(zero_float))
        zero_fixed = first(wide, x2w * x2_lsb >= 2.0 ** (k + 1))
        zero_fixed = None if zero_fixed is None else math.degrees(zero_fixed)
        code_zero = first(wide, spec == 0)
        criterion = "±0.01° float, ±1° fixed"
        if paper_deg is None:
            criterion = "never, float and fixed"
            hf, hx = zero_float is None, zero_fixed is None
        elif paper_deg == 180.0:
            # |D|² = 4 - (π-α)² is flat at π: an error δ of the 10-bit |D|² (each D component
            # within 1 LSB: δ <= 2·|D|·√3 LSB) moves its crossing of 4 by up to √δ radians
            flat = math.degrees(math.sqrt(2 * 2 * math.sqrt(3) * vec_lsb))
            criterion = f"±0.01° float, fixed within {flat:.1f}° (10-bit |D|² bound; flat at π)"
            hf = within(zero_float, paper_deg, 0.01)
            hx = zero_fixed is None or zero_fixed >= paper_deg - flat
        else:
            hf, hx = within(zero_float, paper_deg, 0.01), within(zero_fixed, paper_deg, 1.0)
            hx = bool(hx)
        note = ("fixed: comparator never fires on 0…180°" if zero_fixed is None else
                "fixed: comparator x ≥ 2^k") + (
            f"; output code 0 from {math.degrees(code_zero):.2f}° (f{k} under ½ LSB of t)"
            if code_zero is not None and (zero_fixed is None or code_zero < math.radians(zero_fixed))
            else "") + (f"; smallest output {spec.min():.4f}" if code_zero is None else "")
        rows.append(row(f"n = {n_low}: f{k} reaches 0 at α =", paper_deg, zero_float, zero_fixed,
                         fmt="{:.3f}°", paper_text="never" if paper_deg is None else
                         f"{paper_deg:g}° (π/{180 / paper_deg:g})" if paper_deg < 180 else "180° (π)",
                         criterion=criterion, holds_float=hf, holds_fixed=hx, note=note))

    plot = {"alpha": alpha[::500], "cosn": cosn[::500], "float": {k: flt[k][::500] for k in K},
            "alpha_fixed": alpha[::500], "fixed": {k: fixed[k][::500] for k in K}, "n": n}
    section = {"id": "figure3", "title": "Figure 3: shape functions f0, f1, f2 vs cos^n α, n = 100",
               "setup": "α on 0…0.4 rad in 1e-5 rad steps; fixed point: R, L unit at angle α in a "
                        "seeded generic orientation → S1.10 codes → golden difference (n = 100) → "
                        "golden shape (k). Errors are absolute, i.e. relative to the peak 1.0.",
               "rows": rows, "stats": stats}
    return section, plot


def bisect(error, target, lo=0.0, hi=0.5, steps=200):
    """ε in lo..hi where the increasing ``error(ε)`` reaches ``target``."""
    for _ in range(steps):
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if error(mid) < target else (lo, mid)
    return (lo + hi) / 2


def sensitivity():
    n, target = 1000, 0.05
    phong = lambda e: 1.0 - (1.0 - e) ** n  # noqa: E731
    shape = {k: (lambda e, k=k: 1.0 - float(f_k(n / 2.0 * e * e, k))) for k in K}
    eps_phong = bisect(phong, target)
    eps_shape = {k: bisect(shape[k], target) for k in K}

    # fixed point: R = (1-ε)L in a seeded generic direction, golden difference + shape
    light = rotation() @ np.array([0.0, 0.0, 1.0])
    grid = np.linspace(0.0, 0.03, 15001)  # 2e-6 steps
    x2 = fixed_x2((1.0 - grid)[:, None] * light, light, n)
    fixed_err = {k: 1.0 - fixed_shape(x2, k) for k in K}
    eps_fixed = {k: first(grid, fixed_err[k] >= target) for k in K}

    lsb = get_block("difference").config.fmt("vec").lsb
    rows = [
        row("(R·L)^n: ε for a 5 % peak error, n = 1000", 5e-5, eps_phong, None, fmt="{:.3g}",
             paper_text="0.00005", criterion="within 10 %",
             holds_float=abs(eps_phong / 5e-5 - 1) <= 0.1,
             note=f"approximation nε = 5 % gives {target / n:.3g}; fixed point: no cos^n datapath, "
                  f"and 5e-5 is {5e-5 / lsb:.3f} LSB of S1.10"),
        row("(R·L)^n: bits of normalization accuracy, log2(1/ε)", 14.0, math.log2(1 / eps_phong), None,
             fmt="{:.2f}", paper_text="more than 14", criterion="> 14",
             holds_float=math.log2(1 / eps_phong) > 14),
    ]
    for k in K:
        rows.append(row(f"f{k}: ε for a 5 % peak error, n = 1000", 0.01, eps_shape[k], eps_fixed[k],
                         fmt="{:.4g}", paper_text="0.01", criterion="within 10 %",
                         holds_float=abs(eps_shape[k] / 0.01 - 1) <= 0.1,
                         holds_fixed=None if eps_fixed[k] is None else abs(eps_fixed[k] / 0.01 - 1) <= 0.1,
                         note=f"approximation (n/2)ε² = 5 % gives {math.sqrt(2 * target / n):.4g}"
                              + ("; fixed: first ε on a 2e-6 grid, R = (1−ε)L quantized" if k == 0 else "")))
    rows.append(row("f_k: bits of normalization accuracy, log2(1/ε) (k = 2)", 7.0,
                     math.log2(1 / eps_shape[2]), None if eps_fixed[2] is None else math.log2(1 / eps_fixed[2]),
                     fmt="{:.2f}", paper_text="fewer than 7", criterion="< 7",
                     holds_float=math.log2(1 / eps_shape[2]) < 7,
                     holds_fixed=None if eps_fixed[2] is None else math.log2(1 / eps_fixed[2]) < 7))
    rows.append(row("peak error with R one S1.10 LSB short (ε = 2^-10): (R·L)^n", None, phong(lsb), None,
                     fmt="{:.2%}", paper_text="—", note=f"f2 at the same ε: {shape[2](lsb):.4%}"))

    eps = np.logspace(-6, -1, 400)
    plot = {"eps": eps, "phong": 1.0 - (1.0 - eps) ** n,
            "shape": {k: 1.0 - f_k(n / 2.0 * eps ** 2, k) for k in K},
            "grid": grid, "fixed": fixed_err[2], "eps_phong": eps_phong, "eps_shape": eps_shape}
    section = {"id": "sensitivity", "title": "Length error sensitivity, n = 1000, α = 0",
               "setup": "|R| = 1 − ε, |L| = 1, R ∥ L: (R·L)^n = (1−ε)^n and f_k(x) with x = (n/2)ε²; "
                        "ε by bisection (float), by a 2e-6 grid through the golden difference + shape "
                        "blocks (fixed point).",
               "rows": rows}
    return section, plot
