"""What a scene makes a shading datapath do.

:func:`analyse` reads a :class:`~phongfx.scene.file.SceneSpec` and its frames
(:func:`phongfx.scene.geometry.frames`) and says what varies per pixel, which is what
the compiler (:mod:`phongfx.compiler.compile`) may leave out:

* N always varies; L only if some light is local, V only if the camera is local
  (Lyon 1993, "Local lights and viewer": otherwise no L/V interpolator or normalizer);
* which lights are local, one by one (only those get an L interpolator and normalizer);
* the number of lights and the set or range of shininess ``n``;
* the blend's constants: per material ``ka·M``, and per light ``kd·M·L`` and ``ks·M·L``
  (``M`` the material's RGB colour, ``L`` the light's RGB intensity), which the hardware
  blend multiplies by as constants (:class:`~phongfx.config.BlendConfig`);
* the largest angle between the two end normals of any span over all frames, and the
  shortest interpolated un-normalized normal ``|N'|`` (``N' = (1-a)N0 + a·N1``): it is
  the normalizer's input range, and it decides how far Lyon's first-order ``g1`` stays
  from ``1/√z`` (``z = |N'|²``; ``g1(z) = (3 - z)/2`` and ``g2`` adds ``(1-z)²/2``,
  Lyon's "Approximate Normalization");
* how often the specular maximum falls strictly inside a span above the visibility
  threshold ``c^n >= 0.5/levels``: when never, a scanline unit that interpolates between
  span ends (Gouraud, Euler) cannot miss a highlight.

The g1/g2 choice itself is *measured* by the compiler (the normalizer's order is one of
the parameters its width search lowers); :attr:`Analysis.g1_error` and ``g2_error`` are
the predicted relative length errors at the shortest ``|N'|``, for the manifest.
"""

from dataclasses import asdict, dataclass

import numpy as np

from phongfx.scene.mesh import unit

__all__ = ["Analysis", "analyse", "span_ends_angle", "shortest_normal", "highlight_in_span"]


@dataclass(frozen=True)
class Analysis:
    """The decisions of :func:`analyse` (module docstring); :meth:`as_dict` is JSON-able."""

    local_lights: bool
    local_viewer: bool
    light_local: tuple     # per light: a point light (True) or a directional one
    lights: int
    n_values: tuple
    n_lo: int
    n_hi: int
    single_n: bool
    max_span_angle_deg: float
    min_normal_length: float
    g1_error: float
    g2_error: float
    highlight_in_span: float
    spans: int
    pixels: int
    bits: int = 8
    ambient: tuple = ()    # per material (r, g, b)
    diffuse: tuple = ()    # per material, per light (r, g, b)
    specular: tuple = ()

    @property
    def scanline_may_suffice(self):
        """No visible highlight peaks strictly inside a span (Gouraud/Euler need not miss one)."""
        return self.highlight_in_span == 0.0

    @property
    def local_lights_config(self):
        """A datapath's ``local_lights``: one switch when every light is alike, else one per light."""
        kinds = set(self.light_local)
        return kinds.pop() if len(kinds) == 1 else tuple(self.light_local)

    def as_dict(self):
        out = asdict(self)
        out["n_values"] = list(self.n_values)
        out["scanline_may_suffice"] = self.scanline_may_suffice
        return out


def span_ends_angle(geometry):
    """Largest angle (degrees) between the end normals ``n0``, ``n1`` of any span of a frame."""
    if not len(geometry.n0):
        return 0.0
    cos = np.sum(unit(geometry.n0) * unit(geometry.n1), axis=-1)
    return float(np.degrees(np.arccos(np.clip(cos.min(), -1.0, 1.0))))


def shortest_normal(geometry):
    """Smallest ``|(1-a)·n0 + a·n1|`` over the pixels of a frame (1.0 for none)."""
    if not len(geometry.a):
        return 1.0
    return float(np.linalg.norm(geometry.interpolated, axis=-1).min())


