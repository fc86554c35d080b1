"""Golden model of the root-shininess specular unit, Lyon (1993) Figure 8.

"Hardware Rearrangements for Bit Reductions": shininess is given as ``m = √n`` and
``x = (n/2)·D·D = ½·Σ(m·D_i)²``, so ``m`` scales the three components of ``D``
instead of ``n`` scaling ``D·D``.  ``D`` is rectified, multiplied by ``m``, and only
the fraction of each scaled component enters the dot product; an "augmented
comparator" zeroes the output when any integer part is non-zero.  Figure 7d follows.

The figure's bit annotations are lost from our copy; the text names "six 7×11 and
9×9 multipliers" (three of each).  Our reconstruction, defaults in brackets:

* ``D = R - L`` exact in ``S2.10``, saturated to ``d`` [``S1.10``], as in Figure 7c;
* rectifier: ``|D_i|`` in the unsigned format of ``d`` [``1.10``, the "11"]; ``D_i = -2``
  (α = 180°) saturates to ``2 - 2^-10``, as ``+2`` already did in ``D``;
* three ``m × |D_i|`` multipliers [``6.0 × 1.10``, the "7×11" counting a sign bit as the
  paper's "14×22" does; ``m >= 1`` and ``|D_i| >= 0`` need none], exact [``7.10``];
* ``u_i = m|D_i|/2^s`` moves the point only [``(7-s).(10+s)``], with ``s = ceil((k+1)/2)``
  (:attr:`RootConfig.shift`).  Then ``Σu_i² = (2x)/2^(2s)`` and, with ``c = 2^(2s-1-k)``,
  ``x/2^k = c·Σu_i²``; ``2s >= k+1`` makes ``c`` 1 (``k`` odd) or 2 (``k`` even).  For
  ``k = 1``: ``s = 1``, ``c = 1``, ``Σu_i² = x/2`` exactly.  (The text says the dot product
  "corresponds to x/4"; for ``k = 1`` a whole-bit shift gives ``x/2`` or ``x/8``, so we
  take the ``s`` that lets the comparator see ``x/2^k`` itself.)
* augmented comparator: ``big = any(u_i >= 1)``.  If ``u_j >= 1`` then
  ``x/2^k = c·Σu_i² >= c·u_j² >= c >= 1``, where ``f_k = 0``: zeroing is exact, not
  only a guard for the integer bits the dot product drops;
* each ``u_i`` truncated to its first fraction bits ``frac`` [``0.9``: 2 of ``10+s``
  dropped for ``k = 1``], three squarers [the "9×9"] exact in ``0.18``, their sum exact in
  ``2.18``; moving the point ``2s`` places gives ``2x`` [``4.16`` for ``k = 1``], the input
  of Figure 7d (:func:`phongfx.golden.shape.shape` with :attr:`RootConfig.shape`), whose
  comparator zeroes ``c·Σu_i'² >= 1``;
* the output multiplexer gives 0 where ``big``, else the shape output [``t`` = ``1.15``].

Error against float ``f_k(x)``, ``x = (m²/2)|R-L|²`` on the same codes, when nothing
saturates: truncation gives ``0 <= u_i - u_i' < 2^-f`` (``f`` = fraction bits of
``frac``), so the ``v = x/2^k`` the shape sees is low by ``Δ < c·2^(1-f)·Σu_i <=
2^(1-f)·√(3cv)``, and the output high by at most ``2^k·(1-v+Δ)^(2^k-1)·Δ`` plus the
shape's own ``(2^(k+1) - 1)/2`` LSB (its ``1 - u`` is rounded here).  The worst case,
three equal components each truncated by a whole ``2^-f``, is 2.4, 1.3, 2.3, 2.2, 4.3
levels of 255 for k = 0..4 (``u_i`` holds ``m|D_i|`` to ``2^(s-f)``, coarser as ``s``
grows, and ``c = 2`` scales ``Δ`` by √2).  The same ``Δ`` leaves a sliver past
``x/2^k = 1`` where the output is not yet 0, at most ``Δ^(2^k)``: 2.4 levels for
``k = 0``, 1.5 LSB of ``1.15`` for ``k = 1``, under 0.001 LSB for ``k >= 2``.  Truncation only
ever lowers ``x``, so the output is never below float ``f_k`` by more than the shape's
rounding.  Measured (every ``m``, ``|D|`` code by code along the diagonal and six random
directions): 1.82, 1.00, 2.04, 1.95, 4.02 levels for k = 0..4.

Against Figure 7 (:mod:`~phongfx.golden.difference` with ``n = m²``, then the shape) on
the same codes, whose ``2x`` is within ``2^-13`` of exact, the difference is this
truncation: the ``s+1`` low bits of ``m|D_i|`` (in ``2^-10``) dropped.  Measured on random
unit pairs near the peak, every ``m``: up to 1.77, 0.98, 1.89, 1.88, 3.67 levels, worst at
small or odd ``m``, near nothing where ``m`` is a multiple of ``2^(s+1)`` (no bits to drop).
"""

import numpy as np

from phongfx.core.format import Format

from .fixed import Fixed
from .shape import shape
from .shininess import shininess_input

__all__ = ["root"]


def root(config, r, l, m=None):
    """Specular amount ``f_k(x)``, ``x = (m²/2)·|R-L|²``, by Figure 8's datapath.

    Parameters
    ----------
    config : RootConfig
    r, l : Fixed, shape (count, 3), format ``config.vec``
    m : Fixed, shape (count,), format ``config.m``, integers 1..``config.m_max``
        Exactly when ``config.m_const`` is 0 (``m`` is a port); otherwise None: ``m`` is
        ``m_const`` in format ``m``, the same codes as feeding it on the port
        (:func:`~phongfx.golden.shininess.shininess_input`).

    Returns
    -------
    dict
        ``{"spec": Fixed (count,) in config.t}``
    """
    m = shininess_input(config, m, len(r))
    d = (r - l).quantize(config.d, config.rounding, "saturate", op="root D")
    # rectifier: negator and multiplexer; only D = -2^int_bits saturates into the unsigned twin
    neg = -d
    wide = d.quantize(neg.fmt, config.rounding, "error", op="root D")
    mag = neg.where(d < 0, wide).quantize(Format(d.fmt.int_bits, d.fmt.frac_bits),
                                          config.rounding, "saturate", op="root |D|")
    u = (mag * m[:, None]) >> config.shift
    big = np.any(u >= 1, axis=-1)
    # integer bits go to the comparator only: the squarers see the fraction, truncated
    frac = u.quantize(config.frac, "truncate", "wrap", op="root u")
    x2 = frac.dot(frac) << 2 * config.shift
    spec = shape(config.shape, x2)["spec"]
    return {"spec": Fixed.const(0, config.t).where(big, spec)}
