"""Every normal code of a small box of the domain through the whole unit: the table units'
bound where a box holds few codes.

A box of normals (:mod:`.sphere`) meets, per component, the codes the host's rounding to nearest
can give its ``N' = √z·N̂`` (:func:`code_ranges`).  Where their product is small (the boxes the
branch and bound has cut near the largest error), each code runs through the unit's golden model
once per light (:mod:`phongfx.golden.conventional`, :mod:`phongfx.golden.blinn`), so the
hardware's diffuse and specular codes and its backside test are known exactly; only the
reference varies, over the code's cell ``|N' - code|_∞ <= lsb/2``.  There ``N̂·W`` and Phong's
``R·V = 2(N̂·L)(N̂·V) - L·V`` are bounded by their value at the code and their gradient
(``∇(N̂·W) = (W - (N̂·W)N̂)/|N'|``) times the cell's half width, plus the second-order remainder:
the second derivative of ``N̂ = N'/|N'|`` is at most ``3/|N'|²``, so that of ``N̂·W`` is too and
that of ``2(N̂·L)(N̂·V)`` at most ``2(3 + 3 + 2)/|N'|²``, over the segment from the code, where
``|N'|`` is at least ``|code| - √3·lsb/2``.

Per channel the output's error before its rounding is then a signed range: ``(Ac - Ae) + Σ_i
Dc·diff_hw - De·max(N̂·L, 0) + Sc·gate·spec_hw - Se·lit·ref``, with the reference's ``lit`` that of
:func:`phongfx.scene.geometry.terminator_lit` (any value the cell's ``N̂·L`` allows) and ``ref``
the reference's specular (``max(R·V, 0)^n`` against Phong, the unit's own form against itself),
so that rounding and approximation are bounded together.
"""

import numpy as np

from phongfx.golden.fixed import Fixed

from .outputs import coefficient_tables
from .normalizer import cosine_range
from .sphere import product

__all__ = ["code_ranges", "cell_cosine", "cell_geometry", "code_errors"]


def code_ranges(vec, boxes, basis):
    """``(first, last, count)``: per box and component the first and last code (B, 3) of the
    host's rounding (half up) of ``N'`` over the box, and their number of combinations (B,)
    (inf where a code may saturate)."""
    root = (np.sqrt(np.clip(boxes.z[:, 0], 0, 1)), np.sqrt(np.clip(boxes.z[:, 1], 0, 1)))
    parts = [product(root, cosine_range(boxes, basis, axis)) for axis in np.eye(3)]
    scale = 2.0 ** vec.frac_bits
    first = np.stack([np.floor(p[0] * scale + 0.5) for p in parts], -1)
    last = np.stack([np.floor(p[1] * scale + 0.5) for p in parts], -1)
    count = np.prod(last - first + 1, axis=-1)
    inside = np.all((first > vec.min_raw) & (last < vec.max_raw), axis=-1)
    return first.astype(np.int64), last.astype(np.int64), np.where(inside, count, np.inf)


def _listed(first, last):
    """``(box, codes)``: every code combination of the boxes' ranges, with its box's index."""
    sizes = last - first + 1
    count = np.prod(sizes, axis=-1)
    box = np.repeat(np.arange(len(count)), count)
    index = np.arange(len(box)) - np.repeat(np.cumsum(count) - count, count)
    codes = np.empty((len(box), 3), dtype=np.int64)
    for axis in (2, 1, 0):
        size = sizes[box, axis]
        codes[:, axis] = first[box, axis] + index % size
        index = index // size
    return box, codes


def cell_cosine(geometry, lsb, w, view=None):
    """``(lo, hi)`` of ``N̂·W`` (or of ``R·V = 2(N̂·W)(N̂·V) - W·V`` with ``view``) over the cells
    of side ``lsb`` whose centres have the :func:`cell_geometry` ``geometry`` (module docstring);
    ``w``, ``view`` unit."""
    r, u = geometry
    a = u @ w
    grad = (w - a[:, None] * u) / r[:, None]
    curve = 3.0
    if view is not None:
        b = u @ view
        grad = 2 * (b[:, None] * grad + a[:, None] * (view - b[:, None] * u) / r[:, None])
        a, curve = 2 * a * b - float(w @ view), 16.0
    half = lsb / 2
    reach = np.sqrt(3.0) * half
    spread = np.abs(grad).sum(axis=-1) * half + 0.5 * curve * reach ** 2 / (r - reach) ** 2
    spread = spread * (1 + 1e-9) + 1e-13
    return a - spread, a + spread


