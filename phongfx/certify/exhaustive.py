"""The exhaustive certificate: every input code the host can send, through the golden model.

Where the domain is small enough, the error bound need not be derived: it can be measured
on every input the core can receive.  That is the case of exact per-pixel normals (no spans:
``n0 = n1``, ``a = 0``, as on Lyon's spheres with ``span = 0``), with every light
directional and the viewer at infinity: then ``L`` and ``V`` are constant codes, ``n`` takes
the few values the materials admit, and the only varying input is the normal's code.

Which codes.  The host turns a unit normal into a code by rounding each component to the
vector format (:func:`phongfx.sim.stimulus.datapath.encode`: half up, ``vec_frac`` fraction
bits).  :func:`normal_codes` lists every 3-component code that is the rounding of *some*
unit vector: for every ``(x, y)`` code whose cell ``[x - h, x + h] × [y - h, y + h]`` (``h``
half an LSB) meets the unit disc, the ``z`` codes of the interval that ``±sqrt(1 - x² - y²)``
sweeps over the cell (the cell meets the disc in a convex set, so ``z`` sweeps an interval
and its roundings a run of codes).  Of those it keeps the codes some unit vector of whose
cell can face the viewer (``N·V >= view_cos_min``): every unit vector of a cell lies within
``sqrt(3)·h`` of the code's value, so a code is kept when its value ``c`` has
``c·V >= view_cos_min - sqrt(3)·h``.  Closed cells and that margin make the list a superset
of what the host sends; a superset can only raise the measured maximum, so the bound stays
sound.  At ``vec_frac = 10`` it is about ten million codes facing a viewer along +z (a
hemisphere's surface, 2π·1024², times the mean of ``|x| + |y| + |z|``, 3/2).

Against what.  The reference of a code is Phong (or the method's own float form, against
``"self"``) at the code's own unit direction ``c/|c|``, with the exact lights and viewer.
The normals of the unit vectors inside one cell differ from ``c/|c|`` by up to about half
an LSB in angle; that difference is the host's encoding of the normal, not the core's error,
and the certificate does not cover it (the docs' page on the certificate says so).

The bound is the exact maximum over the list of ``|out - (2^bits - 1)·I_ref|``: nothing is
estimated, so it is sound by construction for the domain it enumerates.
"""

import math
import time

import numpy as np

from phongfx.core.format import Format
from phongfx.explore.compile import run as runs
from phongfx.explore.compile.analysis import analyse
from phongfx.explore.compile.measure import shade_points
from phongfx.scene.geometry import FrameGeometry, frames, levels, pixel_error

from .certificate import Certificate, meets

__all__ = ["MAX_CODES", "CHUNK", "applicable", "normal_format", "normal_codes", "count_codes", "exhaustive"]

#: Largest number of (normal code, shininess) cases :func:`exhaustive` evaluates: about a
#: minute and a half of the golden model (``vec_frac = 10`` with five ``n`` values fits).
MAX_CODES = 60_000_000
#: Normal codes per golden-model call: a few hundred MB of intermediate arrays at most.
CHUNK = 1 << 20


def applicable(method, spec, domain):
    """Why the exhaustive method cannot enumerate ``domain`` for ``method`` (one sentence),
    or None when it can."""
    # Lyon's spheres with span 0 feed n0 = n1 exactly; the domain's angle of such spans,
    # an arccos of a float dot product, can read a few 1e-7 degrees instead of 0
    exact = all(obj.kind == "lyon_spheres" and obj.params["span"] == 0 for obj in spec.objects)
    if domain.max_span_angle_deg > 0 and not exact:
        return (f"the domain has spans (span-end normals up to {domain.max_span_angle_deg:g}° apart), "
                f"too many inputs to enumerate; only exact per-pixel normals are")
    if any(light.kind != "directional" for light in spec.lights):
        return "a point light changes L per pixel; enumeration needs every light directional"
    if spec.camera.kind != "infinity" or spec.frames.camera_path:
        return "a local or moving viewer changes V per pixel; enumeration needs the viewer at infinity"
    if runs.hooks(method).normal_code:
        return None
    return f"the {method} unit is not fed a per-pixel normal code; enumeration covers those that are"


def normal_format(method, config):
    """The format in which ``method``'s shader ``config`` takes the normal from the host."""
    return runs.hooks(method).normal_format(config.units[0])


