"""How each method of :data:`phongfx.explore.methods.METHODS` shades a scene file's frame.

The compiler (:mod:`phongfx.explore.compile.compiler`) asks, per method: can it represent the scene
(:func:`rejection`), what is its block config at given widths (:func:`build`), what
are a frame's raw input codes (:func:`frame_inputs`, the same stream the RTL check
drives), and what diffuse and specular amounts per light do its raw outputs stand for
(:func:`frame_terms`).  :func:`own_specular` is the method's float form (the
``against = "self"`` reference).

* Lyon's datapaths (``fig7``, ``fig8``, ``halfway``) take everything a scene has: span
  ends of N, of L and V when local (:func:`phongfx.sim.stimulus.datapath.encode`), any
  number of lights, ``n`` per pixel or fixed in the hardware (``n_const``/``m_const``).
* ``blinn`` and ``spherical`` compute Blinn's ``(N·H)^n'`` and take one copy of
  the unit per light (their streams are checked one after the other, :func:`copies`).
  ``blinn`` is fed per pixel the interpolated ``N`` and the exact unit ``L`` and
  ``H = (L+V)/|L+V|`` of that pixel, so it takes point lights and a local viewer too (the
  hardware that would compute those per-pixel vectors is not in its cost);
  ``spherical`` needs directional lights and the camera at infinity along +z.  They are
  fed ``n' = 4n`` (Lyon's appendix: ``(N·H)^(4n)`` stands for ``(R·L)^n``), so their
  ``"phong"`` error includes that approximation and ``"self"`` is float ``(N̂·H)^(4n)``
  (spherical: Szirmay-Kalos's ``A^n'·cos²``).  ``spherical`` also needs mesh spans and
  one ``n`` (its per-span setup holds it).
* ``conventional`` computes Phong's own ``(R·V)^n`` with ``n`` itself (no ``4n``), one copy
  per light, fed per pixel the interpolated ``N`` and ``L``, ``V``: the exact unit vectors
  of the pixel, or, for point lights (``local_light``) and a local viewer
  (``local_viewer``), the un-normalized ``(1-a)·X0 + a·X1`` of the span ends' unit vectors
  toward the light or viewer (what a Phong shader interpolates, Lyon 1993 Figure 1, and
  what the datapaths' L and V LIRPs are fed), which the unit normalizes itself.  Its
  ``"self"`` is float Phong with its backside test (0 where ``N̂·L <= 0``).
* ``schlick`` has no diffuse path and ``euler``/``gouraud`` no specular one (they
  interpolate ``N·L``, Hast et al.): rejected for scenes that need the missing term.
"""

import numpy as np

from phongfx.explore.methods import METHODS
from phongfx.golden.reference import specular
from phongfx.render.mesh import shade as mesh_shade
from phongfx.scene.mesh import unit
from phongfx.scene.span_inputs import VIEWER, blinn_codes, conventional_codes, decode, spherical_inputs
from phongfx.sim.stimulus.datapath import encode

__all__ = ["DATAPATHS", "EXTRA", "K_MAX", "rejection", "build", "frame_inputs", "frame_terms", "own_specular",
           "block_name", "copies"]

#: Methods built as a :class:`~phongfx.config.DatapathConfig`.
DATAPATHS = ("fig7", "fig8", "halfway")
#: Parameters the compiler adds to a method's own: the normalizers' order (g1 = 1, g2 = 2).
EXTRA = {name: {"order": (2, (1, 2))} for name in DATAPATHS}
#: Largest shape-function ``k`` (:class:`~phongfx.config.ShapeConfig`): against true Phong
#: the compiler searches ``k`` too, since ``f_k(n·D²/2)`` is ``(R·L)^n`` exactly at ``2^k = n``.
K_MAX = 4
_BLINN = ("blinn", "spherical")
#: The units fed the visible pixels only, each with its own vectors (one stream per light).
_PER_PIXEL = ("blinn", "conventional")


