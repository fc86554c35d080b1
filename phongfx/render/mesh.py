"""Scanline-shaded mesh frames by method, and Szirmay-Kalos Figures 14 and 15.

A frame of a rotating torus or UV sphere (:mod:`phongfx.scene.mesh`) is shaded per span with
``I = AMBIENT + KD·diffuse + KS·specular`` (Hast, Barrera & Bengtsson equation 1 plus
an ambient floor), ``diffuse`` from ``N·L`` and ``specular`` from ``(N·H)^n`` with a
directional light and the viewer at infinity (``H`` constant).  Methods, float
(:data:`FLOAT_METHODS`) and fixed point (:data:`SHADED_UNITS`, named as the units of
``phongfx compile``, so that ``euler`` is the same hardware everywhere):

* ``phong``: the interpolated normal renormalized per pixel (Duff's exact ``p/√q``,
  Hast equation 4) — the reference every other method is measured against;
* ``gouraud-float``: the end intensities ``max(N_a·L, 0)``, ``max(N_a·H, 0)^n`` (and at
  ``N_b``) interpolated linearly along the span;
* ``euler-float`` / ``corrected-euler``: Hast's quadratic recurrences (equations 12–17) for
  ``N·L`` and for ``N·H`` (their §6.1 uses it for both), then clamped and raised;
* ``cosn``: spherical interpolation (Szirmay-Kalos equation 17): the exact
  ``cos θ = A·cos(tγ - φ)`` of a normal turning uniformly from ``N_a`` to ``N_b``, raised
  to ``n``;
* ``cos2``: the same angle through Szirmay-Kalos's ``A^n·cos²(a·(tγ - φ))`` (equation
  19) in float: the approximation alone;
* ``spherical``: the fixed-point spherical unit (:mod:`phongfx.golden.spherical`, ROM of
  ``addr_bits`` address and ``rom_bits`` data bits), fed by
  :func:`phongfx.scene.span_inputs.spherical_inputs`; its diffuse channel reads the ``cos`` ROM;
* ``euler`` / ``gouraud``: ``N·L`` and ``N·H`` each through the fixed-point
  corrected Euler or Gouraud unit (:mod:`phongfx.golden.euler`, ``.gouraud``, default
  formats) fed by :func:`phongfx.scene.span_inputs.euler_inputs` / ``gouraud_inputs``, then
  clamped and raised like the float methods (so ``gouraud`` interpolates the dot
  products, not the end intensities as ``gouraud-float`` does);
* ``blinn``: the 16-bit Blinn–Phong baseline (:mod:`phongfx.golden.blinn`:
  reciprocal square root by table and Newton step, ``t^n`` by log2/exp2 tables) on the
  interpolated normal of every pixel, fed by :func:`phongfx.scene.span_inputs.blinn_inputs`;
* ``conventional``: the 16-bit conventional Phong unit (:mod:`phongfx.golden.conventional`: the
  same normalizer and power, Phong's own ``(R·V)^n``) on the interpolated normal of every
  pixel, fed by :func:`phongfx.scene.span_inputs.conventional_inputs`.  Its specular is
  Phong's reflection lobe, not the ``(N·H)^n`` of ``phong`` here, so against ``phong`` it
  shows the difference of the two highlights (``(R·V)^n`` is about ``(N·H)^(4n)``).

Errors are ``255·|I - I_phong|`` over the visible pixels (8-bit levels, as Hast's
Table 2), for the composite and for each term.  The names ``euler-unit`` and
``gouraud-unit`` of the fixed-point units before they took compile's names are still
accepted (:data:`RENAMED`), with a ``DeprecationWarning``.
"""

import os
import time
import warnings

from collections.abc import Sequence

import numpy as np
from PIL import Image

from phongfx.config import SphericalConfig
from phongfx.core.files import atomic_write
from phongfx.core.methods import METHODS as REGISTERED
from phongfx.core.methods import get_method
from phongfx.core.registry import get_block
from phongfx.golden import euler_setup, spherical_setup
from phongfx.scene import mesh as meshes
from phongfx.scene.span_inputs import (VIEWER, blinn_inputs, conventional_inputs, decode, euler_inputs,
                                       gouraud_inputs, halfway, spherical_inputs)
from phongfx.sim.stimulus.datapath import encode

from .figure import error_figure, frame_figure

