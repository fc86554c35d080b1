"""How far a datapath's ideal (every quantize removed) is from the reference, per box of normals.

Lyon (1993, "Approximate Normalization"): the ideal normalizer scales the interpolated normal
``N' = √z·N̂`` by ``g(z)``, ``g1 = 1 + y/2`` or ``g2 = 1 + (y + y²)/2`` with ``y = 1 - z``, so
the ideal normal is ``N = s·N̂`` with ``s = g(z)·√z``, a little off unit length.  With the
lights and the viewer at infinity everything the ideal and the reference compute depends on
``s``, ``p = N̂·V`` and ``q = N̂·L`` (Figure 2):

* ``R = 2(N·V)N - V = 2s²p·N̂ - V`` and ``D = R - L`` give
  ``|D|² = 4s²p²(s² - 1) + 2 - 4s²pq + 2V·L``, which at ``s = 1`` is ``2(1 - c)`` with Phong's
  ``c = R̂·L = 2pq - V·L``; so the shape function's ``x = (n/2)|D|²`` (Figure 7c) moves by
  ``x(s) - x(1) = 2n(s² - 1)·p·(s²p - q)`` and ``f_k(x) = (1 - x/2^k)^(2^k)`` (Figure 7d) by at
  most ``max|f_k'|·|x(s) - x(1)|``, ``|f_k'(x)| = (1 - x/2^k)^(2^k - 1)`` below ``2^k``, 0 above;
* the diffuse term ``max(s·q, 0)`` is at most ``|s - 1|·max(q, 0)`` from ``max(q, 0)``;
* against the method's own float form (``"self"``, the same formula at ``s = 1``) that is all;
  against Phong (``"phong"``) the form's own distance ``|f_k(n'(1 - c)) - max(c, 0)^n|`` is
  added, a function of ``c`` alone (``n' = n`` for Figure 7, ``m²`` with ``m = round(√n)`` for
  Figure 8, whose ideal is Figure 7's with that ``n'``: its comparator zeroes only where
  ``x >= 2^k`` already).  :func:`form_table` bounds it on each of ``2^20`` cells of ``c`` by
  monotonicity (both terms rise with ``c``), and a box takes the largest cell its ``c`` meets.

The halfway unit (Figure 5, the appendix's rows 7–8: ``D = Q - (Q·N)N`` with ``Q`` the halfway
vector ``H`` or its ``g``-normalized ``H*``, constant when ``L`` and ``V`` are) has
``|D|² = |Q|² - (2s² - s⁴)·w²``, ``w = Q·N̂``, so ``x`` moves by ``(n'/2)·w²·(s² - 1)²`` from
``s = 1`` (``n' = n·2^halfway_shift``); its form at ``s = 1`` is a function of ``w`` and
Phong's of ``c``, which :func:`halfway_distance` bounds by the ranges of both (loose where
both vary, as ``f_k`` and ``c^n`` are different functions of the normal there).
"""

import functools

import numpy as np

from .interval import least, most

__all__ = ["CELLS", "BEND_PIECES", "PIECES", "scale_range", "shape_shift", "bend_shift", "diffuse_shift", "form_table", "form_distance", "halfway_vectors",
           "halfway_distance"]

#: Cells of ``c ∈ [-1, 1]`` in :func:`form_table`.
CELLS = 1 << 20

#: Pieces of a box's ``|D|`` range in :func:`bend_shift` (cheap: a few array operations each).
BEND_PIECES = 256

#: Pieces of a box's ``|D|`` range that the rounding part takes apart
#: (:func:`phongfx.certify.datapath.unit_terms`: the shape function runs once per piece).
PIECES = 16


def _g(y, order):
    return 1 + y / 2 if order == 1 else 1 + (y + y * y) / 2


def _scale(z, order):
    return _g(1 - z, order) * np.sqrt(z)


def scale_range(z, order):
    """``(lo, hi)`` of ``s = g(z)·√z`` over boxes ``z`` (B, 2), ``g`` of ``order`` 1 or 2, exact:
    ``s`` is monotone in ``z`` on ``[0, 1]`` for ``g1`` (``ds/dz = 3(1 - z)/(4√z)``), and for
    ``g2`` rises with ``y = 1 - z`` up to ``y = 1/5`` and falls after (``ds/dy ∝ y(1 - 5y)``):
    Lyon's over-correction, largest at length ``√0.8 ≈ 0.894``."""
    z = np.clip(z, 0.0, 1.0)
    ends = [_scale(z[:, 0], order), _scale(z[:, 1], order)]
    lo, hi = np.minimum(*ends), np.maximum(*ends)
    if order == 2:
        peak = (z[:, 0] <= 0.8) & (0.8 <= z[:, 1])
        hi = np.where(peak, np.maximum(hi, _scale(0.8, 2)), hi)
    return lo * (1 - 1e-15), hi * (1 + 1e-15)


