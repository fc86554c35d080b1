"""``make sim``: shade Lyon's scene through the Figure 7 datapath, golden and RTL.

Every covered pixel goes through the golden model and through the RTL on a back
end, cycle by cycle; every output must be bit-identical.  Then the fixed-point
result is compared with float references (:mod:`phongfx.golden.reference`) with
exact normals, and pictures and a JSON summary are written.

Errors are in 8-bit levels of the specular amount (``|fixed - float| × 255``, per
light); the picture is Lyon's composite (``35·ΣN·L + s(n)·Σspec``, clipped, white
background) as in the appendix code.
"""

import json
import os
import time

import numpy as np

from phongfx.config import fig7_config
from phongfx.core.files import atomic_write
from phongfx.core.registry import get_block
from phongfx.golden.reference import specular
from phongfx.scene.lyon import Scene, pixels
from phongfx.sim.harness import BACKENDS, check
from phongfx.sim.stimulus.datapath import encode

__all__ = ["scene_inputs", "shade", "amounts", "composite", "references", "run", "MODES"]

MODES = ("exact", "spans")
DIFFUSE_GAIN = 35.0  # appendix: diff = 35
SPECULAR_PEAK = 400.0  # appendix: specfs = 400/max(ns^.25)·ns^.25


def scene_inputs(config, scene, px):
    """Raw input codes of ``config``'s datapath for the pixels ``px`` of ``scene``."""
    lights, viewer = list(scene.unit_lights()), scene.unit_viewer()
    return encode(config, px.n0, px.n1, px.a, px.n, viewer, viewer, lights, lights)


def shade(block, raw, backend, chunk=16384, progress=None, bounds=None):
    """Golden outputs of ``raw``, checked against the RTL on ``backend`` chunk by chunk.

    Chunks are ``chunk`` pixels, or run between the given ``bounds`` (``[0, ..., count]``;
    a stateful unit must be cut where it reloads, see :func:`phongfx.render.frames.chunk_starts`).
    Returns (golden outputs, stats dict).  ``progress`` is called with the number of
    pixels just checked.
    """
    golden = block.golden(raw)
    stats = {"pixels": 0, "mismatches": 0, "cycles": 0, "seconds": 0.0, "first_mismatch": None}
    count = len(next(iter(golden.values())))
    if bounds is None:
        bounds = [*range(0, count, chunk), count]
    for lo, hi in zip(bounds, bounds[1:]):
        result = check(block, inputs={name: value[lo:hi] for name, value in raw.items()},
                       expected={name: value[lo:hi] for name, value in golden.items()},
                       backend=backend, bubbles=0.0)
        stats["pixels"] += result.vectors
        stats["cycles"] += result.cycles
        stats["seconds"] += result.seconds
        stats["mismatches"] += result.mismatch_count
        if result.mismatch_count and stats["first_mismatch"] is None:
            stats["first_mismatch"] = result.describe(limit=3)
        if progress:
            progress(result.vectors)
    return golden, stats


def references(config):
    """The float references of ``config``'s datapath: true Phong, and Lyon's float form of
    the datapath as configured, ``lyon-k<k>`` at its shape's own ``k`` (against another
    k the error would be the difference of two shape functions, not the fixed point's)."""
    return ("phong", f"lyon-k{config.shape.k}")


def _errors(config, scene, px, golden):
    """Per-pixel error (max over lights, 8-bit levels) against each float reference; the
    keys are :func:`references` and ``<own>-interpolated`` and ``diffuse``."""
    lights, viewer = scene.unit_lights()[:config.lights], scene.unit_viewer()
    spec, diff = amounts(config, golden)

    def specular_error(method, normals):
        worst = np.zeros(len(px))
        for index, light in enumerate(lights):
            ref = specular(method, normals, light, viewer, px.n.astype(np.float64))
            worst = np.maximum(worst, np.abs(spec[index] - ref) * 255)
        return worst

    phong, own = references(config)
    out = {method: specular_error(method, px.normal) for method in (phong, own)}
    # the float algorithm on the same interpolated (exactly renormalized) normals: what is
    # left is the fixed-point datapath's own error (g2, 10-bit vectors), not span geometry
    lerp = (1 - px.a[:, None]) * px.n0 + px.a[:, None] * px.n1
    out[f"{own}-interpolated"] = specular_error(
        own, lerp / np.maximum(np.linalg.norm(lerp, axis=-1, keepdims=True), 1e-300))
    diff_ref = np.maximum(px.normal @ lights.T, 0)
    out["diffuse"] = np.max(np.abs(np.stack(diff, axis=-1) - diff_ref), axis=-1) * 255
    return out


