"""``phongfx figure9``: Lyon's Figure 9, float rows and fixed-point rows side by side.

The scene is exactly that of ``specular.m`` (Lyon 1993, appendix): spheres of radius
64 pixels, n = 1, 4, 16, 64, 256, specular factor ``400·n^0.25 / max``, diffuse 35,
background 255, lights along [1, 1, -1] and [1, -1, 1], viewer at (0, 0, 1), exact
per-pixel normals.  One row per method of :data:`phongfx.golden.reference.METHODS`
in float; beside it, for each method that has a datapath here, the fixed-point row,
computed by the golden model and checked pixel by pixel through the RTL.
"""

import json
import os

import numpy as np

from phongfx.config import HalfwayConfig, ShapeConfig, fig7_config, fig8_config, halfway_config
from phongfx.core.files import atomic_write
from phongfx.core.methods import get_method
from phongfx.core.registry import get_block
from phongfx.golden.reference import METHODS, specular_all
from phongfx.render.lyon import amounts, composite, scene_inputs, shade
from phongfx.scene.lyon import Scene, pixels

__all__ = ["FIXED_ROWS", "float_rows", "run", "markdown"]

# method row -> (label, datapath config) of its fixed-point twin; Figure 8 stands
# beside row 3 (k = 1), the shape it computes with m = √n (n = m² here exactly)
FIXED_ROWS = {
    "lyon-k0": [("Figure 7, k = 0", fig7_config(shape=ShapeConfig(k=0)))],
    "lyon-k1": [("Figure 7, k = 1", fig7_config(shape=ShapeConfig(k=1))),
                ("Figure 8, m = √n, k = 1", fig8_config())],
    "lyon-k2": [("Figure 7, k = 2", fig7_config())],
    "halfway-proj-k2": [("halfway D3, k = 2", halfway_config(halfway=HalfwayConfig(variant="d3")))],
    "halfway-g2proj-k2": [("halfway g2 proj, k = 2", halfway_config())],
    "halfway-g2proj-k1": [("halfway g2 proj, k = 1", halfway_config(shape=ShapeConfig(k=1)))],
    "halfway-g2-k2": [("halfway g2, k = 2", halfway_config(halfway=HalfwayConfig(variant="g2")))],
}


def float_rows(scene, px):
    """Lyon's float specular amounts and diffuse, per method, per light."""
    lights, viewer = scene.unit_lights(), scene.unit_viewer()
    per_light = [specular_all(px.normal, light, viewer, px.n.astype(np.float64)) for light in lights]
    diff = [np.maximum(px.normal @ light, 0) for light in lights]
    return {method: [row[method] for row in per_light] for method in METHODS}, diff


def _error(spec, reference):
    """Per-pixel specular error, max over lights, in 8-bit levels."""
    return np.max([np.abs(s - r) for s, r in zip(spec, reference)], axis=0) * 255


def run(out_dir="build/figure9", backend="verilator-fast", radius=64, progress=None):
    """Render, check through the RTL, write PNGs and tables; returns the table dict."""
    scene = Scene(radius=radius)
    px = pixels(scene)
    floats, float_diff = float_rows(scene, px)
    rows, checked, mismatches, specs = [], 0, 0, {}
    for method in METHODS:
        float_image = composite(scene, px, floats[method], float_diff)
        row = {"method": method, "float": float_image, "fixed": []}
        for label, config in FIXED_ROWS.get(method, []):
            name = get_method(config.specular).block
            block = get_block(name, config=config)
            golden, stats = shade(block, scene_inputs(config, scene, px), backend, progress=progress)
            checked += stats["pixels"]
            mismatches += stats["mismatches"]
            spec, diff = amounts(config, golden)
            specs[label] = spec
            own, phong = _error(spec, floats[method]), _error(spec, floats["phong"])
            row["fixed"].append({
                "label": label, "datapath": name, "image": composite(scene, px, spec, diff),
                "vs_own_float": {"max": round(float(own.max()), 3), "mean": round(float(own.mean()), 4)},
                "vs_phong": {"max": round(float(phong.max()), 3), "mean": round(float(phong.mean()), 4)},
                "rtl_mismatches": stats["mismatches"], "rtl_pixels": stats["pixels"]})
        rows.append(row)
    # Figure 8 against Figure 7 at equal shininess (n = m², exact for Lyon's n) and k = 1
    fig8_vs_fig7 = _error(specs["Figure 8, m = √n, k = 1"], specs["Figure 7, k = 1"])
    table = {"pixels_per_row": len(px), "rtl_pixels_checked": checked, "rtl_mismatches": mismatches,
             "backend": backend,
             "fig8_vs_fig7_k1": {"max": round(float(fig8_vs_fig7.max()), 3),
                                 "mean": round(float(fig8_vs_fig7.mean()), 4)},
             "rows": [{"row": index + 1, "method": row["method"],
                       "fixed": [{k: v for k, v in f.items() if k != "image"} for f in row["fixed"]]}
                      for index, row in enumerate(rows)]}
    _write(out_dir, scene, rows, table)
    return table


