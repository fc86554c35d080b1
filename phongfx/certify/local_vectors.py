"""A point light's or local viewer's vector as the table units take it, over the domain's cone.

The conventional unit with ``local_light`` (``local_viewer``) is fed per pixel the exact unit
vector toward the light (camera) rounded by the host (:mod:`phongfx.explore.compile.units`)
and normalizes it again with its own copy of the normalizer
(:func:`phongfx.golden.conventional.unit_length`: ``X·X``, even shift, seed table, each
component scaled like a cosine).  Seen from the domain's ball the vector lies in the cone of
:mod:`.cones` (its ``half`` angle about its ``axis``).  The cone is cut into sub-cones
(:data:`~phongfx.certify.datapath.SUB_CONES`), each run through the table units' normalizer on
Intervals (:mod:`.normalizer`: the host's rounding as three shared symbols, which the
normalizer's division takes out along the vector); the unit's vector is their hull, each
component within its largest deviation of the reference's own unit vector at that pixel (the
ideal normalizes the exact vector exactly).  Downstream that deviation is a noise symbol per
component (:data:`~phongfx.certify.normalizer.LIGHT`, :data:`~phongfx.certify.normalizer.VIEW`),
so that ``R·V = 2(N̂·L)(N̂·V) - L·V`` cancels what it cancels: an error ``δL`` enters
``2c_L·c_V`` as ``2(N̂·δL)(N̂·V)`` and ``L·V`` as ``δL·V``, ``δL`` against ``V`` reflected about
``N̂`` in all.

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

__all__ = ["local_vector"]


@functools.lru_cache(maxsize=64)
def _normalized(unit, cone):
    """``(lo, hi, dev, faults)`` per component of the unit's normalized vector over ``cone``."""
    vec = unit.fmt("vec")
    pieces = cover(np.cos(cone.half), 1.0, [(0, 0)], *SUB_CONES)
    x = normal_codes(vec, pieces, frame(cone.axis))
    lo, hi, dev, faults = np.full(3, np.inf), np.full(3, -np.inf), np.zeros(3), set(x.faults)
    for q in length_cases(squared_length(x, pieces.z)):
        k, y_max = inverse_length(unit, q)
        for i, axis in enumerate(np.eye(3)):
            part = clamp(cosine(unit, x, k, y_max, direction(axis, vec, len(pieces)), vec), high=1.0)
            lo[i], hi[i] = min(lo[i], float(part.lo.min())), max(hi[i], float(part.hi.max()))
            dev[i] = max(dev[i], float(part.dev.max()))
            faults |= part.faults
    return tuple(lo), tuple(hi), tuple(dev * (1 + 1e-12)), frozenset(faults)


def local_vector(unit, cone, count, slot, symbols):
    """The unit's normalized vector toward the local :class:`~phongfx.certify.cones.Direction`
    ``cone`` as an Interval (count, 3) against the reference's unit vector (module docstring):
    its deviation per component on the noise symbols ``slot .. slot + 2`` of ``symbols``."""
    lo, hi, dev, faults = _normalized(unit, cone)
    terms = np.zeros((count, 3, symbols))
    terms[:, np.arange(3), slot + np.arange(3)] = dev
    wide = (count, 3)
    return Interval(np.broadcast_to(lo, wide), np.broadcast_to(hi, wide), 0.0, unit.fmt("vec"), faults, terms)