def cell_geometry(x):
    """``(|x|, x/|x|)`` of cell centres ``x`` (C, 3): what every :func:`cell_cosine` of them reads."""
    r = np.linalg.norm(x, axis=-1)
    return r, x / r[:, None]


def _lit(d, hw, levels):
    """``(may_true, may_false)``: the reference's backside test over a cell whose ``N̂·L`` is in
    ``d``, ``hw`` the hardware's own test (:func:`phongfx.scene.geometry.terminator_lit`)."""
    band = 1.0 / levels
    inside = (d[0] <= band) & (d[1] >= -band)
    return (d[1] > band) | (inside & hw), (d[0] < -band) | (inside & ~hw)


def code_errors(shader, golden, boxes, basis, lights, seconds, reflected, n_hw, n_ref):
    """Per box and channel a bound (B, 3) on ``|acc - levels·I_ref|`` before the output's
    rounding, every code of each box run through ``golden`` (the unit's model, ``(config, N, L,
    X, n)``) with ``X`` the light's ``seconds`` (the viewer, or the halfway vector); the
    reference's specular cosine is Phong's ``R·V`` (``reflected``) or ``N̂·X``; ``n_hw``,
    ``n_ref`` per box the applied and the reference's ``n``."""
    unit = shader.units[0]
    vec = unit.fmt("vec")
    first, last, _ = code_ranges(vec, boxes, basis)
    box, codes = _listed(first, last)
    count = len(box)
    geometry = cell_geometry(codes * vec.lsb)
    (ac, dc, sc), (ae, de, se) = coefficient_tables(shader.blend)
    m = boxes.material[box]
    low = (ac - ae)[m].copy()
    high = low.copy()
    view = basis[0]
    for i, (config, light, second) in enumerate(zip(shader.units, lights, seconds)):
        out = golden(config, Fixed(codes, vec), _codes(light, vec, count), _codes(second, vec, count),
                     Fixed(n_hw[box], config.fmt("n")))
        diff, spec = out["diffuse"].to_float(), out["specular"].to_float()
        gate = diff > 0  # the blend's backside test
        d = cell_cosine(geometry, vec.lsb, light)
        c = cell_cosine(geometry, vec.lsb, light, view) if reflected else cell_cosine(geometry, vec.lsb, second)
        n = n_ref[box]
        ref = (np.clip(c[0], 0.0, 1.0) ** n, np.clip(c[1], 0.0, 1.0) ** n)
        may_true, may_false = _lit(d, gate, shader.blend.levels)
        diffuse, specular = de[m, i], se[m, i]
        hw = dc[m, i] * diff[:, None] + sc[m, i] * np.where(gate, spec, 0.0)[:, None]
        low += hw - diffuse * np.maximum(d[1], 0.0)[:, None] - np.where(may_true[:, None], specular * ref[1][:, None], 0.0)
        high += hw - diffuse * np.maximum(d[0], 0.0)[:, None] - np.where(may_false[:, None], 0.0, specular * ref[0][:, None])
    worst = np.maximum(np.abs(low), np.abs(high)) * (1 + 1e-9) + 1e-9
    # the codes are listed box by box (_listed): each box's largest is one reduction of its run
    starts = np.flatnonzero(np.r_[True, box[1:] != box[:-1]])
    out = np.zeros((len(boxes), 3))
    out[box[starts]] = np.maximum.reduceat(worst, starts, axis=0)
    return out


def _codes(vector, vec, count):
    """The code of ``vector`` in ``vec``, ``count`` times (a read-only view of one row)."""
    one = Fixed.from_float(np.asarray(vector, dtype=np.float64)[None, :], vec, "round_half_up", "saturate")
    return Fixed(np.broadcast_to(one.raw, (count, 3)), vec)
