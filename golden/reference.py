"""Floating-point reference for the twelve specular methods of Lyon (1993).

Richard F. Lyon, "Phong Shading Reformulation for Hardware Renderer
Simplification", Apple Technical Report #43, August 1993.  :func:`specular_all`
transcribes the appendix function ``specfuns.m`` statement by statement; its
methods are rows 1-12 of Figure 9, in order (:data:`METHODS`).  The printed code
is followed even where it differs from the prose, so that this module can be
the oracle against which the fixed-point models are judged:

* ``H = (L + V) / 2`` (the text's ``V + L``, halved), so ``|H| <= 1``; every
  halfway method (rows 5-12) uses ``n4 = 4 n``, except row 12, which uses ``n``.
* Comparisons are the printed ``>``: ``f_k(x)`` is zeroed only for ``x > 2**k``
  (at ``x == 2**k`` the other branch gives 0 too, so ``f_k`` stays continuous).
* Rows 11 and 12 reuse ``dot = hv2 . N`` from row 5: the listing's
  ``%dot = sum(hv2.*nv);`` is commented out.
* In the listing a stray ``end;`` precedes row 12's store; Figure 9 shows
  twelve rows, so row 12 is kept.

A zero-length halfway vector (``L == -V``, or ``hl`` underflowing to 0) makes
MATLAB's ``1/sqrt(hl)*hv`` NaN.  Here the reciprocal length is taken as 0
instead, so ``hv2`` is the zero vector and ``dot`` is 0: Blinn gives 0, row 6
sees ``D = -N``, row 11 ``alpha = pi/2`` and row 12 its floor ``(1/(1+n))**2``.
No floating-point warning is raised.
"""

import re

import numpy as np

__all__ = ["METHODS", "SHAPE_FORMS", "specular", "specular_all"]

METHODS = (
    "phong",              # 1. (R.L)^n
    "lyon-k0",            # 2. f_0(x), D = L - R
    "lyon-k1",            # 3. f_1(x)
    "lyon-k2",            # 4. f_2(x)
    "blinn",              # 5. (H*.N)^(4n), Blinn D1
    "halfway-hnorm-k2",   # 6. D = H* - N
    "halfway-proj-k2",    # 7. D = H - projection
    "halfway-g2proj-k2",  # 8. D = H g2(z) - projection
    "halfway-g2proj-k1",  # 9. same D, k = 1
    "halfway-g2-k2",      # 10. D = H g2(z) - N
    "torrance-sparrow",   # 11. Blinn D2, Gaussian
    "trowbridge-reitz",   # 12. Blinn D3
)


#: Rows 2-4 and 8-9 at any ``k``: ``lyon-k<k>`` and ``halfway-g2proj-k<k>`` (the
#: appendix prints k = 0..2 and 1..2; the datapaths' shape function takes k up to 10,
#: and each datapath's float form is the same row at the datapath's own k).
SHAPE_FORMS = re.compile(r"^(lyon|halfway-g2proj)-k(\d+)$")


def _dot(a, b):
    # Summed left to right, as MATLAB's row-times-column product of 3-vectors.
    return a[..., 0] * b[..., 0] + a[..., 1] * b[..., 1] + a[..., 2] * b[..., 2]


def _power_if_positive(dot, e):
    """``dot**e`` where ``dot > 0``, else 0 (rows 1 and 5)."""
    # Base 1 where the answer is 0 anyway, so pow never sees 0**-e or a NaN.
    return np.where(dot > 0, np.where(dot > 0, dot, 1.0) ** e, 0.0)


def _shape(xs, k):
    """Lyon's ``f_k``: 0 if ``xs > 2**k``, else ``1 - xs/2**k`` squared k times."""
    big_k = 2.0 ** k
    # Zeroed before squaring so that a huge xs cannot overflow the squares.
    amount = np.where(xs > big_k, 0.0, 1.0 - xs / big_k)
    for _ in range(k):
        amount = amount * amount
    return amount


