"""The bounding method of the table units: conventional Phong and Blinn–Phong.

Both normalize the interpolated normal per pixel and raise a 16-bit cosine to ``n`` by log and
exp tables (Lyon 1993, "Background"; :mod:`phongfx.golden.conventional`,
:mod:`phongfx.golden.blinn`).  Per box of the domain's normals (:mod:`.sphere`), lights and
viewer at infinity:

* the cosines by :mod:`.normalizer` (Intervals with the host's rounding of ``N`` as shared
  symbols), so against the exact ``N̂·L``, ``N̂·V`` (``N̂·H`` for Blinn) each has a range and a
  deviation ``e``;
* the conventional unit's ``t = 2·c_L·c_V - L·V`` by the Interval product (the shared symbols
  cancel where ``R·V`` is flat in ``N̂``: at the highlight's peak), against Phong's
  ``R·V = 2(N̂·L)(N̂·V) - L·V`` (exact algebra, :func:`phongfx.golden.conventional.reflection`),
  then rounded to ``t`` and clamped to ``[0, 1]`` (which moves no value away from Phong's
  ``max(R·V, 0) <= 1``); Blinn's ``t`` is its clamped cosine;
* the power ``P(t, n)`` against ``t^n`` by :func:`~phongfx.certify.tables.power_bound`
  (exhaustive over the ``t`` codes the box's range meets), per case of the cosines' clamps to 1
  (where ``N̂·L`` is clamped, ``N̂`` is within ``ψ`` of ``L`` and ``R·V <= cos(β - 2ψ)``, ``β`` the
  least angle between ``L`` and ``V``: far from the highlight when they are far apart);
* with point lights or a local viewer, ``L`` and ``V`` as :mod:`.local_vectors` bounds them (their
  distance from the reference's added to ``t``'s deviation per band of ``t``, only the part along
  them counting near ``t = 1``), and the boxes also cut the surface points into cells
  (:mod:`.cells`), each with the narrower cones its points see;
* the diffuse term, the backside test and the blend as :mod:`.outputs` states them, with the
  ideal's scale ``s = 1`` (the unit normalizes exactly but for the rounding bounded here);
* where a box holds few normal codes, each through the golden model (:mod:`.codes`), which
  replaces the interval bound where lower.

The ideal is Phong itself for the conventional unit (against ``"phong"`` and ``"self"`` alike:
its ``"self"`` is Phong with the same backside test), so its approximation part is 0.  Blinn's
ideal is ``(N̂·H)^n'`` with ``n' = 4n`` (:data:`~phongfx.explore.compile.units.BLINN`), its own
``"self"``; against ``"phong"`` its distance from ``max(R·V, 0)^n`` is bounded by the two
ranges over the box (both rise with their cosine), as :mod:`.approximation` does for the
halfway unit.
"""

from dataclasses import replace
from typing import NamedTuple

import numpy as np

from phongfx.explore.compile.units import BLINN, CONVENTIONAL

from phongfx.golden.blinn import blinn
from phongfx.golden.conventional import conventional

from .branch import bound_boxes, cases, first_boxes
from .cells import meets, per_box, root, scale
from .codes import code_errors, code_ranges
from .cones import between, cone_why_not, directions, reflection_range, spread
from .figures import unit_directions_why_not
from .interval import Interval, rounding_error
from .local_vectors import EXACT, geometry_error, local_vector
from .normalizer import (SYMBOLS, clamp, cosine, cosine_range, direction, inverse_length,
                         length_cases, normal_codes, product_of, rounded, squared_length)
from .outputs import blend_errors
from .regions import limits
from .sphere import cover, product
from .tables import power_bound

__all__ = ["CODES_PER_BOX", "CODES_PER_CALL", "CELL_WEIGHT", "CELL_PATIENCE", "TableUnit", "Ranges", "CONVENTIONAL_BOUND", "BLINN_BOUND", "light_terms"]


