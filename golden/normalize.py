"""Golden model of the approximate normalizer, Lyon (1993) Figure 7a: ``N = g(z)·N'``.

``z = N'·N'`` and ``y = 1 - z``; Lyon's section "Approximate Normalization" gives the
first- and second-order stand-ins for ``1/sqrt(z)``::

    g1 = 1 + y/2            g2 = 1 + (y + y²)/2

Bit growth (defaults).  Figure 7a's bit annotations are lost from our copy, so these
formats are our reconstruction (:class:`~phongfx.config.NormalizeConfig`):

* ``z``: each square ``S1.10 × S1.10`` is exact in ``S3.20``, their sum in ``S5.20``;
  one rounding to ``1.12`` keeps two guard bits over the vector's LSB.  A unit
  ``N'`` has ``z <= 1``; ``z >= 2`` only for junk codes (up to 12), so saturate.
* ``y = 1 - z`` is exact in ``S1.12``: ``-1 < y <= 1``.
* ``y²`` (order 2 only) is exact in ``S3.24``, rounded to ``y2 = 1.12``.  With one
  integer bit in ``z``, ``|y| <= 1`` so ``y² <= 1``, which every ``y2`` holds: the
  quantize declares ``overflow="error"`` (see :attr:`NormalizeConfig.y2_overflow`).
* ``g``: ``1 + (y + y²)/2`` is exact in ``S2.13`` and rounded to ``1.12``; ``g1 <= 1.5``
  but ``g2`` reaches 2.0 at ``z = 0`` and saturates to ``2 - 2**-12``.  That happens
  only when ``N'`` rounds to ``z = 0`` (``|N'|`` under about ``2**-6.5``), where
  ``g·N'`` is within 0.01 LSB of ``2·N'``: rounding to nearest gives exactly ``2·N'``,
  truncation one LSB less on positive components, and ``N' = 0`` still gives 0.
* ``N = g·N'``, exact in ``S2.22``, rounded to ``out = S1.10`` and saturated.  At the
  defaults that never triggers (junk saturates ``z``, where ``g2 -> 1`` and ``g1 -> 0.5``,
  so ``N`` stays in ``N'``'s range); it guards narrower ``out`` and wider ``z`` formats.
"""

from .fixed import Fixed

__all__ = ["normalize"]



def normalize(config, n):
    """Approximately normalize ``n`` (``config.order`` 1 or 2 selects ``g1`` or ``g2``).

    Parameters
    ----------
    config : NormalizeConfig
    n : Fixed, shape (count, 3), format ``config.vec``

    Returns
    -------
    dict
        ``{"n": Fixed (count, 3) in config.out}``
    """
    cfg = config
    z = n.dot(n).quantize(cfg.z, cfg.rounding, "saturate", op="normalize z")
    y = Fixed.const(1, cfg.z) - z
    if cfg.order == 1:
        half = y
    else:
        half = y + (y * y).quantize(cfg.y2, cfg.rounding, cfg.y2_overflow, op="normalize y²")
    g = (Fixed.const(1, cfg.g) + half.shift(-1)).quantize(cfg.g, cfg.rounding, "saturate",
                                                          op="normalize g")
    return {"n": (n * g[:, None]).quantize(cfg.out, cfg.rounding, "saturate", op="normalize N")}
