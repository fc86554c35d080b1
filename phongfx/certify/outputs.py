"""The error at a shader's ``r``, ``g``, ``b`` outputs, bounded box by box.

Per channel ``c`` the hardware blend (:mod:`phongfx.golden.blend`) sums, exactly, its
coefficient codes times the unit's terms, and rounds once; the reference
(:func:`phongfx.scene.geometry.shade`) is the same sum with the exact coefficients and the exact
terms.  For a material ``m`` and light ``i`` with codes ``Dc``, ``Sc`` and exact values ``De``,
``Se`` (the display scale ``2^bits - 1`` folded in, as :meth:`BlendConfig.raw_code`):

``out - levels·I_ref = round - acc`` (at most 1/2, the ``"output"`` part: clipping to the
code range moves neither side apart) ``+ rounding + approximation``, with

* ``rounding = (Ac - Ae) + Σ_i Dc·diff_hw - De·diff_ideal + Sc·gate·spec_hw - Se·lit·spec_ideal``,
  bounded by ``|Ac - Ae| + Σ_i Dc·e_diff + |Dc - De|·max diff_ideal + Sc·e_spec +
  |Sc - Se|·max spec_ideal``, where the hardware's gate (``diff_hw > 0``) and the reference's
  ``lit`` agree; they do in a box whose diffuse error ``e_diff`` is below ``s_min/levels``:
  outside the terminator band ``|N̂·L| <= 1/levels`` (where ``lit`` is the hardware's own test,
  :func:`phongfx.scene.geometry.terminator_lit`) the ideal ``N·L = s·q`` is at least
  ``s_min/levels`` from 0, so the hardware's ``N·L`` has the same sign and its clamped,
  rounded ``diff`` is 0 exactly where ``q < 0``.  Elsewhere a mismatch costs the whole term,
  ``max(Sc·max spec_hw, Se·max spec_ideal)``;
* ``approximation = Σ_i De·(diff_ideal - max(q, 0)) + Se·lit·(spec_ideal - spec_ref)``
  (:mod:`.approximation`).
"""

from dataclasses import replace

import numpy as np

from .approximation import (bend_shift, diffuse_shift, form_distance, halfway_distance, halfway_vectors, scale_range,
                            shape_shift)
from .cones import at_infinity
from .datapath import unit_terms
from .sphere import projection

__all__ = ["coefficient_tables", "fewest_coefficient_bits", "light_rounding", "box_errors", "blend_errors"]


def coefficient_tables(blend):
    """``(codes, exact)``, each ``(A, D, S)`` arrays of shape (materials, 3) and
    (materials, lights, 3), in output levels."""
    scale = 2.0 ** -blend.coef_frac
    codes = [blend.coefficients(m) for m in range(blend.materials)]
    out_codes = tuple(np.array([c[part] for c in codes], dtype=np.float64) * scale for part in range(3))
    exact = tuple(np.array(table, dtype=np.float64) * blend.levels
                  for table in (blend.ambient, blend.diffuse, blend.specular))
    return out_codes, exact


def fewest_coefficient_bits(blend):
    """``blend`` at the fewest ``coef_frac`` bits whose coefficient values are its own: its
    outputs are the same for every input (the sum is exact and rounded once), so is any bound
    on them, and a certificate of one holds for the other."""
    codes = coefficient_tables(blend)[0]
    for frac in range(blend.coef_frac):
        fewer = replace(blend, coef_frac=frac)
        if all(np.array_equal(a, b) for a, b in zip(coefficient_tables(fewer)[0], codes)):
            return fewer
    return blend