def amounts(config, golden):
    """Golden outputs as floats: (specular per light, diffuse per light)."""
    spec = [golden[f"spec{i}"] * config.outputs[f"spec{i}"][0].lsb for i in range(config.lights)]
    diff = [golden[f"diff{i}"] * config.outputs[f"diff{i}"][0].lsb for i in range(config.lights)]
    return spec, diff


def composite(scene, px, spec, diff):
    """Lyon's appendix picture: white background, dark spheres, clipped highlights.

    ``spec`` and ``diff`` are float amounts per light (``diff`` already clamped at 0).
    """
    ns = np.array(scene.shininess, dtype=np.float64)
    gain = SPECULAR_PEAK / np.max(ns ** 0.25) * px.n ** 0.25
    total = DIFFUSE_GAIN * np.sum(diff, axis=0) + gain * np.sum(spec, axis=0)
    image = np.full((scene.height, scene.width), 255.0)
    image[px.row, px.col] = np.clip(total, 0, 255)
    return image


def _plots(out_dir, scene, results, own):
    k = own.rpartition("-k")[2]
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(len(MODES), 1, figsize=(10, 3.2 * len(MODES)))
    for ax, mode in zip(axes, MODES):
        ax.imshow(results[mode]["image"], cmap="gray", vmin=0, vmax=255, interpolation="nearest")
        ax.set_title(f"Figure 7 datapath (k = {k}), {mode} normals — n = {', '.join(map(str, scene.shininess))}")
        ax.axis("off")
    fig.tight_layout()
    atomic_write(os.path.join(out_dir, "fig7.png"), lambda p: fig.savefig(p, dpi=110, format="png"))
    plt.close(fig)

    shown_refs = {"phong": "float phong", own: f"float {own}",
                  f"{own}-interpolated": f"float {own} on the same interpolated N"}
    fig, axes = plt.subplots(len(MODES), len(shown_refs), figsize=(20, 3.4 * len(MODES)))
    for r, mode in enumerate(MODES):
        px, errors = results[mode]["pixels"], results[mode]["errors"]
        for c, (method, label) in enumerate(shown_refs.items()):
            ax = axes[r, c]
            image = np.full((scene.height, scene.width), np.nan)
            image[px.row, px.col] = errors[method]
            shown = ax.imshow(image, cmap="inferno", vmin=0, vmax=max(1.0, np.nanmax(image)),
                              interpolation="nearest")
            ax.set_title(f"{mode} normals vs {label}:\nmax {np.nanmax(image):.1f}, "
                         f"mean {np.nanmean(image):.2f} levels", fontsize=9)
            ax.axis("off")
            fig.colorbar(shown, ax=ax, fraction=0.025, label="8-bit levels")
    fig.tight_layout()
    atomic_write(os.path.join(out_dir, "fig7_error.png"), lambda p: fig.savefig(p, dpi=110, format="png"))
    plt.close(fig)