#: A box holding at most this many normal codes is bounded code by code (:mod:`.codes`) ...
CODES_PER_BOX = 256
#: ... up to this many codes per call of the branch and bound
CODES_PER_CALL = 1 << 20
#: How a cell's angle (:mod:`.cells`) weighs against the normals' sides when a box is halved
CELL_WEIGHT = 1.0
#: Rounds of the branch and bound over which boxes with cells must stop falling before it stops
#: (:func:`~phongfx.certify.branch.bound_boxes`' ``patience``): with five sides a box is halved
#: along each of them before its children's bounds fall, and four rounds would stop it there
CELL_PATIENCE = 8


def _t(config, pre):
    """``(lo, hi, dev)`` of a cosine ``pre`` rounded to ``t`` and clamped to ``[0, 1]``."""
    t = clamp(rounded(pre, rounding_error(pre.fmt, config.fmt("t"), config.rounding)), 0.0, 1.0)
    return (t.lo, t.hi), t.dev


def _capped(c, excess=0.0):
    """The two cases of a cosine's clamp to 1 (:func:`phongfx.golden.blinn.cosine`), each with
    where it is exactly 1 (None: nowhere): where the hardware's value is at most 1, it and its
    terms as they are (its range cut at 1); where its range passes 1, also exactly 1, then within
    ``dev`` of an ideal that is at most ``1 + excess`` (no terms).  Apart, the first keeps the
    shared symbols that ``R·V`` cancels, which one clamped Interval would drop wherever its range
    meets 1."""
    over, above = c.hi > 1.0, c.lo > 1.0
    if not np.any(over):
        return [(c, None)]
    one_err = np.maximum(c.dev, excess)

    def case(one):  # exactly 1 where ``one``, with no terms there
        terms = None if c.terms is None else np.where(one[..., None], 0.0, c.terms)
        return Interval(np.where(one, 1.0, np.minimum(c.lo, 1.0)), np.where(one, 1.0, np.minimum(c.hi, 1.0)),
                        np.where(one, one_err, c.err), c.fmt, c.faults, terms), one

    # below 1 it cannot be where the whole range is over 1: there too exactly 1
    return [case(above), case(over)]


def _aligned(ideal, one, c, e, lv):
    """The ideal ``t`` range where a cosine ``c`` (raw, before its clamp) is exactly 1 (``one``):
    the hardware's value at least 1 puts ``N̂·L̂`` at least ``1 - dev`` and ``N̂·L`` at least
    ``1 - dev - e`` (``e`` the vector's distance bound), so ``N̂`` is within ``ψ`` of ``L`` and
    ``R`` (``L`` reflected about it) within ``2ψ``: ``R·V <= cos(β - 2ψ)`` for ``β`` the least
    angle between ``L`` and ``V`` (``lv`` the range of ``L·V``); the same with ``V`` for ``N̂·V``
    (``R·V = R_V·L``).  Where the two vectors are far apart, the highlight is not there."""
    if one is None:
        return ideal
    psi = np.arccos(np.clip(1.0 - c.dev - e, -1.0, 1.0))
    beta = np.arccos(np.clip(lv[1], -1.0, 1.0))
    top = np.cos(np.clip(beta - 2 * psi, 0.0, np.pi)) * (1 + 1e-12) + 1e-15
    return ideal[0], np.where(one, np.maximum(np.minimum(ideal[1], top), ideal[0]), ideal[1])


def _conventional(unit, normal, k, y_max, light, view, light_view, r):
    # against G(L̂, V̂) (module docstring of .local_vectors; L̂ = L at infinity), each Interval's
    # range cut to the geometry's exact one widened by its deviation and by |δL|, |δV| (within):
    # with a cone of L or V, interval products alone would let them wander far past it
    (d_light, d_view) = r.deviations
    near, e_light, e_view = geometry_error(d_light, d_view), d_light.whole, d_view.whole
    # N'·L̂ = |N'|(N̂·L̂), N̂·L̂ within |δL| of N̂·L
    raw_light = cosine(unit, normal, k, y_max, light, unit.fmt("cos"),
                       product(r.root, (r.q[0] - e_light, r.q[1] + e_light))).within(r.q[0] - e_light, r.q[1] + e_light)
    raw_view = cosine(unit, normal, k, y_max, view, unit.fmt("cos"),
                      product(r.root, (r.s[0] - e_view, r.s[1] + e_view))).within(r.s[0] - e_view, r.s[1] + e_view)
    cases = []
    for c_light, l_one in _capped(raw_light, d_light.excess):  # each case of the two clamps
        for c_view, v_one in _capped(raw_view, d_view.excess):
            pre = ((c_light * c_view).shift(1) - light_view).within(r.ideal[0] - near, r.ideal[1] + near)
            ideal = _aligned(_aligned(r.ideal, l_one, raw_light, e_light, r.lv), v_one, raw_view, e_view, r.lv)
            cases.append((*_t(unit, pre), ideal))
    # against G(L̂, V̂): the geometry's part (δL, δV) is added per band of t by _power
    return clamp(raw_light, high=1.0), cases