def light_rounding(tables, m, i, levels, d_hi, e_d, t_hi, e_s, q, margin, ideal=None):
    """Light ``i``'s part of the rounding sum (module docstring) per box (B, 3), and per box
    its gate: 0 where the backside tests agree, else ``margin``.  ``tables``:
    :func:`coefficient_tables`; ``m``: the boxes' materials; ``d_hi``, ``t_hi``: the
    hardware's largest diffuse and specular terms, ``e_d``, ``e_s`` their distance from the
    ideal ones (B,), whose largest values are ``ideal = (diffuse, specular)`` when known, else
    ``d_hi + e_d`` and ``t_hi + e_s``; ``q = (lo, hi)`` the exact ``N̂·L``; ``margin`` (B,) or
    scalar: where ``|q|`` exceeds it, the hardware's gate is the sign of ``q``."""
    (_, dc, sc), (_, de, se) = tables
    d_top, t_top = ideal if ideal is not None else (d_hi + e_d, t_hi + e_s)
    e_d, e_s, d_top, t_hi, t_top = e_d[:, None], e_s[:, None], d_top[:, None], t_hi[:, None], t_top[:, None]
    rounding = dc[m, i] * e_d + np.abs(dc[m, i] - de[m, i]) * d_top
    both = sc[m, i] * e_s + np.abs(sc[m, i] - se[m, i]) * t_top
    # behind the light (q < -margin) both gates close: no specular term on either side
    both = np.where((q[1] < -margin)[:, None], 0.0, both)
    agree = (margin < 1.0 / levels) | (q[0] > margin) | (q[1] < -margin)
    mismatch = np.maximum(sc[m, i] * t_hi, se[m, i] * t_top)
    rounding = rounding + np.where(agree[:, None], both, np.maximum(both, mismatch))
    return rounding, np.where(agree, 0.0, margin)


def _applied_n(unit, n):
    """The ``n`` the hardware's ``x = (n/2)|D|²`` applies for the domain's ``n`` per box."""
    return np.asarray(unit.unit.applied_n(unit, n.astype(np.float64)) if unit.shininess_const == 0
                      else np.full(len(n), float(unit.unit.top_n(unit.shininess_const))))


def _form(against, unit, n_hw, n, k, c):
    """Per box the distance of the ideal form at ``s = 1`` from the reference's (grouped by n)."""
    out = np.zeros(len(n))
    # the distinct (n_hw, n) pairs, as one integer each (a row-wise unique sorts far slower)
    hw, ref = np.asarray(n_hw).astype(np.int64), np.asarray(n).astype(np.int64)
    base = int(ref.max(initial=0)) + 1
    for key in np.unique(hw * base + ref).tolist():
        pair = divmod(key, base)
        if against == "self" and pair[0] == pair[1]:
            continue
        pick = (n_hw == pair[0]) & (n == pair[1])
        out[pick] = form_distance(pair[0], pair[1], k, (c[0][pick], c[1][pick]), against)
    return out


def _halfway(against, unit, boxes, cones, i, s, c, n_hw, n, k):
    target, target_ref = halfway_vectors(unit, cones.basis[0], cones.light_axes[i])
    w, w_ref = projection(boxes, cones.basis, target), projection(boxes, cones.basis, target_ref)
    return halfway_distance(against, s, w, w_ref, c, float(target @ target), float(target_ref @ target_ref),
                            n_hw * 2.0 ** unit.halfway_shift, n, k)