def _intermediates(N, L, V, n):
    """The listing's shared vectors: ``rv``, ``hv``, ``hv1`` (``g2``-normalized), ``hv2``
    (unit) and ``n4``, with the inputs as float arrays."""
    N, L, V = (np.asarray(a, dtype=np.float64) for a in (N, L, V))
    for name, a in (("N", N), ("L", L), ("V", V)):
        if a.ndim == 0 or a.shape[-1] != 3:
            raise ValueError(f"{name} must have shape (..., 3), got {a.shape}")
    n = np.asarray(n, dtype=np.float64)

    rv = 2 * N * _dot(V, N)[..., None] - V
    hv = (L + V) / 2
    hl = _dot(hv, hv)
    dl = 1 - hl
    hv1 = (1 + 0.5 * (dl + dl * dl))[..., None] * hv
    # hl == 0: a zero reciprocal length (not NaN) gives hv2 = 0 and dot = 0;
    # ``where`` skips the division there, so no divide-by-zero warning.
    rlen = np.divide(1.0, np.sqrt(hl), out=np.zeros_like(hl), where=hl > 0)
    hv2 = rlen[..., None] * hv
    n4 = 4 * n
    return N, L, V, n, rv, hv, hv1, hv2, n4


def _lyon_xs(L, rv, n):
    """Row 2's ``x = n/2·|L - R|²``, what ``f_k`` is applied to."""
    dv = L - rv
    return _dot(dv, dv) * n / 2


def _g2proj_xs(N, hv1, n4):
    """Row 8's ``x = 4n/2·|H g2(z) - projection|²``."""
    dv = hv1 - N * _dot(hv1, N)[..., None]
    return _dot(dv, dv) * n4 / 2


def specular_all(N, L, V, n):
    """Evaluate every method of ``specfuns.m``, sharing its intermediates.

    Parameters
    ----------
    N, L, V : array_like, shape (..., 3)
        Surface normal, light and viewpoint vectors (unit length in the paper,
        but used as given).  Leading dimensions broadcast against each other.
    n : float or array_like
        Shininess; broadcast against the leading shape.

    Returns
    -------
    dict of str to ndarray
        Specular amount of each method, keyed and ordered as :data:`METHODS`,
        each of the broadcast leading shape, float64.
    """
    N, L, V, n, rv, hv, hv1, hv2, n4 = _intermediates(N, L, V, n)

    out = {}
    out["phong"] = _power_if_positive(_dot(rv, L), n)
    xs = _lyon_xs(L, rv, n)
    out["lyon-k0"], out["lyon-k1"], out["lyon-k2"] = (_shape(xs, k) for k in (0, 1, 2))

    dot = _dot(hv2, N)
    out["blinn"] = _power_if_positive(dot, n4)
    dv = hv2 - N
    out["halfway-hnorm-k2"] = _shape(_dot(dv, dv) * n4 / 2, 2)
    dv = hv - N * _dot(hv, N)[..., None]
    out["halfway-proj-k2"] = _shape(_dot(dv, dv) * n4 / 2, 2)
    xs = _g2proj_xs(N, hv1, n4)
    out["halfway-g2proj-k2"] = _shape(xs, 2)
    out["halfway-g2proj-k1"] = _shape(xs, 1)  # row 9 reuses row 8's xs, as printed
    dv = hv1 - N
    out["halfway-g2-k2"] = _shape(_dot(dv, dv) * n4 / 2, 2)

    # Rows 11-12 keep row 5's dot.  The clip is not in the listing: it only stops
    # rounding (or a non-unit N) from pushing acos outside its domain into NaN.
    alpha = np.arccos(np.clip(dot, -1.0, 1.0))
    out["torrance-sparrow"] = np.exp(-(n4 / 2) * alpha * alpha)
    out["trowbridge-reitz"] = np.where(
        dot > 0, (1 / (1 + (1 - dot * dot) * n)) ** 2, (1 / (1 + n)) ** 2)
    return {m: np.asarray(out[m]) for m in METHODS}


def specular(method, N, L, V, n):
    """Specular amount of one method of ``specfuns.m``.

    Parameters
    ----------
    method : str
        One of :data:`METHODS`, or a row of :data:`SHAPE_FORMS` at another ``k``.
    N, L, V, n
        As for :func:`specular_all`.

    Returns
    -------
    ndarray
        The amount, of the broadcast leading shape, float64.

    Raises
    ------
    ValueError
        If ``method`` is not in :data:`METHODS`.
    """
    form = SHAPE_FORMS.match(method)
    if form and method not in METHODS:
        N, L, V, n, rv, _hv, hv1, _hv2, n4 = _intermediates(N, L, V, n)
        xs = _lyon_xs(L, rv, n) if form[1] == "lyon" else _g2proj_xs(N, hv1, n4)
        return np.asarray(_shape(xs, int(form[2])))
    if method not in METHODS:
        raise ValueError(
            f"unknown specular method {method!r}; valid methods: {', '.join(METHODS)}")
    # One implementation: the single method is read out of the shared evaluation.
    return specular_all(N, L, V, n)[method]
