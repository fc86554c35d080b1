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

import functools
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


class _Listing:
    """The listing's inputs as float arrays and its shared intermediates, each computed when a
    row first asks for it (one row alone, as the compiler asks, skips the others' work):
    ``rv``, ``hv``, ``hv1`` (``g2``-normalized), ``hv2`` (unit), ``n4`` and row 5's ``dot``."""

    def __init__(self, N, L, V, n):
        N, L, V = (np.asarray(a, dtype=np.float64) for a in (N, L, V))
        for name, a in (("N", N), ("L", L), ("V", V)):
            if a.ndim == 0 or a.shape[-1] != 3:
                raise ValueError(f"{name} must have shape (..., 3), got {a.shape}")
        self.N, self.L, self.V, self.n = N, L, V, np.asarray(n, dtype=np.float64)

    @functools.cached_property
    def rv(self):
        return 2 * self.N * _dot(self.V, self.N)[..., None] - self.V

    @functools.cached_property
    def hv(self):
        return (self.L + self.V) / 2

    @functools.cached_property
    def hl(self):
        return _dot(self.hv, self.hv)

    @functools.cached_property
    def hv1(self):
        dl = 1 - self.hl
        return (1 + 0.5 * (dl + dl * dl))[..., None] * self.hv

    @functools.cached_property
    def hv2(self):
        # hl == 0: a zero reciprocal length (not NaN) gives hv2 = 0 and dot = 0;
        # ``where`` skips the division there, so no divide-by-zero warning.
        hl = self.hl
        rlen = np.divide(1.0, np.sqrt(hl), out=np.zeros_like(hl), where=hl > 0)
        return rlen[..., None] * self.hv

    @functools.cached_property
    def n4(self):
        return 4 * self.n

    @functools.cached_property
    def dot(self):
        return _dot(self.hv2, self.N)

    @functools.cached_property
    def alpha(self):
        # Rows 11-12 keep row 5's dot.  The clip is not in the listing: it only stops
        # rounding (or a non-unit N) from pushing acos outside its domain into NaN.
        return np.arccos(np.clip(self.dot, -1.0, 1.0))

    @functools.cached_property
    def lyon_xs(self):
        """Row 2's ``x = n/2·|L - R|²``, what ``f_k`` is applied to."""
        dv = self.L - self.rv
        return _dot(dv, dv) * self.n / 2

    @functools.cached_property
    def g2proj_xs(self):
        """Row 8's ``x = 4n/2·|H g2(z) - projection|²``."""
        dv = self.hv1 - self.N * _dot(self.hv1, self.N)[..., None]
        return _dot(dv, dv) * self.n4 / 2


def _squared_shape(d, n4, k):
    """``f_k`` of ``|d|²·4n/2`` (rows 6, 7 and 10)."""
    return _shape(_dot(d, d) * n4 / 2, k)


#: Each row of Figure 9 from the shared :class:`_Listing`, statement by statement as printed.
_ROWS = {
    "phong": lambda s: _power_if_positive(_dot(s.rv, s.L), s.n),
    "lyon-k0": lambda s: _shape(s.lyon_xs, 0),
    "lyon-k1": lambda s: _shape(s.lyon_xs, 1),
    "lyon-k2": lambda s: _shape(s.lyon_xs, 2),
    "blinn": lambda s: _power_if_positive(s.dot, s.n4),
    "halfway-hnorm-k2": lambda s: _squared_shape(s.hv2 - s.N, s.n4, 2),
    "halfway-proj-k2": lambda s: _squared_shape(s.hv - s.N * _dot(s.hv, s.N)[..., None], s.n4, 2),
    "halfway-g2proj-k2": lambda s: _shape(s.g2proj_xs, 2),
    "halfway-g2proj-k1": lambda s: _shape(s.g2proj_xs, 1),  # row 9 reuses row 8's xs, as printed
    "halfway-g2-k2": lambda s: _squared_shape(s.hv1 - s.N, s.n4, 2),
    "torrance-sparrow": lambda s: np.exp(-(s.n4 / 2) * s.alpha * s.alpha),
    "trowbridge-reitz": lambda s: np.where(s.dot > 0, (1 / (1 + (1 - s.dot * s.dot) * s.n)) ** 2,
                                           (1 / (1 + s.n)) ** 2),
}


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
    shared = _Listing(N, L, V, n)
    return {m: np.asarray(_ROWS[m](shared)) for m in METHODS}


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
        shared = _Listing(N, L, V, n)
        return np.asarray(_shape(shared.lyon_xs if form[1] == "lyon" else shared.g2proj_xs, int(form[2])))
    if method not in METHODS:
        raise ValueError(
            f"unknown specular method {method!r}; valid methods: {', '.join(METHODS)}")
    # One implementation: the row alone, from the same shared intermediates as specular_all.
    return np.asarray(_ROWS[method](_Listing(N, L, V, n)))
