"""How the compiler fits each method to a scene file: the ``compile`` face of a method.

A :class:`Hooks` answers, for one kind of unit, what :mod:`phongfx.explore.compile.run`
asks: can it represent the scene, how its config is fitted to the scene (lights, local L
and V, the shininess port), its span-input layout (the raw codes of a frame, one stream per
copy), which stream values are the visible pixels, and its float form (the ``against =
"self"`` reference).  The method registry (:data:`phongfx.core.methods.METHODS`) names one
of the objects below per method; a new specular unit of the datapath takes :data:`DATAPATH`
as it is.

* Lyon's datapaths (``fig7``, ``fig8``, ``halfway``) take everything a scene has: span
  ends of N, of L and V when local (:func:`phongfx.sim.stimulus.datapath.encode`), any
  number of lights, ``n`` per pixel or fixed in the hardware (``n_const``/``m_const``).
* ``blinn`` and ``spherical`` compute Blinn's ``(N·H)^n'`` and take one copy of
  the unit per light, side by side in the shader (:func:`~phongfx.explore.compile.run.copies`).
  ``blinn`` is fed per pixel the interpolated ``N`` and the exact unit ``L`` and
  ``H = (L+V)/|L+V|`` of that pixel, so it takes point lights and a local viewer too (the
  hardware that would compute those per-pixel vectors is not in its cost);
  ``spherical`` needs directional lights and the camera at infinity along +z.  They are
  fed ``n' = 4n`` (Lyon's appendix: ``(N·H)^(4n)`` stands for ``(R·L)^n``), so their
  ``"phong"`` error includes that approximation and ``"self"`` is float ``(N̂·H)^(4n)``
  (spherical: Szirmay-Kalos's ``A^n'·cos²``).  ``spherical`` also needs mesh spans and
  one ``n`` (its per-span setup holds it).
* ``conventional`` computes Phong's own ``(R·V)^n`` with ``n`` itself (no ``4n``), one copy
  per light, fed per pixel the interpolated ``N`` and the exact unit ``L``, ``V`` of the
  pixel; for point lights (``local_light``) and a local viewer (``local_viewer``) the unit
  normalizes them again with its own normalizer (in its cost), so a host may feed any vector
  along them.  Not the interpolation of the span ends' unit vectors that Lyon's datapaths
  take (Lyon 1993, "local viewer"): that bends the direction off the pixel's own by up to
  ``(ℓ/D)²/8`` (:mod:`phongfx.certify.cones`), 0.0035 rad on the local mesh's 0.42-long spans
  2.8 from the light, which at ``n = 32`` is worth up to 1.8 levels at the outputs by itself,
  whereas the pixel's own ``P - x`` is affine along a span and interpolates exactly.  Its
  ``"self"`` is float Phong, whose backside test is the reference's, as for ``"phong"``.
* ``schlick`` has no diffuse path and ``euler``/``gouraud`` no specular one (they
  interpolate ``N·L``, Hast et al.): rejected for scenes that need the missing term.
"""

import hashlib

import numpy as np

from phongfx.core.methods import get_method
from phongfx.golden.reference import specular
from phongfx.render.mesh import shade as mesh_shade
from phongfx.scene.mesh import unit
from phongfx.scene.span_inputs import VIEWER, blinn_codes, conventional_codes, spherical_inputs
from phongfx.sim.stimulus.datapath import encode

__all__ = ["Hooks", "Datapath", "DATAPATH", "FIG8", "HALFWAY", "SPHERICAL", "DIFFUSE_ONLY", "SCHLICK", "BLINN",
           "CONVENTIONAL"]


