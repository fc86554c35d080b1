"""Directions toward point lights and a local viewer, as a bound over a domain sees them.

A point light or a local camera at ``P`` is seen from a surface point ``x`` of the domain's ball
along ``unit(P - x)``, within ``α = asin(radius/|P - centre|)`` of the axis ``unit(P - centre)``
(:meth:`phongfx.scene.domain.Domain.cone`; a region's smaller ball gives a narrower cone with no
change here); at infinity the one vector, ``α = 0``.  Every widening below over-approximates:

* **Projections.**  Angles between directions obey the triangle inequality, so for ``W`` within
  ``α`` of ``W0`` the angle ``∠(N̂, W)`` is within ``α`` of ``∠(N̂, W0)``: over a box of normals
  (:mod:`.sphere`) ``N̂·W`` lies in ``cos`` of the box's angle range to ``W0`` widened by ``α``
  and clipped to ``[0, π]``, ``cos`` exact over it (:func:`spread`).  The boxes are polar about
  the viewer cone's axis ``V0``; Phong's ``R̂`` is ``V`` reflected about ``N̂``, an isometry, so
  ``R̂`` is within the viewer's ``γ`` of ``R̂0`` (``V0`` reflected) and ``R̂·L`` widens
  ``R̂0·L0`` by ``γ + α``.  ``N̂·V`` widens by ``γ`` and stays at least the domain's
  ``view_cos_min`` (which holds for every ``V``); the boxes cover ``∠(N̂, V0) <= arccos(view_cos_min)
  + γ``, or ``90° + β + ∠(V0, z)`` when less (a mesh's normals are within ``90° + β`` of the
  view axis ``z``, :mod:`phongfx.scene.domain`).
* **The hardware's L and V** (Lyon 1993, "local viewer"; :mod:`phongfx.golden.datapath`): the
  host encodes the span ends' unit vectors ``l0 = unit(P - x0)``, ``l1 = unit(P - x1)``, the
  LIRP takes ``L' = (1-a)·l0 + a·l1`` with the pixel's ``a``, and ``direction_normalize``
  scales it by ``g``.  Span ends lie in the ball, at most ``ℓ = min(max_span_length, 2·radius)``
  apart, each at least ``D = |P - centre| - radius`` from ``P``, so (``d_i = P - x_i``,
  ``r_i = |d_i|``): ``|l1 - l0| <= |d1 - d0|/√(r0·r1) <= ℓ/D`` (and ``<= 2 sin α``), the
  chord of the LIRP's error (:func:`phongfx.certify.datapath.front`) and ``|L'| >=
  √(1 - chord²/4)``.  ``L'`` points along ``P - x'`` with ``x' = (1-b)x0 + b·x1``,
  ``b - a = a(1-a)(r0 - r1)/((1-a)r1 + a·r0)``, against the pixel's ``x = (1-a)x0 + a·x1``.
  With ``e = x1 - x0``, ``d = P - x`` at the angle ``φ`` to ``e``: ``d0 = d + a·e``,
  ``d1 = d - (1-a)e``, so ``r0² - r1² = 2|d|ℓ cos φ + (2a-1)ℓ²``, and the angle between ``d``
  and ``d' = d - (b-a)e`` has ``sin = |b-a|·ℓ sin φ/|d'|``, at most
  ``a(1-a)ℓ²(|d| + |2a-1|ℓ)/((r0 + r1)·D²)``; with ``|d| <= max r_i <= min r_i + ℓ``,
  ``r_i >= D`` and ``R = |P - centre| + radius``, ``|d|/(r0 + r1) <= ρ = min(R/(R + D),
  (D + ℓ)/(2D + ℓ))``, and ``a(1-a) <= 1/4``, ``a(1-a)|2a-1| <= 1/(6√3) < 0.0963``:
  ``sin <= (ℓ/D)²·(ρ/4 + 0.0963·ℓ/(2D))``, the
  ``bend`` as a chord (when ``α <= 45°``, so the angle is below 90°; else ``2 sin α``).  The
  normalizer's ideal gives ``s·unit(L')``, ``s = g(|L'|²)|L'|``
  (:func:`~phongfx.certify.approximation.scale_range`), within ``max|s - 1| + bend`` of
  ``L_ref``: added to the hardware's deviation, it makes the hardware's L a deviation from the
  reference's own ``L_ref``, and the ideal datapath downstream sees the exact unit vectors of
  the cone.  The cone is
  cut into sub-cones, each run through the golden normalizer on Intervals; the hardware's L is
  their hull, its deviation their largest (no shared symbol: its errors are its own),
  :func:`phongfx.certify.datapath.interpolated`.
"""

