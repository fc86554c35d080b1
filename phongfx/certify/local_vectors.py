"""A point light's or local viewer's vector as the table units take it, over the domain's cone.

The conventional unit with ``local_light`` (``local_viewer``) is fed per pixel the exact unit
vector toward the light (camera) rounded by the host (:mod:`phongfx.explore.compile.units`)
and normalizes it again with its own copy of the normalizer
(:func:`phongfx.golden.conventional.unit_length`: ``X·X``, even shift, seed table, each
component scaled like a cosine).  Seen from the domain's ball the vector lies in the cone of
:mod:`.cones` (its ``half`` angle about its ``axis``).  The cone is cut into sub-cones
(:data:`~phongfx.certify.datapath.SUB_CONES`), each run through the table units' normalizer on
Intervals (:mod:`.normalizer`: the host's rounding as three shared symbols, which the
normalizer's division takes out along the vector); the unit's vector ``L̂`` is their hull, each
component within its largest deviation of the reference's own unit vector ``L`` at that pixel
(the ideal normalizes the exact vector exactly), and ``|δL| = |L̂ - L|`` is bounded from their
shared symbols (the host's rounding, which the normalizer turns across the vector) and their
remainders (:func:`_length`).

Downstream, ``L̂`` enters as an exact vector over that hull, so the cosines and ``R·V`` are
bounded against ``G(L̂, V̂)`` with ``G(X, Y) = 2(N̂·X)(N̂·Y) - X·Y`` (Phong's ``R·V``, exact
algebra for any vectors), and ``G(L̂, V̂) - G(L, V) = δL·R_V + δV·R_L + 2(N̂·δL)(N̂·δV) - δL·δV``
with ``R_V``, ``R_L`` the unit reflections of ``V`` and ``L`` about ``N̂``: at most
``|δL| + |δV| + 3|δL||δV|`` (:func:`geometry_error`), whatever the directions.  Closer where it
matters, at the highlight: ``L·R_V = V·R_L = t``, Phong's ``R·V`` itself, so with ``δL`` split
along ``L`` and across it, ``|δL·R_V| <= |δL·L|·|t| + |δL|·√(1 - t²)`` (``R_V - tL`` is
``R_V``'s part across ``L``, of length ``√(1 - t²)``); at ``t`` near 1, where ``t^n`` is steep,
only the part along ``L`` counts, and the normalizer has taken the host's rounding out of it
(:func:`_along`: what is left is its table's and its own roundings'), or, tighter where the
unit rounds once, :func:`along_by_length`: the host's code already lies on the output's grid,
so the unit moves it by whole steps only, tied to the code's length.  The power's bound takes
``t``'s deviation per band of ``t`` (:mod:`.table_units`).  Symbols per
component of ``δL`` would cancel the same way only where the coefficient vectors were known;
over a cone of ``V`` they range widely and the interval products lose the cancellation.

Its bend is none: the vector is the pixel's own, not the interpolation of the span ends' unit
vectors that Lyon's datapaths take (whose bend :mod:`.cones` bounds); a host that interpolates
the un-normalized ``P - x`` (exact along a span: affine in the surface point) and scales it to
unit length by a constant gives vectors shorter than 1, whose rounding this bound does not cover.
"""

import functools
import itertools
from dataclasses import dataclass

import numpy as np

from phongfx.golden.blinn import inverse_root, scaled, shifted, unclamped_cosine
from phongfx.golden.fixed import Fixed

from .cones import spread
from .datapath import SUB_CONES
from .interval import Interval
from .normalizer import clamp, cosine, direction, inverse_length, length_cases, normal_codes, squared_length
from .sphere import cover, frame

__all__ = ["Deviation", "EXACT", "local_vector", "along_by_length", "geometry_error"]


@dataclass(frozen=True)
class Deviation:
    """Bounds on a vector's distance ``δL`` from the reference's unit ``L``: ``|δL| <= whole``
    and ``|δL·L| <= along`` (the normalizer takes the host's rounding out along ``L``: what is
    left there is its table's and its own roundings')."""

    whole: float
    along: float

    @property
    def excess(self):
        """How far ``|L + δL|`` may pass 1: ``√(1 + 2δL·L + |δL|²) <= 1 + along + whole²/2``."""
        return (self.along + self.whole ** 2 / 2) * (1 + 1e-12)


#: The deviation of a light or viewer at infinity: its code's error is the cosines' own symbol
EXACT = Deviation(0.0, 0.0)


