"""Schlick (1994) Figure 1, measured: ``S_n(t) = t/(n - n·t + t)`` against Phong's ``t^n``.

For ``n`` = 1, 2, 6, 16, 64 (the figure's curves), over every ``t`` code of the unit's
input format in ``0..1``: the largest ``|S_n(t) - t^n|`` with ``S_n`` in float and as the
fixed-point unit computes it (:func:`phongfx.golden.schlick.schlick` through the
registry), and the unit's own error against float ``S_n`` in LSB of its output.  The
paper says only that the curves match best near ``t = 1`` and that the new highlights
are broader; the table puts numbers on "broader".
"""

import json
import os

import numpy as np

from phongfx.core.registry import get_block

__all__ = ["FIGURE1_N", "schlick_table", "run_table", "markdown", "to_json"]

#: The exponents of Schlick's Figure 1.
FIGURE1_N = (1, 2, 6, 16, 64)


def _float_schlick(t, n):
    return t / (n - n * t + t)


def schlick_table(png=None, config=None, ns=FIGURE1_N):
    """Rows ``{n, t_at_max, max_float, max_fixed, max_lsb}`` comparing ``S_n`` with ``t^n``.

    Parameters
    ----------
    png : path, optional
        Where to write Figure 1 (``t^n`` left, ``S_n`` right, their difference below),
        atomically (:func:`phongfx.render.lyon.atomic_write`).
    config : SchlickConfig, optional
        The unit's formats (default :class:`~phongfx.config.SchlickConfig`).
    ns : sequence of int

    Returns
    -------
    list of dict
        ``max_float`` = max ``|S_n - t^n|`` in float at ``t_at_max``; ``max_fixed`` the same
        with the unit's ``S_n``; ``max_lsb`` = max ``|unit - float S_n|`` in output LSB.
    """
    block = get_block("schlick", config=config)
    t_fmt, out = block.config.fmt("t"), block.config.fmt("out")
    raw = np.arange(t_fmt.one + 1, dtype=np.int64)
    t = raw * t_fmt.lsb
    rows, curves = [], []
    for n in ns:
        exact, phong = _float_schlick(t, n), t ** n
        fixed = block.golden({"t": raw, "n": np.full(len(raw), n)})["spec"] * out.lsb
        diff = np.abs(exact - phong)
        worst = int(np.argmax(diff))
        rows.append({"n": n, "t_at_max": float(t[worst]), "max_float": float(diff[worst]),
                     "max_fixed": float(np.max(np.abs(fixed - phong))),
                     "max_lsb": float(np.max(np.abs(fixed - exact)) / out.lsb)})
        curves.append((n, phong, exact))
    if png is not None:
        _plot(png, t, curves)
    return rows


def run_table(name, out_dir="build/schlick"):
    """``phongfx tables schlick``: the Figure 1 rows; the plot goes to ``out_dir/figure1.png``."""
    if name != "schlick":
        raise ValueError(f"unknown table {name!r}; valid tables: schlick")
    return {"source": "C. Schlick (1994), A Fast Alternative to Phong's Specular Model",
            "rows": schlick_table(png=os.path.join(out_dir, "figure1.png"))}


def markdown(result):
    lines = [f"# Figure 1, measured ({result['source']})", "",
             "| n | max \\|S_n − tⁿ\\| (float) | at t | with the fixed-point unit | unit vs float S_n (LSB) |",
             "|---|---|---|---|---|"]
    for r in result["rows"]:
        lines.append(f"| {r['n']} | {r['max_float']:.5f} | {r['t_at_max']:.3f} | {r['max_fixed']:.5f} | "
                     f"{r['max_lsb']:.5f} |")
    return "\n".join(lines) + "\n"


def to_json(result):
    return json.dumps(result, indent=2, ensure_ascii=False)


def _plot(path, t, curves):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from phongfx.core.files import atomic_write

    fig, axes = plt.subplots(1, 3, figsize=(13, 4))
    for n, phong, schlick in curves:
        axes[0].plot(t, phong, label=f"n = {n}")
        axes[1].plot(t, schlick, label=f"n = {n}")
        axes[2].plot(t, schlick - phong, label=f"n = {n}")
    for ax, title in zip(axes, ("Phong  t^n", "Schlick  t/(n - nt + t)", "Schlick - Phong")):
        ax.set_title(title)
        ax.set_xlabel("t = cos α")
        ax.grid(alpha=0.3)
    axes[0].legend()
    fig.tight_layout()
    atomic_write(str(path), lambda p: fig.savefig(p, dpi=100, format="png"))
    plt.close(fig)