import math
from dataclasses import dataclass

import numpy as np

from .approximation import scale_range
from .cells import root, toward
from .sphere import cos_range, frame, product, projection

__all__ = ["Direction", "Directions", "at_infinity", "directions", "cone_why_not", "spread", "between",
           "reflection_range"]

@dataclass(frozen=True)
class Direction:
    """Light or viewer directions: within ``half`` (radians) of the unit ``axis``; a local one
    (``local``) is interpolated by the hardware with span-end chords up to ``chord`` and its
    interpolated direction within ``bend`` of the reference's (module docstring)."""

    axis: tuple
    half: float = 0.0
    local: bool = False
    chord: float = 0.0
    bend: float = 0.0


def _local(domain, positions):
    """The :class:`Direction` toward a point light or local camera at ``positions`` (one, or a
    camera path's): one cone about the mean of the domain's cones' axes (:meth:`Domain.cone
    <phongfx.scene.domain.Domain.cone>`) holding every one of them (:func:`.cells.toward`)."""
    centre, radius = np.asarray(domain.ball[0], dtype=np.float64), float(domain.ball[1])
    positions = [np.asarray(p, dtype=np.float64) for p in positions]
    offsets = [p - centre for p in positions]
    # the cell that holds the whole ball sees them as the ball does
    axes, halves = toward(domain, root(domain, 1), positions)
    axis, half = axes[0], float(halves[0])
    near = min(float(np.linalg.norm(d)) for d in offsets) - radius
    far = max(float(np.linalg.norm(d)) for d in offsets) + radius
    span = min(float(domain.max_span_length), 2 * radius)
    cap = 2 * math.sin(min(half, math.pi / 2))
    chord = min(span / near, cap)
    # sin of the bend (module docstring); as a chord when the angle is below 90°
    ratio = min(far / (far + near), (near + span) / (2 * near + span))
    sine = span * span / (near * near) * (ratio / 4 + 0.0963 * span / (2 * near))
    bend = 2 * math.sin(math.asin(sine) / 2) if sine < 1 and half <= math.pi / 4 else cap
    bend = min(bend, cap)
    return Direction(tuple(float(x) for x in axis), half, True, chord, bend)


def cone_why_not(domain):
    """Why the domain's point lights or local camera cannot be bounded (None when they can):
    one inside the objects' ball sees them from every side."""
    centre, radius = np.asarray(domain.ball[0], dtype=np.float64), float(domain.ball[1])
    for index, (kind, vector, _) in enumerate(domain.lights):
        if kind == "point" and np.linalg.norm(np.asarray(vector) - centre) <= radius * (1 + 1e-9):
            return f"the point light {index} lies inside the objects' bounding ball (radius {radius:.4g})"
    if domain.camera[0] == "point":
        for position in domain.camera_path or (domain.camera[1],):
            if np.linalg.norm(np.asarray(position) - centre) <= radius * (1 + 1e-9):
                return f"the camera at {tuple(position)} lies inside the objects' bounding ball"
    return None


