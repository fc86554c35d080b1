"""Lyon 1993 (Apple TR #43), measured: ``phongfx tables lyon`` and ``phongfx figure9``.

* :mod:`.common`: the shape function ``f_k`` and normalizer ``g_k`` in float, angle and
  ``x`` conversions, the fixed-point shape run both tables share;
* :mod:`.shape`: Figure 3 (f_k against cos^n) and the sensitivity claims;
* :mod:`.normalize`: Figure 4 (g1, g2 against 1/√z) and the span claims;
* :mod:`.tables`: the claims table itself;
* :mod:`.figure9`: Figure 9's float rows and fixed-point rows, RTL-checked.

May import what :mod:`phongfx.papers` may.
"""