class Hooks:
    """A unit computing one light per copy, fed the visible pixels (defaults of every hook).

    ``datapath``: one copy holds every light (Lyon's datapaths); ``n_scale``: the unit is fed
    ``n' = n_scale·n`` (4 for the ``(N·H)^n'`` units standing for ``(R·L)^n``);
    ``extra``: parameters the compiler adds to the method's own (name -> (default, range));
    ``per_pixel``: the stream is one value per visible pixel, so a pixel can be fed alone
    (a domain point, :mod:`phongfx.explore.compile.points`); ``normal_code``: the host feeds
    it the pixel's normal as a code of :meth:`normal_format` (not a per-span setup, nor
    cosines), so exhaustive enumeration can walk every normal
    (:mod:`phongfx.certify.exhaustive`).
    """

    datapath = False
    per_pixel = True
    normal_code = False
    n_scale = 1
    extra = {}

    def n_hi(self, analysis):
        return self.n_scale * analysis.n_hi

    def rejection(self, method, spec, analysis, geometries, kd, ks):
        """Why the method cannot represent the scene file ``spec`` (one sentence), or None;
        ``kd``, ``ks``: the scene's largest diffuse and specular weights."""
        return None

    def fit(self, method, config, params, analysis, light):
        """The unit's config built from the method's parameters, fitted to the scene."""
        return config

    def streams(self, method, config, geometry, n):
        """The raw input codes of each copy of the unit for one frame (shininess ``n``)."""
        raise NotImplementedError

    def visible(self, values, geometry):
        """``values`` of the stream at the frame's visible pixels."""
        return values

    def own_specular(self, method, config, params, geometry, n):
        """(lights, P) the method's float specular form at the exact vectors."""
        raise NotImplementedError

    def own_key(self, method, config, params, n):
        """What :meth:`own_specular` depends on besides the points and ``n``: two width
        points of equal keys have the same terms on the same points (computed once for a
        domain sample); None, not known (computed afresh each time)."""
        return None

    def normal_format(self, config):
        """The :class:`~phongfx.core.format.Format` of the pixel's normal code the host feeds
        a copy of the unit (``config``: one copy's), for a unit with :attr:`normal_code`."""
        raise NotImplementedError


class Datapath(Hooks):
    """A specular unit of Lyon's datapath: span ends of N, of L and V when local
    (:func:`~phongfx.sim.stimulus.datapath.encode`), any number of lights, ``n`` per pixel
    or fixed in the hardware.  Its float form is its registry entry's; the sweeps measure it
    against ``phong_form`` too (the halfway unit against Blinn's ``(N·H)^n``).  ``n_cap``:
    why the ``n`` range ends, when it is the hardware's limit."""

    datapath = True
    normal_code = True
    extra = {"order": (2, (1, 2))}

    def __init__(self, n_cap=None, phong_form="phong"):
        self.n_cap, self.phong_form = n_cap, phong_form

    def float_form(self, method, params):
        """The method's float form (its registry entry's ``float_form``) at ``params``' ``k``
        (its default when ``params`` has none)."""
        method = get_method(method)
        return method.float_form.format(k=params.get("k", method.params.get("k")))

    def rejection(self, method, spec, analysis, geometries, kd, ks):
        """Too many lights; with ``n_cap`` (why the unit's ``n`` range ends), a larger ``n``."""
        ranges = get_method(method).ranges
        top = ranges["lights"][1]
        if analysis.lights > top:
            return f"{analysis.lights} lights; the datapath takes 1..{top}"
        if self.n_cap and analysis.n_hi > ranges["n"][1]:
            return f"n up to {analysis.n_hi}; {self.n_cap}"
        return None

    def fit(self, method, config, params, analysis, light):
        norm = config.normalize.replace(order=params.get("order", 2))
        config = config.replace(normalize=norm, direction_normalize=norm,
                                local_lights=analysis.local_lights_config, local_viewer=analysis.local_viewer)
        return config.unit.fit(config, analysis.n_hi, analysis.n_lo if analysis.single_n else 0)

    def streams(self, method, config, geometry, n):
        # a shininess fixed in the hardware has no port: encode drops it
        return [encode(config.units[0], geometry.n0, geometry.n1, geometry.a, n, geometry.v0, geometry.v1,
                       list(geometry.l0), list(geometry.l1))]

    def own_specular(self, method, config, params, geometry, n):
        form = self.float_form(method, params)
        n = config.units[0].unit.applied_n(config.units[0], n)
        return np.stack([specular(form, geometry.normal, light, geometry.viewer, n) for light in geometry.light])

    def normal_format(self, config):
        """The span ends' normal format (a span of length 0 feeds one normal code)."""
        return config.lirp.fmt("vec")

    def own_key(self, method, config, params, n):  # the form, at the shininess the hardware applies
        applied = np.ascontiguousarray(config.units[0].unit.applied_n(config.units[0], n), dtype=np.float64)
        return method, self.float_form(method, params), hashlib.sha1(applied.tobytes()).hexdigest()


