"""The table units' normalizer and cosines on :class:`~phongfx.certify.interval.Interval` values,
box by box of the domain's normals.

The conventional and Blinn units (:mod:`phongfx.golden.conventional`, :mod:`phongfx.golden.blinn`;
Lyon 1993, "Background": the direct design that normalizes ``N`` per pixel) take the interpolated
normal ``N' = √z·N̂`` as the host rounds it (:func:`phongfx.scene.span_inputs.conventional_codes`:
to nearest in ``vec``, saturated) and form each cosine as
``c = round(round(d·2^(j-h))·y1)`` with ``d = N·X`` exact, ``2^(j-h)·y1 = (1 + r)/sqrt(q)``
(``q = N·N``, ``r`` the seed table's and Newton step's relative error, known per mantissa code:
:func:`~phongfx.certify.tables.rsqrt_factor`).  Against the ideal ``N̂·X`` (exact unit normal,
exact unit ``X``):

* :func:`normal_codes`: ``N = N' + δ``, one shared noise symbol per component of ``δ`` (the
  host's rounding), so that the normalizer's division takes out the part of ``δ`` along ``N'``
  (``d`` and ``1/sqrt(q)`` carry the same symbols);
* :func:`inverse_length`: ``1/sqrt(q)`` in affine form about the box's middle ``q`` (slope there
  times ``q``'s terms, the slope's spread over the range times its deviation as remainder), and
  the table's ``r`` as remainder;
* :func:`cosine`: ``d·k`` by the Interval product, plus the ``dot`` rounding (times ``y1 < 2``)
  and the output rounding;
* :func:`clamp`: the hardware's clamps (to 1, to 0 by an unsigned format's saturation), which
  move no value toward the outside of ``[low, high]``: with the ideal inside, the distance does
  not grow, and the terms stay where the range is inside.
"""

import numpy as np

from phongfx.core.format import Format

from phongfx.golden.fixed import Fixed

from .interval import Interval, rounding_error
from .sphere import cos_range, product
from .tables import rsqrt_factor

__all__ = ["SYMBOLS", "cosine_range", "normal_codes", "direction", "product_of", "squared_length", "length_cases", "inverse_length", "cosine", "clamp", "rounded"]

#: A format finer than any the units' exact products have: rounding from it costs a full half LSB
_EXACT = Format(2, 40, signed=True)


#: Noise symbols of a cosine stage: the three components of the host's rounding of ``N``;
#: :data:`OFFSET`, whose value is 1: the fixed offsets (the light's and viewer's code errors,
#: the middle of the seed table's ``r``), each the same wherever it enters, so that they cancel
#: where the datapath cancels them; :data:`TABLE`, the rest of ``r`` (the same in every cosine
#: of a pixel: they share ``y1``)
SYMBOLS, OFFSET, TABLE = 5, 3, 4


def cosine_range(boxes, basis, w, reflected=False):
    """Exact ``(lo, hi)`` of ``W·N̂`` (or ``R̂·W``, ``reflected``) over each box (``w`` one vector or
    one per box): the form of
    :func:`~phongfx.certify.sphere.projection`, ``a·cos(sθ) + b·sin(sθ)·C`` with ``C = cos(φ - ψ)``,
    is linear in ``C``, so its extremes are at ``C``'s ends, and at a fixed ``C`` it is
    ``A·cos(sθ - α)``, whose range over ``θ`` is exact (:func:`~phongfx.certify.sphere.cos_range`).
    Interval products of the two factors would lose the first order at a cosine's peak, where a
    large ``n`` needs it."""
    v, e1, e2 = basis
    w = np.asarray(w, dtype=np.float64)  # one vector, or one per box (B, 3)
    a, b, psi = w @ v, np.hypot(w @ e1, w @ e2), np.arctan2(w @ e2, w @ e1)
    s = 2.0 if reflected else 1.0
    turn = cos_range(boxes.phi[:, 0] - psi, boxes.phi[:, 1] - psi)
    lo, hi = np.full(len(boxes), np.inf), np.full(len(boxes), -np.inf)
    for c in turn:
        c = np.clip(c, -1.0, 1.0)
        size, alpha = np.hypot(a, b * c), np.arctan2(b * c, a)
        low, high = cos_range(s * boxes.theta[:, 0] - alpha, s * boxes.theta[:, 1] - alpha)
        lo, hi = np.minimum(lo, size * low), np.maximum(hi, size * high)
    return lo - 1e-14, hi + 1e-14