__all__ = ["FLOAT_METHODS", "SHADED_UNITS", "SHADED", "RENAMED", "method_name", "MESHES", "LIGHT", "AMBIENT", "KD", "KS", "FIGURE_WEIGHTS", "build_mesh", "span_angles",
           "shade", "shade_euler", "shade_gouraud", "shade_blinn", "shade_conventional", "shade_spherical",
           "shade_datapath", "intensity", "error_8bit", "write_png", "run", "figure14", "figure15"]

FLOAT_METHODS = ("phong", "gouraud-float", "euler-float", "corrected-euler", "cosn", "cos2")


class _Shaded(Sequence):
    """``first`` and then the methods of :data:`phongfx.core.methods.METHODS` with a
    ``shade`` face, in the registry's order, read on every use (a method registered at run
    time is shaded at once)."""

    def __init__(self, first=()):
        self.first = tuple(first)

    def _names(self):
        return self.first + tuple(name for name, method in REGISTERED.items() if method.has("shade"))

    def __getitem__(self, index):
        return self._names()[index]

    def __len__(self):
        return len(self._names())

    def __repr__(self):
        return repr(self._names())


#: The golden fixed-point units, by the names ``phongfx compile`` gives them (the
#: registered methods that have a ``shade`` face).
SHADED_UNITS = _Shaded()
#: Every name ``phongfx render mesh`` shades: the float methods, then :data:`SHADED_UNITS`.
SHADED = _Shaded(FLOAT_METHODS)
#: Former name -> name: the fixed-point units were ``euler-unit`` and ``gouraud-unit``
#: here while ``euler`` and ``gouraud`` named the float methods, unlike compile.
RENAMED = {"euler-unit": "euler", "gouraud-unit": "gouraud"}
MESHES = ("torus", "sphere")
#: Up, left and towards the viewer, so the highlight sits on the visible side.
LIGHT = (-0.4, 0.5, 0.77)
AMBIENT, KD, KS = 0.1, 0.55, 0.35
#: Darker diffuse in the figures, so the highlights (what Figures 14 and 15 are about) stand out.
FIGURE_WEIGHTS = (0.05, 0.35, 0.6)


def method_name(method):
    """``method``'s name in :data:`SHADED`: itself, or for a former name (:data:`RENAMED`)
    the new one, with a ``DeprecationWarning``; ValueError naming the methods otherwise."""
    if method in RENAMED:
        warnings.warn(f"method {method!r} is now called {RENAMED[method]!r} (the fixed-point unit, "
                      f"named as in phongfx compile)", DeprecationWarning, stacklevel=3)
        return RENAMED[method]
    if method not in SHADED:
        raise ValueError(f"method must be one of {', '.join(SHADED)}, not {method!r}")
    return method


def build_mesh(mesh="torus", *, polygons=800, stacks=8, slices=16):
    """The torus of ``polygons`` quads or the ``stacks × slices`` UV sphere."""
    if mesh == "torus":
        return meshes.torus(polygons)
    if mesh == "sphere":
        return meshes.uv_sphere(stacks, slices)
    raise ValueError(f"mesh must be one of {', '.join(MESHES)}, not {mesh!r}")


def _unit(v):
    v = np.asarray(v, dtype=np.float64)
    return v / np.linalg.norm(v)


def _power(c, n):
    return np.where(c > 0, np.maximum(c, 0.0) ** n, 0.0)


def span_angles(spans, v):
    """Per span ``A, φ, γ`` of Szirmay-Kalos equations 15–17 for a constant ``v``."""
    count = len(spans.length)
    v = np.broadcast_to(v, (count, 3))
    setup = spherical_setup.span_setups(spans.na, spans.nb, v, v, 1, spans.length)
    return setup["A"], setup["phi"], setup["gamma"]


def _spherical_float(spans, v, n, approximate):
    """``cos^n θ`` (``approximate=False``) or ``A^n·cos²(a(tγ - φ))`` per pixel."""
    big_a, phi, gamma = span_angles(spans, v)
    span, t = spans.pixel_span(), spans.pixel_t()
    x = t * gamma[span] - phi[span]
    if not approximate:
        return _power(big_a[span] * np.cos(x), n)
    ax = spherical_setup.solve_a(n) * x
    return big_a[span] ** n * np.where(np.abs(ax) <= np.pi / 2, np.cos(ax) ** 2, 0.0)