class _Spherical(Hooks):
    """Szirmay-Kalos's unit: one copy per light fed every span pixel, one ``n`` per span."""

    n_scale = 4
    per_pixel = False  # its setup is per span: fed every span pixel, hidden ones too

    def rejection(self, method, spec, analysis, geometries, kd, ks):
        if any(g.spans is None for g in geometries):
            return "needs mesh spans (its setup is per span); the scene has Lyon's spheres"
        if analysis.local_lights:
            return "needs directional lights (one H per light and frame)"
        if analysis.local_viewer or not np.allclose(spec.camera.vector, VIEWER):
            return "needs the camera at infinity along +z (V = (0, 0, 1), one H per light and frame)"
        top = get_method(method).ranges["n"][1]
        if self.n_hi(analysis) > top:
            return f"is fed n' = 4n up to {4 * analysis.n_hi}; the unit takes 1..{top}"
        if len(spec.materials) > 1:
            return "its stream covers hidden span pixels, which have no material: the scene has several"
        if not analysis.single_n:
            return "its per-span setup holds one n; the scene has several"
        return None

    def streams(self, method, config, geometry, n):
        lo = int(4 * n.min())
        return [spherical_inputs(geometry.spans, light, lo, sub)
                for light, sub in zip(geometry.light[:, 0], config.units)]

    def visible(self, values, geometry):
        return values[geometry.spans.visible]

    def own_specular(self, method, config, params, geometry, n):
        return np.stack([mesh_shade(geometry.spans, "cos2", light=light, n=4 * float(n[0]))[1][
            geometry.spans.visible] for light in np.asarray(geometry.light)[:, 0]])


class _DiffuseOnly(Hooks):
    """Hast et al.'s units interpolate ``N·L`` only: never chosen for a scene file."""

    def rejection(self, method, spec, analysis, geometries, kd, ks):
        return (f"the {method} unit interpolates the diffuse N·L only (Hast et al.); the scene has "
                f"specular (ks > 0), peaking inside {100 * analysis.highlight_in_span:.1f}% of its "
                f"spans" if ks > 0 else f"diffuse-only scenes are not compiled for the {method} unit")


class _Schlick(Hooks):
    def rejection(self, method, spec, analysis, geometries, kd, ks):
        if kd > 0:
            return "Schlick's unit computes only the specular term; the scene has diffuse (kd > 0)"
        return None


class _PerPixel(Hooks):
    """The table units fed, per visible pixel, the interpolated ``N`` and their own vectors."""

    normal_code = True

    def fit(self, method, config, params, analysis, light):
        top = self.n_hi(analysis)
        return config.replace(n=f"{top.bit_length()}.0", n_max=top)

    def normal_format(self, config):
        return config.fmt("vec")


class _Blinn(_PerPixel):
    """Blinn's ``(N·H)^n'`` with the exact unit L and H of each pixel."""

    n_scale = 4

    def streams(self, method, config, geometry, n):
        return [blinn_codes(geometry.interpolated, light, unit(light + geometry.viewer),
                            (4 * n).astype(np.int64), sub) for light, sub in zip(geometry.light, config.units)]

    def own_specular(self, method, config, params, geometry, n):
        return np.stack([specular("blinn", geometry.normal, light, geometry.viewer, n) for light in geometry.light])

    def own_key(self, method, config, params, n):  # Blinn's form: no width changes it
        return (method,)


class _Conventional(_PerPixel):
    """Phong's own ``(R·V)^n``; a local L or V fed as interpolated, which the unit normalizes."""

    def fit(self, method, config, params, analysis, light):
        return super().fit(method, config, params, analysis, light).replace(
            local_light=analysis.light_local[light], local_viewer=analysis.local_viewer)

    def streams(self, method, config, geometry, n):
        # a local L or V is the pixel's exact unit vector, which the unit normalizes again (module
        # docstring): the normalizer is in the unit and its cost, for any length of the vector
        return [conventional_codes(geometry.interpolated, light, geometry.viewer, n.astype(np.int64), sub)
                for light, sub in zip(geometry.light, config.units)]

    def own_specular(self, method, config, params, geometry, n):
        # Phong itself: the reference's backside test (terminator_lit) is the unit's, as for every
        # unit; a gate on N̂·L here too would overrule that test's band, where the unit's exact
        # N·L > 0 on its codes may light what N̂·L <= 0 does not (the whole (R·V)^n, 37 levels
        # on Lyon's n = 1 ball)
        return np.stack([specular("phong", geometry.normal, light, geometry.viewer, n)
                         for light in np.asarray(geometry.light)])

    def own_key(self, method, config, params, n):  # Phong's form: no width changes it
        return (method,)


DATAPATH, HALFWAY = Datapath(), Datapath(phong_form="blinn")
FIG8 = Datapath(n_cap="Figure 8's m = √n takes at most 63")
SPHERICAL, DIFFUSE_ONLY, SCHLICK = _Spherical(), _DiffuseOnly(), _Schlick()
BLINN, CONVENTIONAL = _Blinn(), _Conventional()