def normal_codes(vec, boxes, basis):
    """The host's ``N`` codes (B, 3) as an Interval over ``boxes`` (:mod:`.sphere`): ``N' =
    √z·N̂`` rounded to nearest in ``vec`` (``|δ| <= lsb/2``) and saturated (a component over the
    largest code moves by its excess); symbols ``0..2`` of :data:`SYMBOLS`."""
    root = (np.sqrt(np.clip(boxes.z[:, 0], 0, 1)), np.sqrt(np.clip(boxes.z[:, 1], 0, 1)))
    parts = [product(root, cosine_range(boxes, basis, axis)) for axis in np.eye(3)]
    lo, hi = np.stack([p[0] for p in parts], -1), np.stack([p[1] for p in parts], -1)
    top, low = vec.max_raw * vec.lsb, vec.min_raw * vec.lsb
    e = np.maximum(vec.lsb / 2, np.maximum(hi - top, low - lo)) * (1 + 1e-12)
    terms = np.zeros(lo.shape + (SYMBOLS,))
    terms[..., :3] = e[..., None] * np.eye(3)
    return Interval(np.clip(lo - e, low, top), np.clip(hi + e, low, top), 0.0, vec, terms=terms)


def direction(vector, fmt, count):
    """A constant unit ``vector`` (a light or viewer at infinity) as the host encodes it (to
    nearest, saturated), (count, 3): its code, whose error is a term on :data:`OFFSET`."""
    vector = np.asarray(vector, dtype=np.float64)
    code = Fixed.from_float(vector, fmt, rounding="round_half_up", overflow="saturate").to_float()
    terms = np.zeros((count, 3, SYMBOLS))
    terms[..., OFFSET] = code - vector
    wide = np.broadcast_to(code, (count, 3))
    return Interval(wide, wide, 0.0, fmt, terms=terms)


def product_of(a, b, count):
    """``A·B`` of two constant directions (:func:`direction`) as the hardware forms it, exact,
    against the exact ``A·B``: ``ΔA·B_code + A·ΔB`` on :data:`OFFSET`."""
    code_a, code_b = a.lo[0], b.lo[0]
    delta_a, delta_b = a.terms[0, :, OFFSET], b.terms[0, :, OFFSET]
    terms = np.zeros((count, SYMBOLS))
    terms[:, OFFSET] = float(delta_a @ code_b) + float((code_a - delta_a) @ delta_b)
    value = np.full(count, float(code_a @ code_b))
    return Interval(value, value, 0.0, a.fmt.mul(b.fmt).add(a.fmt.mul(b.fmt)), terms=terms)


def squared_length(normal, z):
    """``q = N·N`` (B,) as an Interval against ``|N'|²``; ``z`` (B, 2) the range of ``|N'|²``
    (:func:`normal_codes`' ``normal``): ``|N| = |N' + δ|`` is within ``|δ|`` of ``|N'|``, which
    bounds ``q``'s range closer than the Interval's sum of squares (whose components' ranges
    move together)."""
    q = normal.dot(normal)
    shift = np.sqrt(np.sum(np.diagonal(normal.terms[..., :3], axis1=-2, axis2=-1) ** 2, axis=-1))
    length = np.sqrt(np.clip(z, 0.0, None))
    q_lo = np.maximum(q.lo, np.maximum(length[:, 0] - shift, 0.0) ** 2 * (1 - 1e-12))
    q_hi = np.minimum(q.hi, (length[:, 1] + shift) ** 2 * (1 + 1e-12))
    if np.any(q_lo - q.dev <= 0) or np.any(q_hi >= 4):
        raise ValueError("the domain's normals must be longer than the rounding of their codes, and "
                         "shorter than 2")
    return Interval(q_lo, q_hi, q.err, q.fmt, q.faults, q.terms)