def run(config=None, *, radius=64, span=8, backend="verilator-fast", out_dir="build/sim",
        chunk=16384, sample=0, quiet=False):
    """Shade both modes, check every pixel on ``backend``, write pictures and summary.

    ``sample`` pixels are also run on each other back end, only to measure its speed (0:
    none, as ``make sim`` runs it: the other back ends' builds cost twice the rest of the
    render, and ``make bench``'s ``bench.rtl`` times every back end).
    Returns the summary dict; ``summary["mismatches"]`` must be 0.
    """
    from tqdm import tqdm

    if backend not in BACKENDS:
        raise ValueError(f"backend must be one of {', '.join(BACKENDS)}, not {backend!r}")
    if isinstance(sample, bool) or not isinstance(sample, int) or sample < 0:
        raise ValueError(f"speed sample must be a non-negative integer, not {sample!r}")
    config = config or fig7_config()
    block = get_block("fig7", config=config)
    scenes = {"exact": Scene(radius=radius, span=0), "spans": Scene(radius=radius, span=span)}
    prepared = {mode: (scene, pixels(scene)) for mode, scene in scenes.items()}
    total = sum(len(px) for _, px in prepared.values())

    results, speeds = {}, {}
    start = time.perf_counter()
    with tqdm(total=total, unit="px", desc=f"RTL ({backend})", disable=quiet) as bar:
        for mode, (scene, px) in prepared.items():
            raw = scene_inputs(config, scene, px)
            golden, stats = shade(block, raw, backend, chunk=chunk, progress=bar.update)
            results[mode] = {"pixels": px, "raw": raw, "stats": stats, "errors": _errors(config, scene, px, golden),
                             "image": composite(scene, px, *amounts(config, golden))}
    for other in BACKENDS if sample else ():
        if other == backend:
            continue
        part = {name: value[:sample] for name, value in results["spans"]["raw"].items()}
        _, speeds[other] = shade(block, part, other, chunk=sample)

    summary = {
        "datapath": "fig7", "config": _plain(config), "latency": block.latency,
        "float_form": references(config)[1],
        "backend": backend, "radius": radius, "span": span, "shininess": list(Scene().shininess),
        "pixels_checked": sum(r["stats"]["pixels"] for r in results.values()),
        "mismatches": sum(r["stats"]["mismatches"] for r in results.values()),
        "cycles": sum(r["stats"]["cycles"] for r in results.values()),
        "cycles_per_second": {},
        "wall_seconds": round(time.perf_counter() - start, 2),
        "error_8bit": {},
    }
    rtl_seconds = sum(r["stats"]["seconds"] for r in results.values())
    summary["cycles_per_second"][backend] = {
        "cycles": summary["cycles"], "seconds": round(rtl_seconds, 3),
        "cycles_per_second": round(summary["cycles"] / rtl_seconds, 1)}
    for other, stats in speeds.items():
        summary["cycles_per_second"][other] = {
            "cycles": stats["cycles"], "seconds": round(stats["seconds"], 3),
            "cycles_per_second": round(stats["cycles"] / stats["seconds"], 1),
            "note": f"speed sample: first {stats['pixels']} span-mode pixels, also bit-identical"
                    if not stats["mismatches"] else f"{stats['mismatches']} MISMATCHES"}
        summary["mismatches"] += stats["mismatches"]
    for mode, result in results.items():
        px, errors = result["pixels"], result["errors"]
        entry = {}
        for method, err in errors.items():
            per_n = {str(n): {"max": round(float(err[px.n == n].max()), 3),
                              "mean": round(float(err[px.n == n].mean()), 4)}
                     for n in scenes[mode].shininess}
            entry["specular_vs_" + method if method != "diffuse" else "diffuse_vs_float"] = {
                "max": round(float(err.max()), 3), "mean": round(float(err.mean()), 4), "by_n": per_n}
        entry["pixels"] = len(px)
        if result["stats"]["first_mismatch"]:
            entry["first_mismatch"] = result["stats"]["first_mismatch"]
        summary["error_8bit"][mode] = entry

    _plots(out_dir, scenes["spans"], results, references(config)[1])
    atomic_write(os.path.join(out_dir, "summary.json"),
            lambda p: open(p, "w").write(json.dumps(summary, indent=2) + "\n"))
    return summary


def _plain(config):
    from dataclasses import asdict
    return asdict(config)