def _magnitude(r):
    return np.maximum(np.abs(r[0]), np.abs(r[1]))


def shape_shift(s, p, q, c, n_eff, k):
    """Bound on ``|f_k(x(s)) - f_k(x(1))|`` per box (module docstring): ``s``, ``p``, ``q``, ``c``
    are ``(lo, hi)`` arrays (``c`` Phong's ``R̂·L``), ``n_eff`` the ``n`` in ``x``."""
    s2 = (s[0] ** 2, s[1] ** 2)
    corners = [a * b for a in s2 for b in p]
    s2p = (least(corners), most(corners))
    inner = (s2p[0] - q[1], s2p[1] - q[0])
    dx = 2 * n_eff * _magnitude((s2[0] - 1, s2[1] - 1)) * _magnitude(p) * _magnitude(inner)
    big = 2.0 ** k
    x_min = np.maximum(0.0, n_eff * (1 - c[1]) - dx)
    slope = np.maximum(0.0, 1 - x_min / big) ** (big - 1)
    return slope * dx * (1 + 1e-12)


def bend_shift(t, delta, n_eff, k):
    """Bound on ``|f_k(x') - f_k(x)|`` per box, ``x = (n_eff/2)|D|²`` with ``|D|`` in ``t = (lo,
    hi)`` and ``x'`` the same of a ``D'`` within ``delta`` of ``D`` (a point light's or local
    viewer's ideal against the reference's directions, :mod:`.cones`): ``|x' - x| <=
    n_eff(|D|δ + δ²/2)`` and ``|f_k'|`` falls with ``x``, so on each of :data:`BEND_PIECES` pieces
    ``[a, b]`` of ``t`` the shift is at most ``|f_k'(n_eff·a²/2 - Δ)|·Δ``, ``Δ = n_eff(bδ +
    δ²/2)``; the largest piece bounds the box (at most 1: ``f_k`` lies in ``[0, 1]``)."""
    delta = np.broadcast_to(np.asarray(delta, dtype=np.float64), np.shape(t[0]))[:, None]
    if not np.any(delta > 0):
        return np.zeros(np.shape(t[0]))
    cut = np.linspace(0.0, 1.0, BEND_PIECES + 1)
    a = t[0][:, None] + (t[1] - t[0])[:, None] * cut[:-1]
    b = t[0][:, None] + (t[1] - t[0])[:, None] * cut[1:]
    a[:, 0], b[:, -1] = t[0], t[1]  # the pieces share their float ends: they cover the range
    n = np.asarray(n_eff, dtype=np.float64)[:, None]
    reach = n * (b * delta + delta * delta / 2)
    big = 2.0 ** k
    slope = np.maximum(0.0, 1 - np.maximum(0.0, n * a * a / 2 - reach) / big) ** (big - 1)
    return np.minimum(np.max(slope * reach, axis=-1) * (1 + 1e-12), 1.0)


def diffuse_shift(s, q):
    """Bound on ``|max(s·q, 0) - max(q, 0)|`` per box."""
    return _magnitude((s[0] - 1, s[1] - 1)) * np.maximum(q[1], 0.0)


def _shape(x, k):
    big = 2.0 ** k
    t = np.maximum(0.0, 1 - x / big)
    for _ in range(k):
        t = t * t
    return t


def form_table(n_eff, n, k, against="phong"):
    """Per cell ``[c_j, c_j+1]`` of ``c ∈ [-1, 1]`` (:data:`CELLS` of them), a bound on
    ``|f_k(n_eff(1 - c)) - G(c)|`` there, ``G = max(c, 0)^n`` (``"phong"``) or the form at the
    reference's own ``n``, ``f_k(n(1 - c))`` (``"self"``, when the hardware fixes another ``n``):
    ``F = f_k(n_eff(1 - c))`` and ``G`` both rise with ``c``, so on a cell
    ``|F - G| <= max(F(c_j+1) - G(c_j), G(c_j+1) - F(c_j))``."""
    c = np.linspace(-1.0, 1.0, CELLS + 1)
    f = _shape(n_eff * (1 - c), k)
    g = np.maximum(c, 0.0) ** n if against == "phong" else _shape(n * (1 - c), k)
    cell = np.maximum(f[1:] - g[:-1], g[1:] - f[:-1])
    return np.maximum(cell, 0.0) + 1e-12