@functools.lru_cache(maxsize=64)
def _normalized(unit, cone):
    """``(lo, hi, deviation, devs, faults)``: per component the range of the unit's normalized
    vector over ``cone``, the bounds on ``δL`` (a :class:`Deviation`) and per component on
    ``|L̂_i - L_i|``."""
    vec = unit.fmt("vec")
    pieces = cover(np.cos(cone.half), 1.0, [(0, 0)], *SUB_CONES)
    basis = frame(cone.axis)
    x = normal_codes(vec, pieces, basis)
    lo, hi, delta, along, faults = np.full(3, np.inf), np.full(3, -np.inf), 0.0, 0.0, set(x.faults)
    devs = np.zeros(3)
    for q in length_cases(squared_length(x, pieces.z)):
        k, y_max = inverse_length(unit, q)
        parts = [clamp(cosine(unit, x, k, y_max, direction(axis, vec, len(pieces)), vec), high=1.0)
                 for axis in np.eye(3)]
        for i, part in enumerate(parts):
            lo[i], hi[i] = min(lo[i], float(part.lo.min())), max(hi[i], float(part.hi.max()))
            devs[i] = max(devs[i], float(part.dev.max()))
            faults |= part.faults
        whole = _length(parts)
        delta = max(delta, float(np.max(whole)))
        along = max(along, float(np.max(_along(parts, pieces, basis, whole))))
    grow = 1 + 1e-12
    by_length = along_by_length(unit, cone)
    if by_length is not None:
        along = min(along, by_length)
    return (tuple(lo), tuple(hi), Deviation(delta * grow, min(along, delta) * grow), tuple(devs * grow),
            frozenset(faults))


def along_by_length(unit, cone):
    """A bound on ``|δL·L|`` over ``cone`` from the squared lengths the host's codes can have;
    None where some length's shift (:func:`~phongfx.golden.blinn.shifted`) is not exact.

    The host rounds ``2^f·L`` to the code ``c = 2^f·L + η`` (``|η_i| <= 1/2``), and the unit gives
    ``L̂ = (c + k)·2^-f``: each component ``min(U(c_i), 2^f)``, ``U`` one rounding of
    ``c_i·y1·2^(j-h)`` (where the shift is exact) for the ``j``, ``y1`` of ``Q = |c|²``, so that
    ``k_i = U(c_i) - c_i`` is a rounding of ``c_i`` times a constant: monotone in ``c_i``, its
    range over the cone's codes given by its two ends (the clamp can only lower it, to ``2^f -
    c_i``).  Then ``2^f·δL·L = L·η + L·k`` with ``L·η = (Q - 4^f - |η|²)/2^(f+1)`` exactly
    (``|L| = 1``): per ``Q`` (every integer of ``(2^f ± √3/2)²``) an interval, and ``L·k`` by the
    components' ranges.  The interval bound adds the unit's rounding of each component as if
    it were free; here it is tied to the length: ``c`` is already on the output's grid, so
    ``L̂`` moves off it by whole steps only, and only where ``|c_i·(y1·2^(j-h) - 1)|`` reaches
    a half.  Local mesh, 14 bits: ``L`` 7.14e-5 (8.22e-5 by intervals; 2,000,000 samples reach
    5.60e-5), ``V`` 5.29e-5 (6.75e-5; 3.53e-5)."""
    vec = unit.fmt("vec")
    f = vec.frac_bits
    size = 1 << f
    half = np.sqrt(3) / 2
    squares = np.arange(int(np.ceil((size - half) ** 2)), int(np.floor((size + half) ** 2)) + 1, dtype=np.int64)
    one = Fixed(np.zeros((1, 3), dtype=np.int64), vec)
    j, y1 = inverse_root(unit, Fixed(squares, one.dot(one).fmt), "certify |c|²")
    # k depends on a length through its (j, y1) alone, which few lengths tell apart
    _, first, which = np.unique(j * (1 << 48) + y1.raw, return_index=True, return_inverse=True)
    j, y1 = j[first], Fixed(y1.raw[first], y1.fmt)
    axis = np.asarray(cone.axis, dtype=np.float64)
    low, high = [], []
    for i in range(3):
        lo, hi = spread((axis[i], axis[i]), cone.half)
        ends = (int(np.ceil(size * lo - 0.5)), int(np.floor(size * hi + 0.5)))
        odd = ends[0] | 1 if (ends[0] | 1) <= ends[1] else ends[0]
        for c in {*ends, odd}:  # an odd code has j trailing zeros only: a shift that drops bits shows
            d = Fixed(np.full(len(j), c, dtype=np.int64), vec)
            exact, dot = shifted(unit, d, j), scaled(unit, d, j)
            if np.any(dot.raw * 2.0 ** -dot.fmt.frac_bits != exact.raw * 2.0 ** -exact.fmt.frac_bits):
                return None
        k_lo, k_hi = (unclamped_cosine(unit, Fixed(np.full(len(j), c, dtype=np.int64), vec), j, y1, vec).raw - c
                      for c in ends)
        low.append(np.minimum(np.minimum(k_lo, k_hi), size - ends[1]))
        high.append(np.maximum(k_lo, k_hi))
    # L·k is linear in k: its extremes over the box of k's ranges are at a corner, and over the
    # cone's L, for a corner u, at the support of the cap: |u|·cos(max(0, angle(u, axis) - half))
    corners = [np.stack([(high if pick else low)[i] for i, pick in enumerate(corner)], -1).astype(np.float64)
               for corner in itertools.product((0, 1), repeat=3)]
    top = np.max([_support(u, axis, cone.half) for u in corners], axis=0)[which]
    bottom = -np.max([_support(-u, axis, cone.half) for u in corners], axis=0)[which]
    along = np.maximum(top + (squares - size * size) / (2.0 * size),
                       -(bottom + (squares - size * size - 0.75) / (2.0 * size)))
    return float(along.max()) / size


