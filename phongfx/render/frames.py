"""Full rendered frames through the RTL of the scanline units: the golden model and the hardware agree on
whole pictures, not only on stimulus.

One frame of a rotating mesh (:mod:`phongfx.scene.mesh`: torus or UV sphere, orthographic,
back faces culled) is rasterized into spans; :mod:`phongfx.scene.span_inputs` lays out the
per-pixel stream of a unit (Hast et al.'s corrected Euler and Gouraud units,
Szirmay-Kalos et al.'s spherical interpolation unit, Schlick's rational specular
unit); the golden model runs once over the whole stream, and the RTL is checked
against it cycle by cycle, back to back (no bubbles), on a back end.

Every span pixel is checked, hidden ones too: without early depth test the unit
shades each pixel a span covers.  Long streams are checked in chunks that begin at a
span's first pixel: ``init`` reloads all the state of a stateful unit there, so a
chunk run from reset gives the same outputs as the whole stream and the one golden
run can be sliced.  (:func:`phongfx.render.lyon.shade` cuts at fixed pixel counts, which
would split spans, so it is not reused.)
"""

import json
import os
import time

import numpy as np

from phongfx.core.files import atomic_write
from phongfx.core.registry import get_block
from phongfx.scene.span_inputs import check_unit, decode, first_pixels, inputs, units as stream_units
from phongfx.sim.harness import BACKENDS

from .figure import frame_figure
from .lyon import shade
from .mesh import intensity

__all__ = ["MESHES", "LIGHT", "SHOWN", "frame_spans", "chunk_starts", "unit_picture", "rtl_frame",
           "run_all", "markdown"]

MESHES = ("torus", "sphere")
#: Default light: up, left and towards the viewer, so the highlight sits on the frame.
LIGHT = (-0.4, 0.5, 0.77)


def frame_spans(mesh="torus", polygons=800, width=256, height=256, frame=0):
    """Spans of frame ``frame`` of the rotating ``mesh`` (``polygons`` quads) at ``width × height``."""
    from phongfx.scene import mesh as meshes
    if mesh not in MESHES:
        raise ValueError(f"mesh must be one of {', '.join(MESHES)}, not {mesh!r}")
    for name, value in (("width", width), ("height", height)):
        if not isinstance(value, int) or value < 1:
            raise ValueError(f"{name} must be a positive integer, not {value!r}")
    if mesh == "torus":
        return meshes.rasterize(meshes.torus(polygons), meshes.rotation(frame), width, height)
    # the sphere as the torus: 2k² polygons, k stacks by 2k slices
    side = int(round(np.sqrt(polygons / 2))) if isinstance(polygons, int) and polygons > 0 else 0
    if side < 2 or 2 * side * side != polygons:
        raise ValueError(f"polygons must be 2·k² for an integer k >= 2 (8, 18, ..., 800), not {polygons!r}")
    return meshes.rasterize(meshes.uv_sphere(side, 2 * side), meshes.rotation(frame), width, height)


def chunk_starts(first, count, chunk):
    """Chunk boundaries ``[0, ..., count]`` at span starts ``first``, each chunk the
    longest run of whole spans up to ``chunk`` pixels (or one span, if longer)."""
    if not isinstance(chunk, int) or chunk < 1:
        raise ValueError(f"chunk must be a positive integer, not {chunk!r}")
    bounds = [0]
    while bounds[-1] < count:
        end = bounds[-1] + chunk
        if end >= count:
            bounds.append(count)
            break
        i = int(np.searchsorted(first, end, side="right")) - 1  # the last span start <= end
        cut = int(first[i])
        if cut <= bounds[-1]:  # one span longer than chunk: take it whole
            cut = int(first[i + 1]) if i + 1 < len(first) else count
        bounds.append(cut)
    return bounds


#: What a unit's picture shows, by the parts its config shades
#: (:attr:`~phongfx.config.base.BlockConfig.SHADES`): a unit interpolating one cosine (Hast's
#: Euler and Gouraud units, whose two parts are one port) shows ``N·L``, Schlick's the
#: specular term alone, the others both, blended as :func:`phongfx.render.mesh.intensity`.
SHOWN = {"one": "N·L", "spec": "specular", "both": "ambient + diffuse + specular"}


def _shown(config):
    """The key of :data:`SHOWN` for a unit of ``config``."""
    shades = config.SHADES
    if set(shades) == {"diff", "spec"}:
        return "one" if shades["diff"] == shades["spec"] else "both"
    return "spec"


def unit_picture(spans, outputs, config):
    """The (height, width) grey [0, 1] picture of a unit's raw ``outputs`` on ``spans``
    (:data:`SHOWN` says what it shows), black where no surface is visible."""
    from phongfx.scene import mesh as meshes
    if _shown(config) == "both":
        diff = decode(outputs, config, "diff")
        value = intensity(diff[:, 0] if diff.ndim == 2 else diff, decode(outputs, config, "spec"))
    else:
        value = decode(outputs, config)
    return meshes.image(spans, np.clip(value, 0.0, 1.0))