def _n_hi(analysis, method):
    return 4 * analysis.n_hi if method in _BLINN else analysis.n_hi


def rejection(method, spec, analysis, geometries):
    """Why ``method`` cannot represent the scene (one sentence), or None when it can."""
    kd = max(float(np.max(g.kd, initial=0)) for g in geometries)
    ks = max(float(np.max(g.ks, initial=0)) for g in geometries)
    if method in DATAPATHS:
        top = METHODS[method].ranges["lights"][1]
        if analysis.lights > top:
            return f"{analysis.lights} lights; the datapath takes 1..{top}"
        if method == "fig8" and int(np.ceil(np.sqrt(analysis.n_hi))) > 63:
            return f"n up to {analysis.n_hi}; Figure 8's m = √n takes at most 63"
        return None
    if method == "schlick" and kd > 0:
        return "Schlick's unit computes only the specular term; the scene has diffuse (kd > 0)"
    if method in ("euler", "gouraud"):
        return (f"the {method} unit interpolates the diffuse N·L only (Hast et al.); the scene has "
                f"specular (ks > 0), peaking inside {100 * analysis.highlight_in_span:.1f}% of its "
                f"spans" if ks > 0 else f"diffuse-only scenes are not compiled for the {method} unit")
    if method == "spherical" and any(g.spans is None for g in geometries):
        return "needs mesh spans (its setup is per span); the scene has Lyon's spheres"
    if method == "spherical":
        if analysis.local_lights:
            return "needs directional lights (one H per light and frame)"
        if analysis.local_viewer or not np.allclose(spec.camera.vector, VIEWER):
            return "needs the camera at infinity along +z (V = (0, 0, 1), one H per light and frame)"
        top = METHODS[method].ranges["n"][1]
        if _n_hi(analysis, method) > top:
            return f"is fed n' = 4n up to {4 * analysis.n_hi}; the unit takes 1..{top}"
    if method == "spherical" and not analysis.single_n:
        return "its per-span setup holds one n; the scene has several"
    return None


def build(method, params, analysis):
    """Block config of ``method`` at ``params`` (the method's own and :data:`EXTRA`),
    fitted to the scene: lights, local L/V, ``n`` format narrowed to the scene's largest
    ``n``, ``n`` fixed in the hardware for a single ``n``."""
    spec = METHODS[method]
    own = {k: v for k, v in params.items() if k in spec.params}
    k = own.pop("k", None)
    if method in DATAPATHS:
        own["lights"] = analysis.lights
    config = spec.build(spec.resolve(own))
    if k is not None:  # past the sweep's range: the shape function takes k up to 4
        config = (config.replace(root=config.root.replace(k=k)) if method == "fig8"
                  else config.replace(shape=config.shape.replace(k=k)))
    if method not in DATAPATHS:
        if method in _PER_PIXEL:
            top = _n_hi(analysis, method)
            config = config.replace(n=f"{top.bit_length()}.0", n_max=top)
        if method == "conventional":
            config = config.replace(local_light=analysis.local_lights, local_viewer=analysis.local_viewer)
        return config
    norm = config.normalize.replace(order=params.get("order", 2))
    config = config.replace(normalize=norm, direction_normalize=norm,
                            local_lights=analysis.local_lights, local_viewer=analysis.local_viewer)
    const = analysis.n_lo if analysis.single_n else 0
    if method == "fig8":
        m = int(np.ceil(np.sqrt(analysis.n_hi)))
        root = config.root.replace(m=f"{m.bit_length()}.0", m_max=m)
        if const:
            root = root.replace(m_const=min(max(round(np.sqrt(const)), 1), m))
        return config.replace(root=root)
    shift = config.halfway_shift if method == "halfway" else 0
    top = analysis.n_hi << shift
    difference = config.difference.replace(n=f"{top.bit_length()}.0", n_max=top)
    if const:
        difference = difference.replace(n_const=const << shift)
    return config.replace(difference=difference)