def box_errors(shader, unit_bound, against, boxes, basis, lights, min_normal_length, cones=None):
    """Per box and channel ``(rounding, approximation)`` arrays (B, 3), in levels, the unit's
    ``faults`` (quantizes that may overflow: :class:`~phongfx.certify.interval.Interval`) and per
    box ``gate``: 0 where the backside tests agree, else the ``|N·L|`` below which they may not.
    ``unit_bound``: what differs between Lyon's units (:class:`phongfx.certify.figures.LyonDatapaths`:
    its ``specular`` intervals and the field whose ``k`` its shape takes; a unit whose form is
    taken at ``N·H`` says so itself, :attr:`~phongfx.config.base.SpecularUnit.bisector`).  ``cones`` (:class:`~phongfx.certify.cones.Directions`):
    point lights and a local viewer, whose projections it widens; None: ``lights`` directional,
    the viewer ``basis[0]``."""
    unit, blend = shader.units[0], shader.blend
    cones = cones or at_infinity(basis, lights, -1.0)
    spec, diff = unit_terms(unit, unit_bound.specular, boxes, cones.basis, None, min_normal_length, cones)
    tables = coefficient_tables(blend)
    (ac, _, _), (ae, de, se) = tables
    m = boxes.material
    s = scale_range(boxes.z, unit.normalize.order)
    p = cones.p(boxes)
    n = boxes.n.astype(np.float64)
    n_hw = _applied_n(unit, n)
    k = getattr(unit, unit_bound.k_field).k
    rounding = np.abs(ac - ae)[m].copy()
    approximation = np.zeros_like(rounding)
    faults, gate = set(), np.zeros(len(boxes))
    for i in range(len(cones.lights)):
        q, c = cones.q(boxes, i), cones.c(boxes, i)
        d, t = diff[i], spec[i]
        faults |= d.faults | t.faults
        # where |q| exceeds the margin, the hardware's N·L has the reference's sign (its own L within ε)
        slack = cones.slack(cones.lights[i], unit.direction_normalize.order)
        margin = (d.dev + s[1] * slack) / s[0]
        add, off = light_rounding(tables, m, i, blend.levels, d.hi, d.dev, t.hi, t.dev, q, margin)
        rounding += add
        gate = np.maximum(gate, off)
        if unit.unit.bisector:
            shift = _halfway(against, unit, boxes, cones, i, s, c, n_hw, n, k)
        elif cones.local:  # N's scale and the ideal's own L and V against the reference's (:mod:`.cones`)
            shift = (bend_shift(*cones.difference(boxes, s, unit.direction_normalize.order, i), n_hw, k)
                     + _form(against, unit, n_hw, n, k, c))
        else:
            shift = shape_shift(s, p, q, c, n_hw, k) + _form(against, unit, n_hw, n, k, c)
        bent = s[1] * slack * (q[1] > -margin)  # |N·L' - N·L| where some L lights the box
        approximation += de[m, i] * (diffuse_shift(s, q) + bent)[:, None] + se[m, i] * shift[:, None]
    return rounding, approximation, faults, gate


def blend_errors(blend, material, terms, levels):
    """``(rounding, approximation, gate)`` (B, 3), (B, 3), (B,) at the outputs of a table unit
    (:mod:`.table_units`; as this module states them, with ``s = 1``) from per light ``(e_d,
    d_hi, e_s, ideal_hi, hw_hi, approximation, q)``: ``q`` the range of the exact ``N̂·L``."""
    (ac, dc, sc), (ae, de, se) = coefficient_tables(blend)
    m = material
    rounding = np.abs(ac - ae)[m].copy()
    approximation = np.zeros_like(rounding)
    gate = np.zeros(len(m))
    for i, (e_d, d_hi, e_s, ideal_hi, hw_hi, approx, q) in enumerate(terms):
        d, s = dc[m, i], sc[m, i]
        rounding += d * e_d[:, None] + np.abs(d - de[m, i]) * (d_hi + e_d)[:, None]
        both = s * e_s[:, None] + np.abs(s - se[m, i]) * ideal_hi[:, None]
        # the hardware's lit (diff > 0) is the reference's outside the terminator band
        agree = (e_d < 1.0 / levels) | (q[0] > e_d) | (q[1] < -e_d)
        mismatch = np.maximum(s * hw_hi[:, None], se[m, i] * (ideal_hi + approx)[:, None])
        rounding += np.where(agree[:, None], both, np.maximum(both, mismatch))
        gate = np.where(agree, gate, np.maximum(gate, e_d))
        approximation += se[m, i] * approx[:, None]
    return rounding, approximation, gate
