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
``|δL| + |δV| + 3|δL||δV|`` (:func:`geometry_error`), whatever the directions.  Symbols per
component of ``δL`` would cancel the same way only where the coefficient vectors were known;
over a cone of ``V`` they range widely and the interval products lose the cancellation.

Its bend is none: the vector is the pixel's own, not the interpolation of the span ends' unit
vectors that Lyon's datapaths take (whose bend :mod:`.cones` bounds); a host that interpolates
the un-normalized ``P - x`` (exact along a span: affine in the surface point) and scales it to
unit length by a constant gives vectors shorter than 1, whose rounding this bound does not cover.
"""

import functools

import numpy as np

from .datapath import SUB_CONES
from .interval import Interval
from .normalizer import clamp, cosine, direction, inverse_length, length_cases, normal_codes, squared_length
from .sphere import cover, frame

__all__ = ["local_vector", "geometry_error"]


@functools.lru_cache(maxsize=64)
def _normalized(unit, cone):
    """``(lo, hi, delta, faults)``: per component the range of the unit's normalized vector over
    ``cone``, and the bound on ``|δL|``."""
    vec = unit.fmt("vec")
    pieces = cover(np.cos(cone.half), 1.0, [(0, 0)], *SUB_CONES)
    x = normal_codes(vec, pieces, frame(cone.axis))
    lo, hi, delta, faults = np.full(3, np.inf), np.full(3, -np.inf), 0.0, set(x.faults)
    for q in length_cases(squared_length(x, pieces.z)):
        k, y_max = inverse_length(unit, q)
        parts = [clamp(cosine(unit, x, k, y_max, direction(axis, vec, len(pieces)), vec), high=1.0)
                 for axis in np.eye(3)]
        for i, part in enumerate(parts):
            lo[i], hi[i] = min(lo[i], float(part.lo.min())), max(hi[i], float(part.hi.max()))
            faults |= part.faults
        delta = max(delta, float(np.max(_length(parts))))
    return tuple(lo), tuple(hi), delta * (1 + 1e-12), frozenset(faults)


def _length(parts):
    """Per sub-cone a bound on ``|δL|`` from the components' Intervals: their shared symbols
    ``T·ε`` (the host's rounding, mostly across the vector once normalized) at the worst corner
    of ``|ε_k| <= 1``, ``|T·ε|`` being convex, plus the remainders' root sum of squares."""
    terms = np.stack([p.terms for p in parts], axis=-2)  # (S, 3, symbols)
    err = np.stack([p.err for p in parts], axis=-1)  # (S, 3)
    corners = np.array(np.meshgrid(*[[-1.0, 1.0]] * terms.shape[-1], indexing="ij")).reshape(terms.shape[-1], -1)
    shared = np.sqrt(np.max(np.sum((terms @ corners) ** 2, axis=-2), axis=-1))
    return shared + np.sqrt(np.sum(err ** 2, axis=-1))


def local_vector(unit, cone, count, symbols):
    """``(L̂, delta)``: the unit's normalized vector toward the local
    :class:`~phongfx.certify.cones.Direction` ``cone`` as an exact Interval (count, 3) over its
    hull, with ``symbols`` noise symbols (all 0), and the bound ``delta`` on its distance
    ``|δL|`` from the reference's unit vector (module docstring)."""
    lo, hi, delta, faults = _normalized(unit, cone)
    wide = (count, 3)
    return Interval(np.broadcast_to(lo, wide), np.broadcast_to(hi, wide), 0.0, unit.fmt("vec"), faults,
                    np.zeros(wide + (symbols,))), delta


def geometry_error(light, view):
    """A bound on ``|G(L̂, V̂) - G(L, V)|`` from ``|δL| <= light`` and ``|δV| <= view`` (module
    docstring)."""
    return (light + view + 3 * light * view) * (1 + 1e-12)
