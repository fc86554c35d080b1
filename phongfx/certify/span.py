"""What a span of the domain can be, for the units fed once per span (Szirmay-Kalos et al. 2000;
Hast, Barrera & Bengtsson): how far apart its end normals are, how many pixels it holds, and how
far a pixel's normal on the great circle through the ends is from Phong's.

A span's end normals ``n0``, ``n1`` are unit vectors at most ``Γ`` (the domain's
``max_span_angle_deg``) apart; its pixel ``k`` of ``L`` sits at ``t = k/(L - 1)``.  Phong's
normal there is ``N̂ = unit((1 - t)·n0 + t·n1)`` (:func:`phongfx.scene.mesh.Spans.interpolated_normals`),
the spherical unit's the slerp ``N_s(t)``, at angle ``t·γ`` from ``n0`` on the same great
circle (Szirmay-Kalos equation 17: ``A·cos(tγ - φ) = N_s·V``).  ``N̂`` is at angle
``ω(t) = atan2(t·sin γ, 1 - t + t·cos γ)``, so the two are ``|ω(t) - tγ|`` apart, and
``∂(ω - tγ)/∂γ = -t(1 - t)(1 - 2t)(1 - cos γ)/|(1 - t)n0 + t·n1|²``: for ``t <= 1/2`` the gap
only grows with ``γ`` (and ``t -> 1 - t`` mirrors it), so its largest over the domain is
:func:`slerp_gap` at ``γ = Γ``, one variable.
"""

import math

import numpy as np

from phongfx.scene.geometry import scene_mesh
from phongfx.scene.mesh import fit_scale

__all__ = ["slerp_gap", "max_pixels", "widen"]


def slerp_gap(angle_deg, cells=1 << 16):
    """A bound (radians) on the angle between the slerp ``N_s(t)`` and Phong's ``N̂(t)`` over
    every span whose ends are at most ``angle_deg`` apart (module docstring): the gap at ``Γ``
    on ``cells`` points of ``t ∈ [0, 1/2]``, plus half a cell times its largest slope in
    ``t``, ``sin Γ/cos²(Γ/2) + Γ`` (``|(1 - t)n0 + t·n1| >= cos(Γ/2)``); inf at 180°."""
    gamma = math.radians(angle_deg)
    if gamma >= math.pi:
        return math.inf
    t = np.linspace(0.0, 0.5, cells + 1)
    gap = np.abs(np.arctan2(t * math.sin(gamma), 1 - t + t * math.cos(gamma)) - t * gamma)
    slope = math.sin(gamma) / math.cos(gamma / 2) ** 2 + gamma
    return float(gap.max()) + 0.25 / cells * slope + 1e-12


def max_pixels(spec, domain):
    """The most pixels a span of the scene ``spec`` can hold under ``domain``'s poses: its pixel
    centres lie inside one triangle's run on a scanline, at most the longest edge
    (``domain.max_span_length``) times the rasterizer's scale (:func:`~phongfx.scene.mesh.fit_scale`,
    the same under every rotation about the origin) long, so ``L - 1 <= that``."""
    mesh, _ = scene_mesh(spec)
    scale = fit_scale(mesh, spec.output.width, spec.output.height)
    return int(math.floor(domain.max_span_length * scale * (1 + 1e-12))) + 1


def widen(cosines, angle):
    """``(lo, hi)`` of ``W·X`` for every unit ``X`` within ``angle`` of a unit ``N`` whose
    ``W·N`` (``W`` unit) lies in ``cosines = (lo, hi)``."""
    far = np.minimum(np.pi, np.arccos(np.clip(cosines[0], -1, 1)) + angle)
    near = np.maximum(0.0, np.arccos(np.clip(cosines[1], -1, 1)) - angle)
    return np.cos(far) - 1e-14, np.cos(near) + 1e-14