def _cells(fmt, xs):
    """``(x, y, zlo, zhi)`` raw codes: each ``(x, y)`` of the rows ``xs`` whose cell meets
    the unit disc, and the run ``zlo..zhi`` of non-negative ``z`` codes over it."""
    one, h = float(fmt.one), 0.5
    ys = np.arange(-fmt.one, fmt.one + 1, dtype=np.int64)
    x, y = np.repeat(xs, len(ys)), np.tile(ys, len(xs))

    def nearest(c):  # |c| closest to 0 over the cell [c - h, c + h], in LSB
        return np.where(np.abs(c) <= h, 0.0, np.abs(c) - h)
    rmin = (nearest(x) ** 2 + nearest(y) ** 2) / one ** 2
    rmax = ((np.abs(x) + h) ** 2 + (np.abs(y) + h) ** 2) / one ** 2
    keep = rmin <= 1.0
    x, y, rmin, rmax = x[keep], y[keep], rmin[keep], rmax[keep]
    # a hair of slack either way: one code too many is harmless, one too few is not
    zhi = np.floor(np.sqrt(1.0 - rmin) * one + 0.5 + 1e-9).astype(np.int64)
    zlo = np.floor(np.sqrt(np.maximum(1.0 - rmax, 0.0)) * one + 0.5 - 1e-9).astype(np.int64)
    return x, y, np.maximum(zlo, 0), np.minimum(zhi, fmt.max_raw)