def shade(spans, method, *, light=LIGHT, n=20, addr_bits=6, rom_bits=6):
    """Per-pixel ``(diffuse, specular)`` float arrays (P,) of ``method`` (module docstring).

    ``spherical`` loads ``C = 0`` on spans whose angle misses the ``cos²(a·x)`` lobe
    (:func:`phongfx.golden.spherical_setup.span_setups`): the wrapping angle register
    would otherwise read the lit cells again.
    """
    method = method_name(method)
    light = _unit(light)
    h = halfway(light)
    if method in ("phong", "euler-float", "corrected-euler"):
        key = {"phong": "phong", "euler-float": "euler", "corrected-euler": "corrected"}[method]
        span, step = spans.pixel_span(), spans.pixel_step()
        curve = [euler_setup.curves_at(euler_setup.span_setups(spans.na, spans.nb, v, spans.length),
                                       span, step)[key] for v in (light, h)]
        return np.maximum(curve[0], 0.0), _power(curve[1], n)
    if method == "gouraud-float":
        span, t = spans.pixel_span(), spans.pixel_t()
        ends = [(np.maximum(spans.na @ light, 0), np.maximum(spans.nb @ light, 0)),
                (_power(spans.na @ h, n), _power(spans.nb @ h, n))]
        return tuple(a[span] + t * (b[span] - a[span]) for a, b in ends)
    if method in ("cosn", "cos2"):
        return (_spherical_float(spans, light, 1, False),
                _spherical_float(spans, h, n, method == "cos2"))
    return get_method(method).load("shade")(spans, method, light=light, h=h, n=n, addr_bits=addr_bits,
                                             rom_bits=rom_bits)


def _scanline(feed):
    """The ``shade`` face of a unit interpolating a dot product along the span (Euler,
    Gouraud; ``feed`` its span inputs): ``N·L`` and ``N·H`` each through it, then clamped and
    raised like the float methods."""
    def shade_unit(spans, method, *, light, h, n, **options):
        block = get_block(method)
        curve = [decode(block.golden(feed(spans, v, block.config)), block.config) for v in (light, h)]
        return curve[0], _power(curve[1], n)
    return shade_unit


def _tables(feed):
    """The ``shade`` face of a unit on the tables of :mod:`phongfx.golden.blinn` (Blinn,
    conventional Phong; ``feed`` its span inputs): its own diffuse and specular outputs."""
    def shade_unit(spans, method, *, light, h, n, **options):
        block = get_block(method)
        out = block.golden(feed(spans, light, n, block.config))
        return decode(out, block.config, "diff"), decode(out, block.config, "spec")
    return shade_unit


shade_euler, shade_gouraud = _scanline(euler_inputs), _scanline(gouraud_inputs)
shade_blinn, shade_conventional = _tables(blinn_inputs), _tables(conventional_inputs)


def shade_spherical(spans, method, *, light, h, n, addr_bits=6, rom_bits=6):
    """The spherical unit at ``addr_bits``, ``rom_bits``; its diffuse reads the ``cos`` ROM."""
    config = SphericalConfig(addr_bits=addr_bits, rom=f"0.{rom_bits}")
    block = get_block("spherical", addr_bits=addr_bits, rom=f"0.{rom_bits}")
    raw = spherical_inputs(spans, light, n, config)
    out = block.golden(raw)
    return decode(out, config, "diff")[:, 0], decode(out, config, "spec")


def shade_datapath(spans, method, *, light, h, n, **options):
    """A specular unit of the datapath (its method's block at its defaults, one light,
    viewer along +z) on the interpolated normals of the span ends: ``diff0``, ``spec0``."""
    config = get_block(get_method(method).block).config.replace(lights=1)
    span = spans.pixel_span()
    count = len(span)
    raw = encode(config, spans.na[span], spans.nb[span], spans.pixel_t(), np.full(count, float(n)),
                 VIEWER, VIEWER, [light], [light])
    out = get_block(get_method(method).block, config=config).golden(raw)
    return tuple(np.asarray(out[name]) * config.outputs[name][0].lsb for name in ("diff0", "spec0"))


def intensity(diffuse, specular, weights=(AMBIENT, KD, KS)):
    """``ambient + kd·diffuse + ks·specular`` clipped to [0, 1], ``weights = (ambient, kd, ks)``."""
    ambient, kd, ks = weights
    return np.clip(ambient + kd * diffuse + ks * specular, 0.0, 1.0)