def _blinn(unit, normal, k, y_max, light, half, light_view, r):
    c_light = clamp(cosine(unit, normal, k, y_max, light, unit.fmt("out")), 0.0, 1.0)
    return c_light, [(*_t(unit, clamp(cosine(unit, normal, k, y_max, half, unit.fmt("t")), 0.0, 1.0)), r.ideal)]


def _reflected(boxes, basis, light, view):
    """Phong's ``R·V`` over each box."""
    return cosine_range(boxes, basis, light, reflected=True)


def _direct(boxes, basis, light, half):
    """``N̂·H`` over each box."""
    return cosine_range(boxes, basis, half)


#: Edges of the bands of the ideal ``t`` over which the power's bound takes the geometry's part of
#: ``t``'s deviation (:func:`~.local_vectors.geometry_error`): ``1 - t`` quartered toward 1, where
#: ``t^n`` is steep and the part across ``L`` and ``V`` fades as ``√(1 - t²)`` (halved per band)
BANDS = (-1.0, 0.0) + tuple(1.0 - 4.0 ** -k for k in range(1, 8)) + (1.0,)


def _power(unit, n_hw, ideal, dev, deviations, hardware):
    """:func:`~phongfx.certify.tables.power_bound` for an ideal ``t`` in ``ideal`` and a hardware
    ``t`` within ``dev`` of ``G(L̂, V̂)`` (or ``V̂``'s ``N̂·H``), itself within the geometry's
    bound of Phong's ``t`` for the ``deviations`` ``(δL, δV)``: over the whole range when both
    are exact (at infinity), else per band of :data:`BANDS` the range meets, each with the
    geometry's bound at its own ``|t|`` and ``√(1 - t²)``."""
    light, view = deviations
    if light.whole == 0 and view.whole == 0:
        return power_bound(unit, n_hw, ideal, dev, hardware)
    # Phong's t is a cosine: its ranges pass [-1, 1] only by their float slack
    a, b = (np.clip(np.asarray(v, dtype=np.float64), -1.0, 1.0) for v in ideal)
    bands = []
    for edge_lo, edge_hi in zip(BANDS[:-1], BANDS[1:]):
        lo, hi = np.maximum(a, edge_lo), np.minimum(b, edge_hi)
        least = np.where((lo <= 0) & (hi >= 0), 0.0, np.minimum(np.abs(lo), np.abs(hi)))
        sine = np.sqrt(np.clip(1.0 - least ** 2, 0.0, 1.0))
        bands.append(((lo, hi), dev + geometry_error(light, view, np.minimum(np.maximum(np.abs(lo), np.abs(hi)), 1.0),
                                                     sine)))
    return power_bound(unit, n_hw, (a, b), dev + geometry_error(light, view), hardware, bands)


class Ranges(NamedTuple):
    """What the geometry says of a box (B,) each: the exact ranges ``(lo, hi)`` of ``N̂·L`` (``q``),
    of the unit's other cosine ``N̂·S`` (``s``: ``V``, or Blinn's ``H``), of its ideal ``t``
    (``ideal``) and of ``L·V`` (``lv``); the :class:`~.local_vectors.Deviation` of the unit's
    ``L`` and ``S`` (``deviations``, exact at infinity) and the range of ``|N'|`` (``root``)."""

    q: tuple
    s: tuple
    ideal: tuple
    lv: tuple
    deviations: tuple
    root: tuple