def markdown(table):
    lines = [f"Lyon's Figure 9 in fixed point: {table['pixels_per_row']} pixels per row, "
             f"{table['rtl_pixels_checked']} checked through the RTL ({table['backend']}), "
             f"{table['rtl_mismatches']} mismatches.", "",
             "Specular error in 8-bit levels (max / mean over both lights).", "",
             f"Figure 8 against Figure 7 (k = 1, n = m²): max {table['fig8_vs_fig7_k1']['max']:.2f}, "
             f"mean {table['fig8_vs_fig7_k1']['mean']:.3f} levels.", "",
             "| row | float method | fixed-point datapath | vs its own float | vs float phong |",
             "|---|---|---|---|---|"]
    for row in table["rows"]:
        for fixed in row["fixed"] or [None]:
            if fixed is None:
                lines.append(f"| {row['row']} | {row['method']} | (float only) | | |")
                continue
            own, phong = fixed["vs_own_float"], fixed["vs_phong"]
            lines.append(f"| {row['row']} | {row['method']} | {fixed['label']} | "
                         f"{own['max']:.2f} / {own['mean']:.3f} | {phong['max']:.2f} / {phong['mean']:.3f} |")
    return "\n".join(lines) + "\n"


def _pyplot():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def _save(fig, path):
    fig.tight_layout()
    atomic_write(path, lambda p: fig.savefig(p, dpi=90, format="png"))
    _pyplot().close(fig)


def _pictures(out_dir, rows):
    """``figure9.png``: every row, float then fixed point, grey as Lyon printed it."""
    plt = _pyplot()
    columns = 1 + max(len(row["fixed"]) for row in rows)
    fig, axes = plt.subplots(len(rows), columns, figsize=(5.2 * columns, 1.9 * len(rows)))
    for r, row in enumerate(rows):
        panels = [("float " + row["method"], row["float"])] + [(f["label"], f["image"]) for f in row["fixed"]]
        for c in range(columns):
            ax = axes[r, c]
            ax.axis("off")
            if c < len(panels):
                ax.imshow(panels[c][1], cmap="gray", vmin=0, vmax=255, interpolation="nearest")
                ax.set_title(f"{r + 1}. {panels[c][0]}", fontsize=8)
    fig.suptitle("Lyon's Figure 9: float (left), fixed point through the datapaths")
    _save(fig, os.path.join(out_dir, "figure9.png"))


def _differences(out_dir, rows):
    """``figure9_diff.png``: ``|fixed − float|`` of the picture for the rows that have a
    datapath, in 8-bit levels on one colour scale up to the largest difference (a fixed
    ×32 gain left most of it black), square-root, so that the common one-level differences
    show beside a rare large one; with its colour bar.  Returns that largest difference."""
    from matplotlib.colors import PowerNorm
    plt = _pyplot()
    shown = [(r, row, fixed) for r, row in enumerate(rows) for fixed in row["fixed"]]
    diffs = [np.abs(fixed["image"] - row["float"]) for _, row, fixed in shown]
    top = max(1.0, max(float(d.max()) for d in diffs))
    columns = max(len(row["fixed"]) for row in rows)
    fixed_rows = [r for r, row in enumerate(rows) if row["fixed"]]
    fig, axes = plt.subplots(len(fixed_rows), columns, figsize=(5.6 * columns, 1.9 * len(fixed_rows)),
                             squeeze=False)
    for ax in axes.flat:
        ax.axis("off")
    image = None
    for (r, row, fixed), diff in zip(shown, diffs):
        ax = axes[fixed_rows.index(r), row["fixed"].index(fixed)]
        image = ax.imshow(diff, cmap="inferno", norm=PowerNorm(0.5, vmin=0, vmax=top), interpolation="nearest")
        ax.set_title(f"{r + 1}. {fixed['label']} vs float {row['method']}: max {diff.max():.1f} levels",
                     fontsize=8)
    fig.suptitle(f"|fixed − float| of the picture in 8-bit levels (black: equal; square-root colour "
                 f"scale 0–{top:.1f}, the largest difference; rows without a datapath left out)", fontsize=10)
    fig.colorbar(image, ax=axes, fraction=0.03, label="8-bit levels")
    atomic_write(os.path.join(out_dir, "figure9_diff.png"), lambda p: fig.savefig(p, dpi=90, format="png"))
    plt.close(fig)
    return top


def _write(out_dir, scene, rows, table):
    _pictures(out_dir, rows)
    table["diff_scale_levels"] = round(_differences(out_dir, rows), 3)
    atomic_write(os.path.join(out_dir, "figure9.json"),
                 lambda p: open(p, "w").write(json.dumps(table, indent=2) + "\n"))
    atomic_write(os.path.join(out_dir, "figure9.md"), lambda p: open(p, "w").write(markdown(table)))
