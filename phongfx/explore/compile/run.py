"""How each method of :data:`phongfx.core.methods.METHODS` shades a scene file's frame.

The compiler (:mod:`phongfx.compiler.compile`) asks, per method: can it represent the scene
(:func:`rejection`), what is its whole shader at given widths (:func:`build`: the unit,
:func:`unit_config`, and the hardware blend of the scene's constants to ``r``, ``g``,
``b``), what are a frame's raw input codes (:func:`frame_inputs`, the same stream the RTL
check drives), and which pixels its ``r``, ``g``, ``b`` codes are (:func:`frame_codes`).
:func:`own_specular` is the method's float form (the ``against = "self"`` reference).

What differs between methods is their ``compile`` face in the method registry
(:mod:`phongfx.explore.compile.units`), which says how each kind of unit is fed and fitted.
"""

import numpy as np

from phongfx.config import MAX_PIPELINE, BlendConfig, ShaderConfig
from phongfx.config.shader import intervals, unit_terms
from phongfx.core.methods import get_method
from phongfx.core.methods import METHODS

__all__ = ["EXTRA", "COEF_DEFAULT", "ARCHITECTURE", "hooks", "is_datapath", "per_pixel", "rejection", "unit_config",
           "build", "architectures",
           "frame_inputs", "visible", "frame_codes", "own_specular", "own_key", "block_name", "copies"]

#: Fraction bits of the blend's constants (``coef``) at a method's defaults: their rounding
#: moves a pixel by at most (2·lights + 1)·2^-(coef+1) levels before its own rounding.
COEF_DEFAULT = 8
#: The parameter the compiler adds to every method's own: the blend's ``coef``; a method's
#: hooks add theirs (the normalizers' order, g1 = 1, g2 = 2, for Lyon's datapaths).
EXTRA = {"coef": (COEF_DEFAULT, (0, 16))}


def hooks(method):
    """The compiler's :class:`~phongfx.explore.compile.units.Hooks` of ``method`` (its
    ``compile`` face in the method registry)."""
    return get_method(method).load("compile")


def is_datapath(method):
    """Whether ``method`` is a specular unit of Lyon's datapath (one copy holds every light)."""
    return hooks(method).datapath


def per_pixel(method):
    """Whether ``method``'s stream is one value per visible pixel (a domain point can be fed
    alone), not one per span pixel."""
    return hooks(method).per_pixel


def extra(method):
    """``{name: (default, range)}`` of the parameters the compiler adds to ``method``'s own."""
    return {**EXTRA, **hooks(method).extra}


def rejection(method, spec, analysis, geometries):
    """Why ``method`` cannot represent the scene (one sentence), or None when it can."""
    kd = max(float(np.max(g.kd, initial=0)) for g in geometries)
    ks = max(float(np.max(g.ks, initial=0)) for g in geometries)
    return hooks(method).rejection(method, spec, analysis, geometries, kd, ks)


def unit_config(method, params, analysis, light=None):
    """The shading unit's config of ``method`` at ``params`` (the method's own and
    :func:`extra`), fitted to the scene: lights, local L/V (each light on its own), ``n``
    format narrowed to the scene's largest ``n``, ``n`` fixed in the hardware for a single
    ``n``.  ``light``: the light of a copy of a one-light unit (its L local or not)."""
    spec = METHODS[method]
    own = {k: v for k, v in params.items() if k in spec.params}
    if is_datapath(method):
        own["lights"] = analysis.lights
    return hooks(method).fit(method, spec.build(spec.resolve(own)), params, analysis, light)


#: The architecture :func:`build` takes when given none: depth 0, one pixel per clock, the
#: light-independent inputs shared (:class:`~phongfx.config.ShaderConfig`).
ARCHITECTURE = {"pipeline": 0, "interval": 1, "share": True}


def _architecture(architecture):
    """``architecture`` with :data:`ARCHITECTURE`'s defaults for what it leaves out; an
    unknown key is a ValueError naming it."""
    unknown = sorted(set(architecture or {}) - set(ARCHITECTURE))
    if unknown:
        raise ValueError(f"architecture keys must be among {', '.join(ARCHITECTURE)}, not {', '.join(unknown)}")
    return {**ARCHITECTURE, **(architecture or {})}