def error_8bit(value, reference, visible):
    """``{"max", "mean"}`` of ``255·|value - reference|`` over the visible pixels."""
    diff = 255 * np.abs(np.asarray(value) - np.asarray(reference))[visible]
    return {"max": float(diff.max()) if diff.size else 0.0,
            "mean": float(diff.mean()) if diff.size else 0.0}


def write_png(path, picture):
    """Write a [0, 1] grey (H, W) or RGB (H, W, 3) float picture as an 8-bit PNG, atomically."""
    data = np.round(np.clip(picture, 0, 1) * 255).astype(np.uint8)
    atomic_write(path, lambda tmp: Image.fromarray(data).save(tmp, format="PNG"))
    return path


def _frame(spans, method, weights=(AMBIENT, KD, KS), **options):
    diffuse, specular = shade(spans, method, **options)
    return diffuse, specular, intensity(diffuse, specular, weights)


def _errors(spans, shaded, reference):
    names = ("diffuse", "specular", "total")
    return {name: error_8bit(a, b, spans.visible) for name, a, b in zip(names, shaded, reference)}


def run(method, *, mesh="torus", polygons=800, stacks=8, slices=16, n=20, addr_bits=6, rom_bits=6,
        width=256, height=256, frame=0, light=LIGHT, out_dir="build/mesh"):
    """Shade one frame by ``method``, write ``<out_dir>/<name>.png`` (the frame, titled
    with the method, mesh, n and frame) and ``<name>_error.png`` (its composite's error
    against ``phong`` in 8-bit levels, with a colour bar up to the largest), return a summary.

    The summary holds the PNG ``path`` and ``error_path``, the method's ``kind`` (float or
    fixed point), the geometry counts, the seconds taken and ``error_8bit``:
    ``{diffuse, specular, total}`` each ``{max, mean}`` against ``phong``.
    """
    method = method_name(method)
    if isinstance(n, bool) or not isinstance(n, (int, float)) or not n > 0:
        raise ValueError(f"n must be a positive number, not {n!r}")
    start = time.perf_counter()
    shape = build_mesh(mesh, polygons=polygons, stacks=stacks, slices=slices)
    spans = meshes.rasterize(shape, meshes.rotation(frame), width, height)
    options = {"light": light, "n": n, "addr_bits": addr_bits, "rom_bits": rom_bits}
    shaded = _frame(spans, method, **options)
    reference = shaded if method == "phong" else _frame(spans, "phong", **options)
    size = f"{polygons}" if mesh == "torus" else f"{stacks}x{slices}"
    # the ROM sizes name the picture of a method that has them (Szirmay-Kalos's unit)
    roms = method in REGISTERED and {"addr_bits", "rom_bits"} <= set(REGISTERED[method].params)
    bits = f"-a{addr_bits}d{rom_bits}" if roms else ""
    name = f"{mesh}{size}-{method}{bits}-n{n:g}-f{frame}"
    kind = "float" if method in FLOAT_METHODS else "fixed point"
    rom = f", ROM of {addr_bits} address and {rom_bits} data bits"
    errors = _errors(spans, shaded, reference)
    what = f"{mesh} {size}{' polygons' if mesh == 'torus' else ''}, n = {n:g}, frame {frame}"
    path = frame_figure(os.path.join(out_dir, f"{name}.png"), meshes.image(spans, shaded[2]),
                        f"{method} ({kind}{rom if bits else ''}): {what}")
    levels = meshes.image(spans, 255 * np.abs(shaded[2] - reference[2]), background=np.nan)
    total = errors["total"]
    error_path = error_figure(os.path.join(out_dir, f"{name}_error.png"), levels,
                              f"|{method} − phong|: {what}; max {total['max']:.2f}, "
                              f"mean {total['mean']:.3f} levels", max(1.0, total["max"]))
    return {"method": method, "kind": kind, "mesh": mesh, "polygons": shape.polygons, "n": n, "frame": frame,
            "width": width, "height": height, "addr_bits": addr_bits, "rom_bits": rom_bits,
            "name": name, "path": path, "error_path": error_path, "spans": int(len(spans.length)),
            "pixels": int(spans.visible.sum()), "error_8bit": errors,
            "seconds": time.perf_counter() - start}


def _label(picture, text):
    """``picture`` (H, W) with ``text`` written in white in its top-left corner."""
    from PIL import ImageDraw
    mask = Image.new("L", picture.shape[::-1], 0)
    ImageDraw.Draw(mask).text((4, 3), text, fill=255)
    return np.maximum(picture, np.asarray(mask, dtype=np.float64) / 255)