def rtl_frame(unit, *, mesh="torus", polygons=800, width=256, height=256, frame=0, light=LIGHT, n=32,
              backend="verilator-fast", chunk=16384, progress=None, png=None):
    """Check one full frame of ``unit`` (one of ``euler``, ``gouraud``, ``spherical``,
    ``schlick``) on the RTL against the golden model, pixel by pixel.

    ``n`` is the shininess of the spherical and Schlick units (the Euler and Gouraud
    units shade diffuse ``N·L``).  ``progress`` is called with the number of pixels
    just checked.  Returns ``dict(unit, pixels, visible, spans, cycles, mismatches,
    cycles_per_second, seconds, wall_seconds, ...)``: ``seconds`` is the RTL simulation,
    ``wall_seconds`` also the rasterizer, setup, golden model and any Verilator build;
    ``mismatches`` must be 0.  With ``png`` (a path) the golden frame, which the RTL
    matched, is written there titled (:func:`unit_picture`), and the row names it.
    """
    check_unit(unit)
    if backend not in BACKENDS:
        raise ValueError(f"backend must be one of {', '.join(BACKENDS)}, not {backend!r}")
    start = time.perf_counter()
    spans = frame_spans(mesh, polygons, width, height, frame)
    raw = inputs(unit, spans, light, n=n)
    block = get_block(unit)
    first, count = first_pixels(spans)
    bounds = chunk_starts(first, count, chunk)
    golden, stats = shade(block, raw, backend, progress=progress, bounds=bounds)
    if png is not None:
        frame_figure(png, unit_picture(spans, golden, block.config),
                     f"{unit} unit, {SHOWN[_shown(block.config)]}: {mesh} {polygons} polygons, frame {frame}, "
                     f"{width}×{height}; RTL ({backend}) {stats['mismatches']} mismatches")
    return {"unit": unit, "backend": backend, "mesh": mesh, "polygons": polygons, "width": width,
            "height": height, "frame": frame, "pixels": count, "visible": int(np.sum(spans.visible)),
            "spans": len(first), "chunks": len(bounds) - 1, "cycles": stats["cycles"],
            "mismatches": stats["mismatches"], "seconds": round(stats["seconds"], 3),
            "cycles_per_second": round(stats["cycles"] / stats["seconds"], 1) if stats["seconds"] else None,
            "wall_seconds": round(time.perf_counter() - start, 2), "first_mismatch": stats["first_mismatch"],
            **({"png": os.fspath(png)} if png is not None else {})}


def run_all(out_dir="build/frames", units=None, *, quiet=False, **options):
    """:func:`rtl_frame` for each of ``units`` (None: every unit with a stream,
    :func:`~phongfx.scene.span_inputs.units`) on the same frame; writes each unit's
    picture to ``out_dir/<unit>.png`` and ``out_dir/frames.json``, atomically, and returns ``{"frames": [...], "mismatches",
    "wall_seconds"}``.  ``options`` go to :func:`rtl_frame`."""
    from tqdm import tqdm

    units = stream_units() if units is None else units
    for unit in units:
        check_unit(unit)
    start, rows = time.perf_counter(), []
    for unit in units:
        with tqdm(unit="px", desc=f"{unit} RTL ({options.get('backend', 'verilator')})",
                  disable=quiet) as bar:
            rows.append(rtl_frame(unit, progress=bar.update, png=os.path.join(out_dir, f"{unit}.png"),
                                  **options))
    result = {"frames": rows, "mismatches": sum(row["mismatches"] for row in rows),
              "wall_seconds": round(time.perf_counter() - start, 2)}
    text = json.dumps(result, indent=2) + "\n"
    atomic_write(os.path.join(out_dir, "frames.json"), lambda p: open(p, "w").write(text))
    return result


def markdown(result):
    """The :func:`run_all` table as Markdown: one row per unit."""
    lines = ["| unit | frame | pixels (visible) | spans | cycles | mismatches | cycles/s | RTL s | wall s |",
             "|---|---|---:|---:|---:|---:|---:|---:|---:|"]
    for row in result["frames"]:
        lines.append(f"| {row['unit']} | {row['mesh']} {row['polygons']} polygons, {row['width']}×"
                     f"{row['height']}, frame {row['frame']} | {row['pixels']} ({row['visible']}) | "
                     f"{row['spans']} | {row['cycles']} | {row['mismatches']} | "
                     f"{row['cycles_per_second']:.0f} | {row['seconds']:.2f} | {row['wall_seconds']:.1f} |")
    lines.append(f"\nTotal mismatches {result['mismatches']}; wall time {result['wall_seconds']:.1f} s "
                 f"(rasterizer, setup, golden models, Verilator builds and RTL).")
    return "\n".join(lines)
