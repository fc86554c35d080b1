"""The highlight scan: a witness search's look at Phong's peaks, where ``t^n`` is steepest.

A specular term's error is mostly its cosine's deviation times the slope of ``t^n``, which
is largest at the highlight's peak: ``t = R·V = 1``, where the normal bisects the light and
the viewer (``N = H = unit(L + V)``; Lyon 1993, "Background": the halfway vector).  A uniform
sample of the domain puts few points there.  Where a point light or a local viewer makes ``L``
and ``V`` depend on the surface point, the unit's own roundings of them (the host's codes,
normalized again) differ from point to point, and whether they line up at the peak is a
matter of the position, which the climb's small steps rarely change by enough.  So, in two
steps, each through the design's golden model (``evaluate``):

1. **positions**: the worst points of the witness's fresh sample (positions where something
   already goes wrong), each at its material's largest ``n`` (the steepest ``t^n``) with its
   normal turned to ``H`` of one of the lights (chosen per point), measured there; the
   :data:`KEEP` worst kept;
2. **normals**: at each of those, as many normals drawn uniformly in the cap about ``H``
   where ``t^n`` is steepest (``t >= 1 - STEEP/n``, ``t = cos(2ε)`` for a normal ``ε`` off
   ``H``): the worst of them join the climb's starts (:mod:`.climb`).

Every point stays in the domain (:func:`~phongfx.explore.compile.climb.errors`): the span's
ends both take the turned normal (a span of one normal), and a point the domain does not
hold is dropped.  On the local mesh's chosen design (conventional, 14-bit vectors) the
witness rose from 0.776 to 0.826 levels with these starts: at the positions kept the
renormalized ``L`` and ``V`` both fall short along themselves (``δL·L + δV·V`` of -5e-5 to
-7e-5, where over the ball it ranges from -8.5e-5 to +7.4e-5), which lowers ``t`` at the
peak by as much.
"""

import numpy as np

from phongfx.scene.mesh import unit

from .climb import errors, points, state_of
from .points import worst_index

__all__ = ["KEEP", "STEEP", "cap_angle", "scan"]

#: Positions kept for step 2.
KEEP = 8
#: The cap of step 2: ``t >= 1 - STEEP/n``, where ``n·t^(n-1)`` is at least ``e^-STEEP``-ish of its peak.
STEEP = 0.5


def cap_angle(n):
    """The angle ``ε`` of a normal off ``H`` at which ``t = cos(2ε)`` falls to ``1 - STEEP/n``
    (radians, per ``n``)."""
    return np.arccos(np.clip(1.0 - STEEP / np.asarray(n, dtype=np.float64), -1.0, 1.0)) / 2


def _peak_normals(g, light):
    """(P, 3) ``H = unit(L + V)`` at each point of ``g`` for its light ``light`` (P,)."""
    rows = np.arange(len(g.a))
    return unit(np.asarray(g.light)[light, rows] + np.asarray(g.viewer))


def _turned(s, normals):
    """The state ``s`` with both span ends' normals ``normals`` (the pixel's normal too)."""
    s = s.rows(np.arange(len(s)))
    s.n0, s.n1 = normals, normals.copy()
    return s


def scan(evaluate, positions, domain, rgb, bits, seed, count, normals):
    """``(starts, evaluated)``: the ``count`` worst points of the two steps (module docstring)
    as a :class:`~phongfx.scene.geometry.FrameGeometry` (None without a light) and how many
    points were measured: step 1 at the domain points ``positions`` (their own positions,
    spans and materials), step 2 ``normals`` normals in all, shared among the :data:`KEEP`
    worst.  ``evaluate``: ``g -> (levels, unrounded)``; ``seed``: of the lights' choice and
    the normals."""
    if not domain.lights or not len(positions.a):
        return None, 0
    rng = np.random.default_rng([seed, 5])
    s = state_of(positions, domain)
    # the steepest t^n of each point's material: its largest admissible n
    s.n_index = np.array([len(values) - 1 for _, values in domain.materials], dtype=np.int64)[s.material]
    light = rng.integers(len(domain.lights), size=len(s))
    peak = _peak_normals(points(s, domain, rgb, bits), light)
    # a light straight behind the viewer has no H: the point keeps its normal (and likely drops out)
    s = _turned(s, np.where(np.isfinite(peak), peak, s.n0))
    e, u = errors(evaluate, s, domain, rgb, bits)
    found = np.isfinite(u)
    if not np.any(found):
        return None, len(s)
    keep = np.flatnonzero(found)[worst_index(e[found], u[found], KEEP)]
    # step 2: normals about each kept position's H, uniform on the cap's area
    each = max(normals // len(keep), 1)
    rows = np.repeat(keep, each)
    around = s.rows(rows)
    peak = around.n0
    n = [values[i] for (_, values), i in zip((domain.materials[m] for m in s.material[keep]), s.n_index[keep])]
    angle = np.repeat(cap_angle(n), each) * np.sqrt(rng.random(len(rows)))
    side = unit(np.cross(peak, rng.normal(size=peak.shape)))
    around = _turned(around, unit(peak * np.cos(angle)[:, None] + side * np.sin(angle)[:, None]))
    e2, u2 = errors(evaluate, around, domain, rgb, bits)
    ok = np.flatnonzero(np.isfinite(u2))
    if not len(ok):
        return None, len(s) + len(around)
    worst = ok[worst_index(e2[ok], u2[ok], count)]
    return points(around.rows(worst), domain, rgb, bits), len(s) + len(around)
