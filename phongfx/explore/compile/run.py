"""How each method of :data:`phongfx.explore.methods.METHODS` shades a scene file's frame.

The compiler (:mod:`phongfx.explore.compile.compiler`) asks, per method: can it represent the scene
(:func:`rejection`), what is its whole shader at given widths (:func:`build`: the unit,
:func:`unit_config`, and the hardware blend of the scene's constants to ``r``, ``g``,
``b``), what are a frame's raw input codes (:func:`frame_inputs`, the same stream the RTL
check drives), and which pixels its ``r``, ``g``, ``b`` codes are (:func:`frame_codes`).
:func:`own_specular` is the method's float form (the ``against = "self"`` reference).

* Lyon's datapaths (``fig7``, ``fig8``, ``halfway``) take everything a scene has: span
  ends of N, of L and V when local (:func:`phongfx.sim.stimulus.datapath.encode`), any
  number of lights, ``n`` per pixel or fixed in the hardware (``n_const``/``m_const``).
* ``blinn`` and ``spherical`` compute Blinn's ``(N·H)^n'`` and take one copy of
  the unit per light, side by side in the shader (:func:`copies`).
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

from phongfx.config import BlendConfig, ShaderConfig
from phongfx.config.shader import UNIT_TERMS
from phongfx.explore.methods import METHODS
from phongfx.golden.reference import specular
from phongfx.render.mesh import shade as mesh_shade
from phongfx.scene.mesh import unit
from phongfx.scene.span_inputs import VIEWER, blinn_codes, conventional_codes, spherical_inputs
from phongfx.sim.stimulus.datapath import encode

__all__ = ["DATAPATHS", "EXTRA", "COEF_DEFAULT", "rejection", "unit_config", "build", "frame_inputs",
           "visible", "frame_codes", "own_specular", "block_name", "copies"]

#: Methods built as a :class:`~phongfx.config.DatapathConfig`.
DATAPATHS = ("fig7", "fig8", "halfway")
#: Fraction bits of the blend's constants (``coef``) at a method's defaults: their rounding
#: moves a pixel by at most (2·lights + 1)·2^-(coef+1) levels before its own rounding.
COEF_DEFAULT = 8
#: Parameters the compiler adds to a method's own: the blend's ``coef`` (every method) and
#: the normalizers' order (g1 = 1, g2 = 2; Lyon's datapaths).
EXTRA = {name: {"coef": (COEF_DEFAULT, (0, 16)), **({"order": (2, (1, 2))} if name in DATAPATHS else {})}
         for name in METHODS}
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
    if method == "spherical" and len(spec.materials) > 1:
        return "its stream covers hidden span pixels, which have no material: the scene has several"
    if method == "spherical" and not analysis.single_n:
        return "its per-span setup holds one n; the scene has several"
    return None


def unit_config(method, params, analysis, light=None):
    """The shading unit's config of ``method`` at ``params`` (the method's own and
    :data:`EXTRA`), fitted to the scene: lights, local L/V (each light on its own), ``n``
    format narrowed to the scene's largest ``n``, ``n`` fixed in the hardware for a single
    ``n``.  ``light``: the light of a copy of a one-light unit (its L local or not)."""
    spec = METHODS[method]
    own = {k: v for k, v in params.items() if k in spec.params}
    if method in DATAPATHS:
        own["lights"] = analysis.lights
    config = spec.build(spec.resolve(own))
    if method not in DATAPATHS:
        if method in _PER_PIXEL:
            top = _n_hi(analysis, method)
            config = config.replace(n=f"{top.bit_length()}.0", n_max=top)
        if method == "conventional":
            config = config.replace(local_light=analysis.light_local[light],
                                    local_viewer=analysis.local_viewer)
        return config
    norm = config.normalize.replace(order=params.get("order", 2))
    config = config.replace(normalize=norm, direction_normalize=norm,
                            local_lights=analysis.local_lights_config, local_viewer=analysis.local_viewer)
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


def build(method, params, analysis):
    """The whole shader of ``method`` at ``params``: its unit (one copy, or one per light
    for a one-light unit, :func:`unit_config`) and the blend of the scene's constants
    (:class:`~phongfx.config.BlendConfig`: ``coef`` fraction bits, the scene's output bits)."""
    lights = range(copies(method, analysis))
    units = tuple(unit_config(method, params, analysis, light) for light in lights)
    block = METHODS[method].block
    diff, _, spec = UNIT_TERMS[block](units[0])[0]
    outputs = units[0].outputs
    blend = BlendConfig(lights=analysis.lights, diff=str(outputs[diff][0]) if diff else "",
                        spec=str(outputs[spec][0]), coef_frac=params.get("coef", COEF_DEFAULT),
                        bits=analysis.bits, ambient=analysis.ambient,
                        diffuse=analysis.diffuse if diff else _zeros(analysis.diffuse),
                        specular=analysis.specular, gate=diff is not None,
                        pipeline=getattr(units[0], "pipeline", 0))
    return ShaderConfig(unit=block, units=units, blend=blend)


def _zeros(nested):
    """``nested`` (per material, per light, RGB) with every value 0."""
    return tuple(tuple((0.0, 0.0, 0.0) for _ in material) for material in nested)


def frame_inputs(method, config, geometry, n):
    """Raw shader input codes of one frame with per-pixel shininess ``n`` (visible pixels;
    every span pixel for the units fed per span): each copy's stream side by side, and
    the pixel's material."""
    units = config.units
    if method in DATAPATHS:  # a shininess fixed in the hardware has no port: encode drops it
        streams = [encode(units[0], geometry.n0, geometry.n1, geometry.a, n, geometry.v0, geometry.v1,
                          list(geometry.l0), list(geometry.l1))]
    elif method == "blinn":  # visible pixels only, each with its own L and H
        streams = [blinn_codes(geometry.interpolated, light, unit(light + geometry.viewer),
                               (4 * n).astype(np.int64), sub) for light, sub in zip(geometry.light, units)]
    elif method == "conventional":  # visible pixels only; a local L or V as interpolated
        view = _lirp(geometry, geometry.v0, geometry.v1) if config.units[0].local_viewer else geometry.viewer
        streams = [conventional_codes(geometry.interpolated,
                                      _lirp(geometry, l0, l1) if sub.local_light else light, view,
                                      n.astype(np.int64), sub)
                   for l0, l1, light, sub in zip(geometry.l0, geometry.l1, geometry.light, units)]
    else:  # one copy of the unit per light, fed every span pixel
        lo = int(4 * n.min())
        streams = [spherical_inputs(geometry.spans, light, lo, sub)
                   for light, sub in zip(geometry.light[:, 0], units)]
    raw = {config.prefix(copy) + name: value for copy, stream in enumerate(streams)
           for name, value in stream.items()}
    if "material" in config.inputs:
        raw["material"] = np.asarray(geometry.material, dtype=np.int64)
    return raw


def visible(method, values, geometry):
    """``values`` (count,) of the shader's stream at the frame's visible pixels (P,): the
    stream is those pixels, except the spherical unit's, which is every span pixel."""
    values = np.asarray(values)
    return values if method != "spherical" else values[geometry.spans.visible]


def frame_codes(method, outputs, geometry):
    """(P, 3) the ``r``, ``g``, ``b`` codes of the frame's visible pixels from the shader's
    raw ``outputs``."""
    return np.stack([visible(method, outputs[name], geometry) for name in "rgb"], axis=-1)


def own_specular(method, config, params, geometry, n):
    """(lights, P) the method's float specular form at the exact vectors (``"self"``);
    ``config`` the shader's."""
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
        unit_ = config.units[0]
        m = unit_.shininess_const or np.clip(np.round(np.sqrt(n)), 1, unit_.root.m_max)
        n = np.broadcast_to(m * m, n.shape).astype(np.float64)
    normal = geometry.normal
    return np.stack([specular(form, normal, light, geometry.viewer, n) for light in lights])


def _lirp(geometry, start, end):
    """``(1-a)·start + a·end`` at every pixel (``start``, ``end``: (..., P, 3) span-end vectors)."""
    a = np.asarray(geometry.a, dtype=np.float64)[:, None]
    return (1 - a) * start + a * end


def copies(method, analysis):
    """How many copies of ``method``'s unit the shader holds (one per light for the
    single-light units; Lyon's datapaths hold every light)."""
    return 1 if method in DATAPATHS else analysis.lights


def block_name(method):
    """The registry block of ``method``'s whole shader: unit and blend."""
    return "shader"