def light_terms(unit, boxes, basis, vectors, ranges, specular, n_hw):
    """Per box the unit's terms for one light (B,) each: ``(e_d, d_hi, e_s, ideal_hi, hw_hi,
    faults)``, the diffuse term's deviation from ``max(N̂·L, 0)`` and its largest value, the
    specular term's deviation from the ideal ``t^n'`` and the largest ideal and hardware
    values; ``vectors`` the unit's ``(L, S, L·S)`` as Intervals against the reference's
    (``S`` its other vector, ``V`` or ``H``; a local one exact over its hull, its distance from the
    reference's bounded apart), ``ranges`` the box's :class:`Ranges`; ``specular`` the unit's
    cosine stage (:func:`_conventional`, :func:`_blinn`): the clamped ``N̂·L`` and per case of its
    clamps ``(t's hardware range, t's deviation, the ideal t's range)``, the worst case taken;
    ``n_hw`` the applied ``n'``."""
    l_code, s_code, light_view = vectors
    normal = normal_codes(unit.fmt("vec"), boxes, basis)
    out, faults, worst = unit.fmt("out"), set(normal.faults) | l_code.faults | s_code.faults, None
    count = len(boxes)
    for q in length_cases(squared_length(normal, boxes.z)):  # each point is in one of them
        k, y_max = inverse_length(unit, q)
        c_light, cases = specular(unit, normal, k, y_max, l_code, s_code, light_view, ranges)
        diff = clamp(rounded(c_light, rounding_error(c_light.fmt, out, unit.rounding)), 0.0, 1.0)

        # the cases end to end, each but the first where it differs from it: one power bound for all
        flat = [[np.broadcast_to(x, (count,)) for x in (c[0][0], c[0][1], c[1], c[2][0], c[2][1])] for c in cases]
        rows = [np.arange(count)] + [np.flatnonzero(np.any([x != y for x, y in zip(f, flat[0])], axis=0))
                                     for f in flat[1:]]
        lo, hi, dev, a, b = (np.concatenate([f[i][r] for f, r in zip(flat, rows)]) for i in range(5))
        index = np.concatenate(rows)
        power = _power(unit, np.broadcast_to(n_hw, (count,))[index], (a, b), dev, ranges.deviations, (lo, hi))
        worst_case = []
        for x in power:  # each element's worst over its cases
            top = np.full(count, -np.inf)
            np.maximum.at(top, index, x)
            worst_case.append(top)
        # the diffuse term against max(N̂·L̂, 0), then within |δL| of max(N̂·L, 0)
        case = (diff.dev + ranges.deviations[0].whole, diff.hi, *worst_case)
        worst = case if worst is None else tuple(np.maximum(a, b) for a, b in zip(worst, case))
        faults |= diff.faults | c_light.faults
    e_d, d_hi, e_s, hw_hi, ideal_hi = worst
    return e_d, d_hi, e_s, ideal_hi, hw_hi, faults


def _phong_distance(boxes, basis, light, half, n_hw, n):
    """Per box a bound on ``|max(N̂·H, 0)^n' - max(R·V, 0)^n|`` (module docstring)."""
    w, c = cosine_range(boxes, basis, half), cosine_range(boxes, basis, light, reflected=True)

    def power(x, e):
        return np.maximum(x, 0.0) ** e

    form = np.maximum(power(w[1], n_hw) - power(c[0], n), power(c[1], n) - power(w[0], n_hw))
    return np.maximum(form, 0.0) * (1 + 1e-12) + 1e-15