def _normalizer_errors(length):
    """Relative error ``|g(z)·√z - 1|`` of Lyon's g1 and g2 at ``z = length²``."""
    z = length * length
    g1 = (3 - z) / 2
    g2 = g1 + (1 - z) ** 2 / 2
    return abs(g1 * length - 1), abs(g2 * length - 1)


def highlight_in_span(geometry, levels):
    """(spans with a visible specular peak strictly inside, spans) of one frame.

    Per pixel and light the Phong cosine ``c = R·L`` (``R`` Phong's normal's reflection
    of the viewer); a span's peak is its largest ``c`` over its visible pixels, *inside*
    when it sits at ``0 < a < 1`` and ``c^n >= 0.5/levels`` (half a display level).
    """
    span = np.asarray(geometry.span)
    ids, index = np.unique(span, return_inverse=True)
    if not len(ids):
        return 0, 0
    normal, viewer = geometry.normal, np.asarray(geometry.viewer)
    reflect = 2 * np.sum(normal * viewer, -1, keepdims=True) * normal - viewer
    a, n = np.asarray(geometry.a, dtype=np.float64), np.asarray(geometry.n, dtype=np.float64)
    inside = np.zeros(len(ids), dtype=bool)
    for light in np.asarray(geometry.light):
        c = np.sum(reflect * light, -1)
        order = np.lexsort((-c, index))  # per span, its largest c first
        first = order[np.r_[True, index[order][1:] != index[order][:-1]]]
        peak = first[np.argsort(index[first])]
        visible = np.maximum(c[peak], 0.0) ** n[peak] >= 0.5 / levels
        inside |= visible & (a[peak] > 0) & (a[peak] < 1)
    return int(inside.sum()), len(ids)


def _per_light(materials, lights, name):
    """Per material, per light, ``k·M_c·L_c`` for the material's coefficient ``name`` (kd, ks)."""
    return tuple(tuple(tuple(getattr(m, name) * mc * lc for mc, lc in zip(m.colour, light.rgb))
                       for light in lights) for m in materials)


def analyse(spec, geometries):
    """The :class:`Analysis` of ``spec`` over its frames ``geometries``.

    :param spec: the scene, a :class:`~phongfx.scene.file.SceneSpec`.
    :param geometries: every frame of the scene, a sequence of
        :class:`~phongfx.scene.geometry.FrameGeometry` (``n`` per pixel at each material's
        lowest value).
    :returns: an :class:`Analysis`.
    """
    values = tuple(int(round(v)) for v in spec.shininess)
    if not values:
        raise ValueError("scene must have at least one shininess n, not none")
    levels = 2 ** spec.output.bits - 1
    angle = max((span_ends_angle(g) for g in geometries), default=0.0)
    length = min((shortest_normal(g) for g in geometries), default=1.0)
    inside = spans = pixels = 0
    for g in geometries:
        got, total = highlight_in_span(g, levels)
        inside, spans, pixels = inside + got, spans + total, pixels + len(g.a)
    g1, g2 = _normalizer_errors(length)
    materials = list(spec.materials.values())
    return Analysis(local_lights=bool(spec.local_lights), local_viewer=bool(spec.local_viewer),
                    light_local=tuple(light.kind == "point" for light in spec.lights),
                    bits=spec.output.bits,
                    ambient=tuple(tuple(m.ka * c for c in m.colour) for m in materials),
                    diffuse=_per_light(materials, spec.lights, "kd"),
                    specular=_per_light(materials, spec.lights, "ks"),
                    lights=len(spec.lights), n_values=values, n_lo=min(values), n_hi=max(values),
                    single_n=len(set(values)) == 1, max_span_angle_deg=angle,
                    min_normal_length=length, g1_error=float(g1), g2_error=float(g2),
                    highlight_in_span=inside / spans if spans else 0.0, spans=spans, pixels=pixels)