#: Tables kept: one per (n the hardware applies, reference n) of a certificate, so that a
#: material's whole n range (up to this many values) is computed once, not once per round
#: of the branch and bound; each is 8 MB (float32).
TABLES_KEPT = 160


@functools.lru_cache(maxsize=TABLES_KEPT)
def _levels(n_eff, n, k, against):
    """:func:`form_table` and its maxima over aligned blocks of 2, 4, ... cells, concatenated,
    with the offset of each level; in float32 rounded up (never below the float64 bound), which
    halves what a kept table costs."""
    table = form_table(n_eff, n, k, against)
    levels, offsets, at = [table], [0], len(table)
    while len(levels[-1]) > 1:
        last = levels[-1]
        offsets.append(at)
        levels.append(np.maximum(last[0::2], last[1::2]))
        at += len(levels[-1])
    flat = np.concatenate(levels)
    return np.nextafter(flat.astype(np.float32), np.float32(np.inf)), np.array(offsets)


def form_distance(n_eff, n, k, c, against="phong"):
    """Per box, a bound on the :func:`form_table` cells that ``c = (lo, hi)`` meets: the larger
    of the (at most two) aligned blocks of ``2^l >= `` as many cells that hold them."""
    flat, offsets = _levels(int(n_eff), int(n), int(k), against)
    first = np.clip(np.floor((np.clip(c[0], -1, 1) + 1) / 2 * CELLS), 0, CELLS - 1).astype(np.int64)
    last = np.clip(np.floor((np.clip(c[1], -1, 1) + 1) / 2 * CELLS), 0, CELLS - 1).astype(np.int64)
    level = np.ceil(np.log2(np.maximum(last - first + 1, 1))).astype(np.int64)
    # float log2 may land one low at an exact power: one level up is still sound
    level = np.minimum(level + ((last >> level) - (first >> level) > 1), len(offsets) - 1)
    return np.maximum(flat[offsets[level] + (first >> level)], flat[offsets[level] + (last >> level)])


def halfway_vectors(unit, view, light):
    """``(Q, Q_ref)``: the ideal unit's constant ``Q`` (None for a variant not bounded here) and
    that of the float form ``halfway-g2proj`` (``H = (L + V)/2``, ``g2``-normalized)."""
    cfg = unit.halfway
    h = view + light
    mean = h / 2
    if cfg.h == "mean":
        h = mean
    if cfg.variant == "g2proj":
        y = 1 - h @ h
        q = _g(max(y, -1.0), cfg.normalize.order) * h
    elif cfg.variant == "d3":
        q = h
    else:
        q = None
    y = 1 - mean @ mean
    return q, _g(y, 2) * mean


def _square(r):
    low = np.where((r[0] <= 0) & (r[1] >= 0), 0.0, np.minimum(r[0] ** 2, r[1] ** 2))
    return low, np.maximum(r[0] ** 2, r[1] ** 2)


def halfway_distance(against, s, w, w_ref, c, q2, q2_ref, n_hw, n, k):
    """Bound on ``|spec_ideal - spec_ref|`` of the halfway unit per box (module docstring):
    ``w``, ``w_ref`` the ranges of ``Q·N̂`` and ``Q_ref·N̂``, ``q2`` and ``q2_ref`` the
    constants ``|Q|²``, ``|Q_ref|²``, ``n_hw`` the hardware's ``n'`` per box."""
    w2, s2 = _square(w), (s[0] ** 2, s[1] ** 2)
    dx = n_hw / 2 * w2[1] * np.maximum((s2[0] - 1) ** 2, (s2[1] - 1) ** 2)
    f_lo = _shape(n_hw / 2 * (q2 - w2[0]), k)
    f_hi = _shape(n_hw / 2 * np.maximum(q2 - w2[1], 0.0), k)
    if against == "self":
        if np.all(n_hw == 4 * n) and abs(q2 - q2_ref) == 0:
            return dx * (1 + 1e-12)
        r2 = _square(w_ref)
        g_lo, g_hi = _shape(2 * n * (q2_ref - r2[0]), k), _shape(2 * n * np.maximum(q2_ref - r2[1], 0.0), k)
    else:
        g_lo, g_hi = np.maximum(c[0], 0.0) ** n, np.maximum(c[1], 0.0) ** n
    form = np.maximum(np.maximum(f_hi - g_lo, g_hi - f_lo), 0.0)
    return (dx + form) * (1 + 1e-12) + 1e-15