class Directions:
    """The viewer's and every light's :class:`Direction` over a domain, the frame of the boxes
    (about the viewer's axis) and the projections a bound takes of them (module docstring)."""

    def __init__(self, view, lights, view_cos_min, theta_max):
        self.view, self.lights = view, tuple(lights)
        self.basis = frame(view.axis)
        self.view_cos_min, self.theta_max = float(view_cos_min), float(theta_max)

    @property
    def local(self):
        """Whether some light or the viewer is local (interpolated by the hardware)."""
        return self.view.local or any(light.local for light in self.lights)

    @property
    def cover_cos_min(self):
        """The smallest ``N̂·V0`` of the domain's normals: what :func:`~.sphere.cover` covers."""
        return math.cos(self.theta_max)

    @property
    def light_axes(self):
        return [np.asarray(light.axis, dtype=np.float64) for light in self.lights]

    def p(self, boxes):
        """``(lo, hi)`` of ``N̂·V`` per box."""
        p = projection(boxes, self.basis, self.basis[0])
        if self.view.half == 0:
            return p
        lo, hi = spread(p, self.view.half)
        return np.maximum(lo, self.view_cos_min), np.maximum(hi, self.view_cos_min)

    def q(self, boxes, index):
        """``(lo, hi)`` of ``N̂·L`` per box for light ``index``."""
        light = self.lights[index]
        return spread(projection(boxes, self.basis, self.light_axes[index]), light.half)

    def slack(self, direction, order):
        """``ε``: how far the ideal normalizer's L (V) ``s·unit(L')`` may be from the
        reference's unit vector, ``max|s - 1| + bend`` (module docstring); 0 at infinity."""
        if not direction.local:
            return 0.0
        shortest = 1.0 - direction.chord ** 2 / 4
        s = scale_range(np.array([[max(0.0, shortest), 1.0]]), order)
        return (max(abs(float(s[0][0]) - 1.0), abs(float(s[1][0]) - 1.0)) + direction.bend) * (1 + 1e-12)

    def reflected(self, boxes, s, order):
        """``(lo, hi)`` (B, 3) of the components of the ideal ``R = 2(N·V)N - V`` over ``boxes``,
        ``N = s·N̂`` (``s`` the normal's scale range), ``V`` the ideal normalizer's: ``R̂``'s
        components widened by the viewer's ``γ``, then by ``2|s² - 1|`` (``R - R̂ =
        2(s² - 1)(N̂·V)N̂``) and the viewer's :meth:`slack` (``V`` itself off unit)."""
        grow = 2 * np.maximum(np.abs(s[0] ** 2 - 1), np.abs(s[1] ** 2 - 1)) * (1 + self.slack(self.view, order))
        grow = grow + self.slack(self.view, order) * (1 + 1e-12)
        lo, hi = [], []
        for axis in np.eye(3):
            part = spread(projection(boxes, self.basis, axis, reflected=True), self.view.half)
            lo.append(part[0] - grow)
            hi.append(part[1] + grow)
        return np.stack(lo, -1), np.stack(hi, -1)

    def difference(self, boxes, s, order, index):
        """``(t, δ)`` for light ``index``: ``t = (lo, hi)`` of ``|D| = √(2(1 - c))``, ``D = R̂ - L``
        at the reference's unit ``N̂``, ``V`` and ``L`` (Figure 2), and ``δ`` bounding how far the
        ideal's ``D`` is from it: ``N = s·N̂`` moves ``R`` by ``2(s² - 1)(N̂·V)N̂``, and its own ``V``
        and ``L`` (each within its :meth:`slack`) move ``R`` and ``L`` by at most that, ``R``
        being linear in ``V`` with norm ``max(1, |2s² - 1|)``."""
        p, c = self.p(boxes), self.c(boxes, index)
        t = (np.sqrt(np.maximum(2 * (1 - c[1]), 0.0)) * (1 - 1e-12),
             np.sqrt(np.maximum(2 * (1 - c[0]), 0.0)) * (1 + 1e-12))
        s2 = (s[0] ** 2, s[1] ** 2)
        scale = 2 * np.maximum(np.abs(s2[0] - 1), np.abs(s2[1] - 1)) * np.maximum(np.abs(p[0]), np.abs(p[1]))
        gain = np.maximum(1.0, 2 * s2[1] - 1)
        delta = scale + gain * self.slack(self.view, order) + self.slack(self.lights[index], order)
        return t, delta * (1 + 1e-12)

    def c(self, boxes, index):
        """``(lo, hi)`` of Phong's ``R̂·L`` per box for light ``index``."""
        light = self.lights[index]
        return spread(projection(boxes, self.basis, self.light_axes[index], reflected=True),
                      light.half + self.view.half)