def length_cases(q):
    """``q`` split where its range meets a power of 4, below and above it (the even shift's
    mantissa jumps there from near 1 to 1/4, and with it the seed table's error and ``y1``): two
    Intervals (B,), the same where the range holds no power of 4."""
    edge = 4.0 ** ((np.frexp(q.hi)[1] - 1) // 2)
    across = (q.lo < edge) & (edge <= q.hi)
    below = Interval(q.lo, np.where(across, edge * (1 - 1e-15), q.hi), q.err, q.fmt, q.faults, q.terms)
    above = Interval(np.where(across, edge, q.lo), q.hi, q.err, q.fmt, q.faults, q.terms)
    return below, above


def inverse_length(config, q):
    """``(k, y_max)``: the hardware's ``k = 2^(j-h)·y1`` (B,) for ``q = N·N`` (an Interval in
    :data:`SYMBOLS`, :func:`squared_length`) against the ideal ``1/|N'|`` (module docstring),
    and a bound on ``y1`` itself."""
    f_lo, f_hi, m_min = rsqrt_factor(config, (q.lo, q.hi))
    dev = q.dev
    low = q.lo - dev
    mid = q.mid
    slope = -0.5 * mid ** -1.5
    # the slope of q^-1/2 is monotone: its spread over the range is largest at an end
    spread = np.maximum(np.abs(-0.5 * low ** -1.5 - slope), np.abs(-0.5 * (q.hi + dev) ** -1.5 - slope))
    # r·q^-1/2 with r = r_mid + r_rad·ε: about the middle of q^-1/2's range, the rest as remainder
    g_lo, g_hi = q.hi ** -0.5, q.lo ** -0.5
    g_mid, r_mid, r_rad = (g_lo + g_hi) / 2, (f_lo + f_hi) / 2 - 1, (f_hi - f_lo) / 2
    table = np.maximum(np.abs(f_lo - 1), np.abs(f_hi - 1)) * (g_hi - g_lo) / 2
    err = np.abs(slope) * q.err + spread * dev + table
    terms = q.terms * slope[..., None]
    terms[..., OFFSET] += r_mid * g_mid
    terms[..., TABLE] += r_rad * g_mid
    k = Interval(f_lo * g_lo, f_hi * g_hi, err * (1 + 1e-12), config.fmt("y"), q.faults, terms)
    y_max = f_hi / np.sqrt(m_min) * (1 + 1e-12)  # y1 = (1 + r)/sqrt(m)
    return k, y_max


def rounded(x, error):
    """``x`` after a rounding that moves it by at most ``error``."""
    return Interval(x.lo - error, x.hi + error, (x.err + error) * (1 + 1e-12), x.fmt, x.faults, x.terms)


def cosine(config, normal, k, y_max, vector, fmt, ideal=None):
    """``round(round(N·X·2^(j-h))·y1)`` in ``fmt`` before its clamps: ``N·X`` exact (``vector``
    the constant ``X`` as an Interval, its code's distance to the exact one as remainder, or a
    local one over its cone, :mod:`.local_vectors`),
    times ``k``, and the two roundings.  The scaled ``N·X`` must fit ``dot`` (it does for
    ``|X| < 2``: ``|N·X·2^(j-h)| <= sqrt(m)·|X|``).  Its rounding to ``dot`` costs nothing where
    it is on ``dot``'s grid already: with ``X``'s codes multiples of ``2^t`` LSBs, ``N·X`` is on
    a grid of ``2F - t`` fraction bits, and ``2^(j-h)`` moves it right by at most one bit
    (``q < 4``), so an axis-aligned viewer's ``N·V`` is exact there; a vector over a cone takes
    any codes (``t = 0``).  ``ideal``: ``(lo, hi)``, where the ideal ``N'·X`` is known to lie (the
    geometry's range, :meth:`~.interval.Interval.within`), which keeps a vector over a cone from
    widening the product's remainders by the whole of its hull."""
    dot = config.fmt("dot")
    d = normal.dot(vector)
    if ideal is not None:
        d = d.within(*ideal)
    c = d * k
    faults = c.faults
    if np.max(np.linalg.norm(vector.magnitude, axis=-1)) >= dot.max_raw * dot.lsb:
        faults = faults | {"blinn d'"}
    frac = normal.fmt.frac_bits
    codes = np.round(np.asarray(vector.lo).reshape(-1, 3)[0] * 2.0 ** frac).astype(np.int64)
    codes = codes[codes != 0]
    zeros = min(((int(x) & -int(x)).bit_length() - 1 for x in codes), default=None)
    if np.any(vector.lo != vector.hi):  # a vector over a cone (a local L or V): any codes
        zeros = 0
    scaled = 0.0 if zeros is None else rounding_error(Format(2, 2 * frac - zeros + 1, signed=True), dot,
                                                      config.rounding)  # X = 0: N·X = 0, exact
    error = y_max * scaled + rounding_error(_EXACT, fmt, config.rounding)
    c = rounded(c, error)
    return Interval(c.lo, c.hi, c.err, fmt, faults, c.terms)


def clamp(x, low=-np.inf, high=np.inf):
    """``x`` clamped to ``[low, high]``, against an ideal inside it (module docstring)."""
    inside = (x.lo >= low) & (x.hi <= high)
    err = np.where(inside, x.err, x.dev)
    terms = None if x.terms is None else np.where(inside[..., None], x.terms, 0.0)
    return Interval(np.clip(x.lo, low, high), np.clip(x.hi, low, high), err, x.fmt, x.faults, terms)