class TableUnit:
    """Bounds the ``conventional`` or ``blinn`` unit (module docstring)."""

    #: what the certificate names as its method
    name = "interval+tables"

    def __init__(self, hooks, golden, specular, cosine_range, halfway):
        self.n_scale, self.specular, self.halfway = hooks.n_scale, specular, halfway
        self.golden, self.cosine_range = golden, cosine_range

    def why_not(self, shader, domain):
        """None when this method bounds ``shader`` on ``domain``, else one sentence why not."""
        why = cone_why_not(domain)
        if why:
            return why
        if not any(values for _, values in domain.materials):
            return "the domain admits no shininess n"
        why = unit_directions_why_not(domain)
        if why:
            return why
        if len(shader.units) != len(domain.lights):
            return f"the shader holds {len(shader.units)} copies of the unit for {len(domain.lights)} lights"
        local = domain.camera[0] == "point" or any(kind == "point" for kind, _, _ in domain.lights)
        if local and self.halfway:
            return ("Blinn's unit with point lights or a local viewer is fed the pixel's exact H, whose "
                    "direction the light and viewer cones do not bound where L and V nearly oppose")
        for index, (unit, (kind, _, _)) in enumerate(zip(shader.units, domain.lights)):
            if getattr(unit, "local_light", False) != (kind == "point"):
                return f"light {index} is a {kind} light but its unit's local_light is {unit.local_light}"
            if getattr(unit, "local_viewer", False) != (domain.camera[0] == "point"):
                return f"the camera is {domain.camera[0]} but the unit's local_viewer is {unit.local_viewer}"
        return None

    def limits(self, domain):
        """What of ``domain`` :meth:`bound` reads: about a local viewer's cone the N·V limits only
        through the cover of the cone's normals (:attr:`~.cones.Directions.cover_cos_min`)."""
        cones = directions(domain)
        if cones.view.half:
            return limits(domain, ("view_cos_min", "view_cos_max")), cones.cover_cos_min
        return limits(domain)

    def errors(self, shader, against, boxes, cones, floor=-np.inf, domain=None):
        """``errors(boxes, floor)`` of :func:`~phongfx.certify.branch.bound_boxes`; ``cones`` the
        light and viewer :class:`~phongfx.certify.cones.Directions` (the boxes about its axis);
        boxes with cells (:mod:`.cells`) take per box the cones of their cell in ``domain``."""
        n = boxes.n.astype(np.int64)
        n_hw = self.n_scale * n
        basis, count = cones.basis, len(boxes)
        terms, faults = [], set()
        light_cells, view_cell = (per_box(domain, boxes) if boxes.cells is not None
                                  else ([None] * len(cones.lights), None))
        # the cones about each box's own axes (the whole domain's without cells)
        v_axis, v_half = view_cell if view_cell is not None else (basis[0], cones.view.half)
        # R̂ reflects the box frame's V0: a cell's V is within its half of an axis off V0
        v_turn = v_half + (np.arccos(np.clip(v_axis @ basis[0], -1.0, 1.0)) if view_cell is not None else 0.0)
        p = spread(cosine_range(boxes, basis, v_axis), v_half)
        for unit, light, light_cell in zip(shader.units, cones.lights, light_cells):
            axis, view = np.asarray(light.axis), basis[0]
            l_axis, l_half = light_cell if light_cell is not None else (axis, light.half)
            second = _unit(axis + view) if self.halfway else view
            vec = unit.fmt("vec")
            l_code, e_light = (local_vector(unit, light, count, SYMBOLS, light_cell) if light.local
                               else (direction(axis, vec, count), EXACT))
            s_code, e_view = (local_vector(unit, cones.view, count, SYMBOLS, view_cell) if cones.view.local
                              else (direction(second, vec, count), EXACT))
            light_view = (l_code.dot(s_code) if light.local or cones.view.local
                          else product_of(l_code, s_code, count))
            q = spread(cosine_range(boxes, basis, l_axis), l_half)
            # the reference's L and V anywhere in their cones: R̂·L moves by both halves
            ideal = spread(self.cosine_range(boxes, basis, l_axis, second), l_half + v_turn)
            lv = between((l_axis, l_half), (v_axis, v_half))
            if light_cell is not None or view_cell is not None:
                ideal = reflection_range(ideal, q, p, lv)
            root = tuple(np.sqrt(np.clip(boxes.z[:, i], 0.0, 1.0)) for i in (0, 1))
            s_range = p if not self.halfway else spread(cosine_range(boxes, basis, second), cones.view.half)
            ranges = Ranges(q, s_range, ideal, lv, (e_light, e_view), root)
            e_d, d_hi, e_s, ideal_hi, hw_hi, found = light_terms(unit, boxes, basis, (l_code, s_code, light_view),
                                                                 ranges, self.specular, n_hw)
            faults |= found
            approx = (_phong_distance(boxes, basis, axis, second, n_hw, n)
                      if self.halfway and against == "phong" else np.zeros(len(boxes)))
            terms.append((e_d, d_hi, e_s, ideal_hi, hw_hi, approx, q))
        rounding, approximation, gate = blend_errors(shader.blend, boxes.material, terms, shader.blend.levels)
        if boxes.cells is not None:  # a cell outside the ball holds no input
            empty = ~meets(domain, boxes.cells)
            rounding[empty], approximation[empty], gate[empty] = 0.0, 0.0, 0.0
        if not cones.local:  # the listed codes take L and V as constants
            lights = [np.asarray(light.axis) for light in cones.lights]
            self._listed(shader, against, boxes, basis, lights, (rounding, approximation, gate), floor)
        return rounding, approximation, faults, gate

    def _listed(self, shader, against, boxes, basis, lights, parts, floor):
        """Where a box holds at most :data:`CODES_PER_BOX` normal codes and its interval bound is
        above ``floor``, every one of them through the golden model
        (:func:`~phongfx.certify.codes.code_errors`, up to :data:`CODES_PER_CALL` codes, the boxes
        of largest bound first); its bound replaces the interval one where lower (both hold), as
        rounding: it bounds rounding and approximation together."""
        rounding, approximation, gate = parts
        total = np.max(rounding + approximation, axis=-1)
        count = code_ranges(shader.units[0].fmt("vec"), boxes, basis)[2]
        order = np.argsort(-total)
        order = order[(count[order] <= CODES_PER_BOX) & (total[order] > floor)]
        order = order[np.cumsum(count[order]) <= CODES_PER_CALL]
        if not len(order):
            return
        n = boxes.n.astype(np.int64)[order]
        reflected = not self.halfway or against == "phong"
        seconds = [_unit(light + basis[0]) if self.halfway else basis[0] for light in lights]
        n_ref = n if reflected else self.n_scale * n
        listed = code_errors(shader, self.golden, boxes.take(order), basis, lights, seconds, reflected,
                             self.n_scale * n, n_ref)
        better = listed.max(axis=-1) < total[order]
        pick = order[better]
        rounding[pick], approximation[pick], gate[pick] = listed[better], 0.0, 0.0

    def bound(self, shader, spec, domain, *, max_boxes=300_000, enough=None, resume=None):
        """``(bound_levels, parts)`` over ``domain`` (:func:`~phongfx.certify.branch.bound_boxes`);
        point lights and a local viewer as :mod:`.cones` and :mod:`.local_vectors` bound them."""
        cones = directions(domain)
        against = spec.requirement.against
        boxes = None
        if cones.view.half:  # the boxes cover the normals about the viewer cone's axis
            boxes = cover(cones.cover_cos_min, domain.min_normal_length, cases(domain))
        if cones.local and not self.halfway:  # and the surface points, in cells narrowed as needed
            boxes = first_boxes(domain) if boxes is None else boxes
            boxes = replace(boxes, cells=root(domain, len(boxes)),
                            cell_scale=(CELL_WEIGHT * scale(domain), float(domain.ball[1])))

        def errors(boxes, floor):
            return self.errors(shader, against, boxes, cones, floor, domain)

        return bound_boxes(errors, domain, max_boxes=max_boxes, enough=enough, boxes=boxes, resume=resume,
                           patience=CELL_PATIENCE if boxes is not None and boxes.cells is not None else 4,
                           separable=cones.local)  # errors() lists codes across boxes only when not local


def _unit(v):
    return v / np.linalg.norm(v)


CONVENTIONAL_BOUND = TableUnit(CONVENTIONAL, conventional, _conventional, _reflected, halfway=False)
BLINN_BOUND = TableUnit(BLINN, blinn, _blinn, _direct, halfway=True)