def frame_inputs(method, config, geometry, n):
    """Raw input codes of one frame with per-pixel shininess ``n`` (visible pixels; every
    span pixel for the units fed per span)."""
    if method in DATAPATHS:  # a shininess fixed in the hardware has no port: encode drops it
        return encode(config, geometry.n0, geometry.n1, geometry.a, n, geometry.v0, geometry.v1,
                      list(geometry.l0), list(geometry.l1))
    if method == "blinn":  # visible pixels only, each with its own L and H
        streams = [blinn_codes(geometry.interpolated, light, unit(light + geometry.viewer),
                                      (4 * n).astype(np.int64), config) for light in geometry.light]
    elif method == "conventional":  # visible pixels only; a local L or V as interpolated
        view = _lirp(geometry, geometry.v0, geometry.v1) if config.local_viewer else geometry.viewer
        lights = _lirp(geometry, geometry.l0, geometry.l1) if config.local_light else geometry.light
        streams = [conventional_codes(geometry.interpolated, light, view, n.astype(np.int64), config)
                   for light in lights]
    else:  # one copy of the unit per light: their streams in a row
        lo = int(4 * n.min())
        streams = [spherical_inputs(geometry.spans, light, lo, config) for light in geometry.light[:, 0]]
    return {name: np.concatenate([raw[name] for raw in streams]) for name in streams[0]}


def frame_terms(method, config, outputs, geometry):
    """``(diff, spec)``, each (lights, P), the amounts the raw ``outputs`` stand for."""
    if method in DATAPATHS:
        ports = config.outputs
        lights = range(config.lights)
        return tuple(np.stack([outputs[f"{part}{i}"] * ports[f"{part}{i}"][0].lsb for i in lights])
                     for part in ("diff", "spec"))
    lights = len(geometry.light)
    visible = slice(None) if method in _PER_PIXEL else geometry.spans.visible
    diff = decode(method, outputs, config, "diff")
    diff = diff[:, 0] if diff.ndim > 1 else diff
    spec = decode(method, outputs, config, "spec")
    return tuple(term.reshape(lights, -1)[:, visible] for term in (diff, spec))


def own_specular(method, config, params, geometry, n):
    """(lights, P) the method's float specular form at the exact vectors (``"self"``)."""
    lights = np.asarray(geometry.light)
    if method == "spherical":
        return np.stack([mesh_shade(geometry.spans, "cos2", light=light, n=4 * float(n[0]))[1][
            geometry.spans.visible] for light in lights[:, 0]])
    if method == "conventional":  # Phong with the unit's backside test
        normal, viewer = geometry.normal, geometry.viewer
        return np.stack([np.where(np.sum(normal * light, -1) > 0, specular("phong", normal, light, viewer, n), 0.0)
                         for light in lights])
    if method == "blinn":
        form = "blinn"
    elif method == "halfway":
        form = f"halfway-g2proj-k{params.get('k', METHODS[method].params['k'])}"
    else:
        form = f"lyon-k{params.get('k', METHODS[method].params['k'])}"
    if method == "fig8":
        m = config.shininess_const or np.clip(np.round(np.sqrt(n)), 1, config.root.m_max)
        n = np.broadcast_to(m * m, n.shape).astype(np.float64)
    normal = geometry.normal
    return np.stack([specular(form, normal, light, geometry.viewer, n) for light in lights])


def _lirp(geometry, start, end):
    """``(1-a)·start + a·end`` at every pixel (``start``, ``end``: (..., P, 3) span-end vectors)."""
    a = np.asarray(geometry.a, dtype=np.float64)[:, None]
    return (1 - a) * start + a * end


def copies(method, analysis):
    """How many copies of ``method``'s block the scene needs (one per light for the
    single-light units; Lyon's datapaths hold every light)."""
    return 1 if method in DATAPATHS else analysis.lights


def block_name(method):
    """The registry block of ``method``."""
    return METHODS[method].block