def _length(parts):
    """Per sub-cone a bound on ``|δL|`` from the components' Intervals: their shared symbols
    ``T·ε`` (the host's rounding, mostly across the vector once normalized) at the worst corner
    of ``|ε_k| <= 1``, ``|T·ε|`` being convex, plus the remainders' root sum of squares."""
    terms = np.stack([p.terms for p in parts], axis=-2)  # (S, 3, symbols)
    err = np.stack([p.err for p in parts], axis=-1)  # (S, 3)
    corners = np.array(np.meshgrid(*[[-1.0, 1.0]] * terms.shape[-1], indexing="ij")).reshape(terms.shape[-1], -1)
    shared = np.sqrt(np.max(np.sum((terms @ corners) ** 2, axis=-2), axis=-1))
    return shared + np.sqrt(np.sum(err ** 2, axis=-1))


def _along(parts, pieces, basis, whole):
    """Per sub-cone a bound on ``|δL·L|``: about the sub-cone's middle direction ``u``, ``δL·u``
    from the components' shared symbols (a linear form: its largest ``Σ_k |Σ_i u_i T_ik|``) and
    remainders (``Σ_i |u_i| err_i``), and ``|δL·(L - u)| <= |δL|·|L - u|``, ``|L - u|`` at most
    the arc from the middle to a corner (half the θ cut plus half the φ cut's arc at its widest)."""
    theta, phi = pieces.theta.mean(axis=-1), pieces.phi.mean(axis=-1)
    v, e1, e2 = basis
    u = (np.cos(theta)[:, None] * v
         + np.sin(theta)[:, None] * (np.cos(phi)[:, None] * e1 + np.sin(phi)[:, None] * e2))  # (S, 3)
    terms = np.stack([p.terms for p in parts], axis=-2)  # (S, 3, symbols)
    err = np.stack([p.err for p in parts], axis=-1)  # (S, 3)
    shared = np.sum(np.abs(np.einsum("si,sik->sk", u, terms)), axis=-1)
    arc = (np.diff(pieces.theta, axis=-1)[:, 0] / 2
           + np.sin(np.minimum(pieces.theta[:, 1], np.pi / 2)) * np.diff(pieces.phi, axis=-1)[:, 0] / 2)
    return shared + np.sum(np.abs(u) * err, axis=-1) + whole * arc


def local_vector(unit, cone, count, symbols, cells=None):
    """``(L̂, deviation)``: the unit's normalized vector toward the local
    :class:`~phongfx.certify.cones.Direction` ``cone`` as an exact Interval (count, 3) over its
    hull, with ``symbols`` noise symbols (all 0), and the :class:`Deviation` bounding its distance
    ``δL = L̂ - L`` from the reference's unit vector (module docstring).  ``cells``: ``(axis (B,
    3), half (B,))``, per box a narrower cone inside ``cone`` (:mod:`.cells`), whose hull is its
    exact components' ranges widened by each component's largest deviation over ``cone``."""
    lo, hi, deviation, devs, faults = _normalized(unit, cone)
    wide = (count, 3)
    if cells is not None:
        axis, half = cells
        parts = [spread((axis[:, i], axis[:, i]), half) for i in range(3)]
        lo = np.maximum(np.stack([p[0] for p in parts], -1) - devs, lo)
        hi = np.minimum(np.stack([p[1] for p in parts], -1) + devs, hi)
    return Interval(np.broadcast_to(lo, wide), np.broadcast_to(hi, wide), 0.0, unit.fmt("vec"), faults,
                    np.zeros(wide + (symbols,))), deviation


def _support(u, axis, half):
    """(Q,) the largest ``u·L`` over unit ``L`` within ``half`` of ``axis`` (``u`` (Q, 3))."""
    length = np.linalg.norm(u, axis=-1)
    angle = np.arccos(np.clip(u @ axis / np.maximum(length, 1e-300), -1.0, 1.0))
    return length * np.cos(np.clip(angle - half, 0.0, np.pi)) * (1 + 1e-12)


def geometry_error(light, view, t=1.0, sine=1.0):
    """A bound on ``|G(L̂, V̂) - G(L, V)|`` from the :class:`Deviation` of ``L̂`` and of ``V̂``
    where Phong's ``t = R·V`` has ``|t| <= t`` and ``√(1 - t²) <= sine`` (module docstring);
    arrays broadcast."""
    def part(d):
        return np.minimum(d.whole, d.along * t + d.whole * sine)

    return (part(light) + part(view) + 3 * light.whole * view.whole) * (1 + 1e-12)
