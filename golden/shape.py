"""Golden model of the shape function, Lyon (1993) Figure 7d: ``f_k(x) = (1 - x/2^k)^(2^k)``.

``f_k`` is taken as 0 once ``x/2^k >= 1`` ("Phong Specularity Reformulation"; the
appendix zeroes only ``x > 2^k``, but ``f_k(2^k) = 0`` too).  Figure 7d, for any
``k`` ("changing the shifter to shift by k+1 places and changing the number of
successive squaring multipliers to be k"):

* ``v = 2x >> (k+1) = x/2^k`` moves the point only: ``13.12`` becomes ``(12-k).(13+k)``;
* a comparator gives ``ge1 = (v >= 1)``;
* the "1-" block needs only the fraction ``u`` of ``v`` (its integer bits matter
  only when ``ge1`` zeroes the output anyway): ``1 - u`` lies in ``(0, 1]``, held
  in ``t`` = ``1.15`` (the integer bit holds 1.0 exactly, at ``x = 0``), rounded
  when ``13+k > 15``, i.e. for ``k >= 3``;
* ``k`` squarings ``1.15 × 1.15``, each exact in ``2.30`` and rounded back to ``1.15``
  (``t <= 1``, so ``t² <= 1`` cannot overflow);
* the output multiplexer gives 0 where ``ge1``, else ``t``.

Error against float ``f_k`` at the exact ``x`` of the code, with ``r`` the error of
one rounding (1/2 LSB of ``t``; 1 LSB for ``truncate``): ``1 - u`` costs ``e0`` (0
for ``k <= 2``, ``r`` otherwise), which doubles at each squaring (``d(t²) = 2t·dt``,
``t <= 1``), and each squaring adds ``r``: at most ``2^k·e0 + (2^k - 1)·r`` LSB.
Measured (round half up, every code): 0, 0.50, 1.42, 6.62, 12.45 LSB for k = 0..4.
Rounding and squaring are monotone, so the output never rises with ``x``.
"""

from phongfx.core.format import Format

from .fixed import Fixed

__all__ = ["shape"]


def shape(config, x2):
    """Specular amount ``f_k(x)`` for ``2x`` given as ``x2``.

    Parameters
    ----------
    config : ShapeConfig
    x2 : Fixed, shape (count,), format ``config.x2``

    Returns
    -------
    dict
        ``{"spec": Fixed (count,) in config.t}``
    """
    v = x2 >> (config.k + 1)
    ge1 = v >= 1
    u = v.quantize(Format(0, v.fmt.frac_bits), "truncate", "wrap", op="shape u")
    t = (Fixed.const(1, "1.0") - u).quantize(config.t, config.rounding, "error", op="shape 1-u")
    for _ in range(config.k):
        t = (t * t).quantize(config.t, config.rounding, "error", op="shape t²")
    return {"spec": Fixed.const(0, config.t).where(ge1, t)}