def build(method, params, analysis, architecture=None):
    """The whole shader of ``method`` at ``params``: its unit (one copy, or one per light
    for a one-light unit, :func:`unit_config`) and the blend of the scene's constants
    (:class:`~phongfx.config.BlendConfig`: ``coef`` fraction bits, the scene's output bits).

    ``architecture``: ``{"pipeline": 0..4, "interval": int, "share": bool}`` (missing keys
    and None: :data:`ARCHITECTURE`), one of :func:`architectures`.  ``pipeline`` is the
    depth of the unit(s) and of the blend; a unit without a depth (the conventional unit,
    pipelined by hand; Blinn's, Schlick's and the spherical unit) keeps its own and only the
    blend takes it.  ``interval`` and ``share`` are the :class:`~phongfx.config.ShaderConfig`
    fields: the lights computed in ``interval`` clocks, the light-independent inputs once."""
    arch = _architecture(architecture)
    depth = arch["pipeline"]
    lights = range(copies(method, analysis))
    units = tuple(unit_config(method, params, analysis, light) for light in lights)
    if depth:
        units = tuple(unit.replace(pipeline=depth) if hasattr(unit, "pipeline") else unit for unit in units)
    block = METHODS[method].block
    diff, _, spec = unit_terms(block, units[0])[0]
    outputs = units[0].outputs
    blend = BlendConfig(lights=analysis.lights, diff=str(outputs[diff][0]) if diff else "",
                        spec=str(outputs[spec][0]), coef_frac=params.get("coef", COEF_DEFAULT),
                        bits=analysis.bits, ambient=analysis.ambient,
                        diffuse=analysis.diffuse if diff else _zeros(analysis.diffuse),
                        specular=analysis.specular, gate=diff is not None,
                        pipeline=max(depth, getattr(units[0], "pipeline", 0)))
    return ShaderConfig(unit=block, units=units, blend=blend, share=arch["share"], interval=arch["interval"])


def architectures(method, analysis):
    """The architectures :func:`build` can give ``method`` for the scene ``analysis``, each
    a dict of :data:`ARCHITECTURE`'s keys, share always True: every depth ``0..4`` (the
    blend's, and the unit's where it has one) × every interval of
    :func:`~phongfx.config.shader.intervals` whose light groups are legal (lights that share
    one physical unit alike: a point light and a directional one of the conventional unit
    cannot take turns on one copy).  Interval 1, depth 0 first."""
    legal = []
    for interval in intervals(analysis.lights):
        try:
            build(method, {}, analysis, {"interval": interval})
        except ValueError:
            continue
        legal.append(interval)
    return [{"pipeline": depth, "interval": interval, "share": True}
            for interval in legal for depth in range(MAX_PIPELINE + 1)]


def _zeros(nested):
    """``nested`` (per material, per light, RGB) with every value 0."""
    return tuple(tuple((0.0, 0.0, 0.0) for _ in material) for material in nested)


def frame_inputs(method, config, geometry, n):
    """Raw shader input codes of one frame with per-pixel shininess ``n`` (visible pixels;
    every span pixel for the units fed per span): each copy's stream side by side, the
    shared inputs (:attr:`~phongfx.config.ShaderConfig.shared`) once, and the pixel's
    material."""
    streams = hooks(method).streams(method, config, geometry, n)
    raw = {}
    for copy, stream in enumerate(streams):
        for name, value in stream.items():  # a shared input (the same in every stream) once
            raw.setdefault(config.port_name(copy, name), value)
    if "material" in config.inputs:
        raw["material"] = np.asarray(geometry.material, dtype=np.int64)
    return raw


def visible(method, values, geometry):
    """``values`` (count,) of the shader's stream at the frame's visible pixels (P,): the
    stream is those pixels, except the spherical unit's, which is every span pixel."""
    return hooks(method).visible(np.asarray(values), geometry)


def frame_codes(method, outputs, geometry):
    """(P, 3) the ``r``, ``g``, ``b`` codes of the frame's visible pixels from the shader's
    raw ``outputs``."""
    return np.stack([visible(method, outputs[name], geometry) for name in "rgb"], axis=-1)


def own_specular(method, config, params, geometry, n):
    """(lights, P) the method's float specular form at the exact vectors (``"self"``);
    ``config`` the shader's."""
    return hooks(method).own_specular(method, config, params, geometry, n)


def own_key(method, config, params, n):
    """What :func:`own_specular` depends on besides the points and ``n`` (equal keys, equal
    terms on the same points), or None when not known."""
    return hooks(method).own_key(method, config, params, n)


def copies(method, analysis):
    """How many copies of ``method``'s unit the shader holds (one per light for the
    single-light units; Lyon's datapaths hold every light)."""
    return 1 if is_datapath(method) else analysis.lights


def block_name(method):
    """The registry block of ``method``'s whole shader: unit and blend."""
    return "shader"