def at_infinity(basis, lights, view_cos_min):
    """The :class:`Directions` of a viewer at infinity (``basis``, :func:`~.sphere.frame` of its
    direction) and directional ``lights`` (unit vectors, taken as given)."""
    lights = [Direction(tuple(float(x) for x in light)) for light in lights]
    return Directions(Direction(tuple(float(x) for x in basis[0])), lights, view_cos_min,
                      math.acos(min(1.0, max(-1.0, view_cos_min))))


def directions(domain):
    """The :class:`Directions` of ``domain`` (:func:`cone_why_not` None)."""
    def toward(kind, vector, positions):
        if kind == "directional":  # taken as given, as the host encodes it
            return Direction(tuple(float(x) for x in vector))
        if kind == "infinity":
            return Direction(tuple(float(x) for x in frame(vector)[0]))
        return _local(domain, positions)

    view = toward(domain.camera[0], domain.camera[1], domain.camera_path or (domain.camera[1],))
    lights = [toward(kind, vector, (vector,)) for kind, vector, _ in domain.lights]
    theta = math.acos(min(1.0, max(-1.0, domain.view_cos_min))) + view.half
    if view.half and domain.face_cap_deg <= 90.0:
        tilt = math.acos(min(1.0, max(-1.0, view.axis[2])))
        theta = min(theta, math.radians(90.0 + domain.face_cap_deg) + tilt)
    return Directions(view, lights, domain.view_cos_min, min(math.pi, theta))


def spread(cosines, half):
    """``(lo, hi)`` of ``cos(t)`` for ``t`` within ``half`` of an angle whose cosine is in
    ``cosines = (lo, hi)`` (module docstring): ``cosines`` itself when ``half`` is 0 (``half`` one
    angle or one per element)."""
    if np.all(np.asarray(half) == 0):
        return cosines
    near = np.arccos(np.clip(cosines[1], -1.0, 1.0))
    far = np.arccos(np.clip(cosines[0], -1.0, 1.0))
    return cos_range(np.maximum(near - half, 0.0), np.minimum(far + half, np.pi))


def between(light, view):
    """``(lo, hi)`` of ``L·V`` for ``L`` and ``V`` in the cones ``(axis, half)`` ``light`` and
    ``view`` (one or one per box): the angle between the axes, widened by both halves."""
    (l_axis, l_half), (v_axis, v_half) = light, view
    l_axis, v_axis = np.asarray(l_axis, dtype=np.float64), np.asarray(v_axis, dtype=np.float64)
    apart = np.arccos(np.clip(np.sum(l_axis * v_axis, -1), -1.0, 1.0))
    return cos_range(np.maximum(apart - l_half - v_half, 0.0), np.minimum(apart + l_half + v_half, np.pi))


def reflection_range(ideal, q, p, lv):
    """Phong's ``R·V = 2(N̂·L)(N̂·V) - L·V`` over a box with cells: ``ideal`` (about the frame's
    ``V0``) cut to the product of the cell's ranges of ``N̂·L`` and ``N̂·V`` less its range of
    ``L·V``, ``lv`` (:func:`between`)."""
    qp = product(q, p)
    lo = np.maximum(ideal[0], 2 * qp[0] - lv[1])
    hi = np.minimum(ideal[1], 2 * qp[1] - lv[0])
    return lo, np.maximum(hi, lo)