def _panel(pictures, gap=4, labels=None):
    """Pictures (rows of equal-size arrays) tiled with a ``gap`` of grey between them;
    ``labels`` (rows of strings) written on the tiles."""
    if labels:
        pictures = [[_label(p, text) for p, text in zip(row, names)] for row, names in zip(pictures, labels)]
    rows = []
    for row in pictures:
        h = row[0].shape[0]
        sep = np.full((h, gap), 0.5)
        rows.append(np.hstack([x for p in row for x in (p, sep)][:-1]))
    sep = np.full((gap, rows[0].shape[1]), 0.5)
    return np.vstack([x for r in rows for x in (r, sep)][:-1])


def figure15(out_dir="build/mesh", *, stacks=8, slices=16, n=20, size=256, frame=20, bits=(4, 6)):
    """Szirmay-Kalos Figure 15: a coarse sphere through the spherical unit with ``bits[0]``-
    and ``bits[1]``-bit ROM (address and data bits alike), side by side in ``figure15.png``:
    top row the composite, bottom row the specular term alone; ``cosn`` (exact) in the
    third column.  The ROM's steps fall on contours of the span angle ``x = tγ - φ``
    (``cos θ = A·cos x``, ``A`` per span), so at 4 bits they show as bands across the
    highlight, gone at 6 bits.

    Returns the path and, per bit count, the error (8-bit levels, ``max``/``mean`` of each
    term and the composite) against ``cosn`` (the exact spherical interpolation: the ROM
    and register error plus the ``cos²(a·x)`` approximation) and against ``phong``.
    """
    spans = meshes.rasterize(meshes.uv_sphere(stacks, slices), meshes.rotation(frame), size, size)
    cosn, phong = _frame(spans, "cosn", FIGURE_WEIGHTS, n=n), _frame(spans, "phong", FIGURE_WEIGHTS, n=n)
    rows, errors = [[], []], {}
    units = [(_frame(spans, "spherical", FIGURE_WEIGHTS, n=n, addr_bits=b, rom_bits=b), b) for b in bits]
    for shaded, b in units + [(cosn, None)]:
        rows[0].append(meshes.image(spans, shaded[2]))
        rows[1].append(meshes.image(spans, shaded[1]))
        if b is not None:
            errors[f"{b}-bit"] = {"vs_cosn": _errors(spans, shaded, cosn),
                                  "vs_phong": _errors(spans, shaded, phong)}
    names = [f"{b}-bit ROM" for b in bits] + ["cos^n (exact)"]
    labels = [[f"{name}, n = {n}" for name in names], [f"{name}, specular" for name in names]]
    path = write_png(os.path.join(out_dir, "figure15.png"), _panel(rows, labels=labels))
    return {"path": path, "n": n, "stacks": stacks, "slices": slices, "bits": list(bits),
            "errors": errors}


def figure14(out_dir="build/mesh", *, shininess=(5, 10, 20), stacks=24, slices=48, size=192, frame=20):
    """Szirmay-Kalos Figure 14: spheres of shine ``n`` = 5, 10, 20 rendered with ``cos^n θ``
    (top row) and ``cos²(a·θ)`` (bottom row), in float, one grid in ``figure14.png``.

    Returns the path and per ``n`` the ``a(n)`` used and the max/mean difference (8-bit
    levels) of the specular term and of the composite.
    """
    spans = meshes.rasterize(meshes.uv_sphere(stacks, slices), meshes.rotation(frame), size, size)
    rows, per_n = [[], []], {}
    for n in shininess:
        cosn, cos2 = _frame(spans, "cosn", FIGURE_WEIGHTS, n=n), _frame(spans, "cos2", FIGURE_WEIGHTS, n=n)
        rows[0].append(meshes.image(spans, cosn[2]))
        rows[1].append(meshes.image(spans, cos2[2]))
        errors = _errors(spans, cos2, cosn)
        per_n[str(n)] = {"a": spherical_setup.solve_a(n), "specular": errors["specular"],
                         "total": errors["total"]}
    labels = [[f"cos^n, n = {n}" for n in shininess],
              [f"cos^2(a x), a = {spherical_setup.solve_a(n):.3f}" for n in shininess]]
    path = write_png(os.path.join(out_dir, "figure14.png"), _panel(rows, labels=labels))
    return {"path": path, "stacks": stacks, "slices": slices, "difference": per_n}