def _rows(fmt, chunk):
    """Blocks of ``x`` codes whose ``(x, y)`` pairs number about ``chunk``."""
    xs = np.arange(-fmt.one, fmt.one + 1, dtype=np.int64)
    step = max(1, chunk // (2 * fmt.one + 1))
    return [xs[i:i + step] for i in range(0, len(xs), step)]


def count_codes(fmt, chunk=CHUNK):
    """How many codes :func:`normal_codes` considers before the viewer test (both
    hemispheres): what decides whether enumeration is affordable."""
    total = 0
    for xs in _rows(Format.parse(fmt), chunk):
        _, _, zlo, zhi = _cells(Format.parse(fmt), xs)
        total += 2 * int(np.sum(zhi - zlo + 1))
    return total


def normal_codes(fmt, view, view_cos_min, chunk=CHUNK):
    """Every normal code of ``fmt`` the host can send (module docstring), in arrays of at
    most about ``chunk`` rows: raw ``(count, 3)`` int64."""
    fmt = Format.parse(fmt)
    view = np.asarray(view, dtype=np.float64)
    view = view / np.linalg.norm(view)
    margin = view_cos_min - math.sqrt(3) * 0.5 / fmt.one
    for xs in _rows(fmt, chunk):
        x, y, zlo, zhi = _cells(fmt, xs)
        runs_ = zhi - zlo + 1
        start = np.repeat(np.cumsum(runs_) - runs_, runs_)
        z = np.repeat(zlo, runs_) + (np.arange(int(runs_.sum())) - start)
        x, y = np.repeat(x, runs_), np.repeat(y, runs_)
        for sign in (1, -1):
            codes = np.stack([x, y, sign * z], axis=-1)
            if sign < 0:
                codes = codes[z > 0]  # z = 0 is in both hemispheres: list it once
            value = codes.astype(np.float64) / fmt.one
            codes = codes[value @ view >= margin]
            for i in range(0, len(codes), chunk):
                yield codes[i:i + chunk]


def _geometry(spec, codes, fmt, material, n, bits):
    """A :class:`FrameGeometry` of one pixel per normal code: exact per-pixel normals
    (``n0 = n1`` = the code's value, ``a = 0``), the scene's lights and viewer at infinity."""
    count = len(codes)
    value = codes.astype(np.float64) / fmt.one
    length = np.linalg.norm(value, axis=-1, keepdims=True)
    normal = value / np.where(length > 0, length, 1.0)
    # the scene file's unit vectors as they are, as phongfx.scene.geometry.frames feeds them
    lights = np.stack([np.broadcast_to(np.asarray(light.vector, dtype=np.float64), (count, 3))
                       for light in spec.lights])
    viewer = np.broadcast_to(np.asarray(spec.camera.vector, dtype=np.float64), (count, 3))
    m = list(spec.materials.values())[material]
    zeros = np.zeros(count, dtype=np.int64)
    return FrameGeometry(
        0, 0, zeros, zeros, np.arange(count), np.zeros(count), value, value, normal, np.zeros((count, 3)),
        lights, lights, lights, viewer, viewer, viewer,
        np.array([light.rgb for light in spec.lights], dtype=np.float64).reshape(-1, 3),
        np.full(count, float(n)), np.full(count, m.kd), np.full(count, m.ks), np.full(count, m.ka),
        np.broadcast_to(np.asarray(m.colour, dtype=np.float64), (count, 3)), np.full(count, material),
        None, -1, bits)


def exhaustive(method, params, spec, domain, *, analysis=None, chunk=CHUNK, max_codes=MAX_CODES,
               progress=None):
    """The :class:`~.certificate.Certificate` of ``method`` at ``params`` over ``domain`` by
    enumeration (module docstring); ``certified: false`` with why when the domain is not
    enumerable (:func:`applicable`) or too large (``max_codes`` cases).

    ``parts`` holds ``codes`` (normal codes × shininess values evaluated),
    ``max_error_levels`` (the largest displayed error, ``|out - level(I_ref)|``), ``witness``
    (the input with the largest displayed error, ties by the unrounded one, in the witness
    format of :mod:`phongfx.explore.compile.witness`: its normal code, material index and
    ``n``, the port codes, outputs and displayed reference) and ``reference`` (what the error
    is measured against).
    """
    started = time.monotonic()
    why = applicable(method, spec, domain)
    if analysis is None:
        analysis = analyse(spec, frames(spec))
    config = runs.build(method, params, analysis)
    fmt = normal_format(method, config)
    cases = [(index, int(n)) for index, (_, values) in enumerate(domain.materials) for n in values]
    if why is None:
        # the share of the sphere facing the viewer, (1 - view_cos_min)/2, of every code
        share = (1 - min(1.0, max(-1.0, domain.view_cos_min))) / 2
        total = round(count_codes(fmt, chunk) * share) * len(cases)
        if total > max_codes:
            why = (f"{total:,} normal codes × shininess values at {fmt.frac_bits} fraction bits exceed "
                   f"the {max_codes:,} enumeration affords")
    if why is not None:
        return Certificate(False, None, "exhaustive", {}, why, time.monotonic() - started)
    against = spec.requirement.against
    scale, bound, worst, done = (1 << spec.output.bits) - 1, 0.0, None, 0
    for material, n in cases:
        for codes in normal_codes(fmt, spec.camera.vector, domain.view_cos_min, chunk):
            g = _geometry(spec, codes, fmt, material, n, spec.output.bits)
            shininess = np.full(len(codes), n, dtype=np.int64)
            out, ref, raw, _ = shade_points(method, config, params, against, g, shininess)
            unrounded = np.abs(out - ref * scale).max(axis=-1)
            shown = pixel_error(out, ref, spec.output.bits).max(axis=-1)
            bound = max(bound, float(unrounded.max()))
            pixel = int(np.lexsort((unrounded, shown))[-1])
            if worst is None or (shown[pixel], unrounded[pixel]) > (worst["error_levels"], worst["unrounded"]):
                worst = {"error_levels": int(shown[pixel]), "unrounded": float(unrounded[pixel]),
                         "point": {"normal_code": codes[pixel].tolist(), "normal": g.normal[pixel].tolist(),
                                   "material": material, "n": n},
                         "codes": {port: np.asarray(value)[pixel].tolist() for port, value in raw.items()},
                         "outputs": dict(zip("rgb", out[pixel].tolist())),
                         "reference_levels": levels(ref[pixel], spec.output.bits).tolist()}
            done += len(codes)
            if progress:
                progress(f"exhaustive {method}: {done:,} codes, max {bound:.3f} levels")
    if worst is not None:
        worst["found_by"] = f"exhaustive enumeration ({done:,} normal codes × shininess values)"
    certified = meets(bound, spec.requirement.max_error_levels)
    parts = {"codes": done, "max_error_levels": worst["error_levels"] if worst else 0, "witness": worst,
             "reference": f"{'Phong' if against == 'phong' else 'own float form'} at each code's unit direction"}
    why = "" if certified else (f"some input code misses the requirement by enumeration: "
                                f"{bound:.3f} levels rounds to more than {spec.requirement.max_error_levels:g}")
    return Certificate(certified, bound, "exhaustive", parts, why, time.monotonic() - started)
