"""The seed papers' claims and tables, measured on our blocks (``phongfx tables NAME``).

One module or package per paper: :mod:`.lyon` (Apple TR #43: shape and normalizer
claims, span claims, Figure 9), :mod:`.szirmay` (Szirmay-Kalos et al. 2000: Table 1 and
the Figure 11 ROM error grid), :mod:`.hast` (Hast, Barrera, Bengtsson: Tables 1–2 on
rotating tori), :mod:`.schlick` (Schlick 1994: Figure 1); :mod:`.claims` holds the
table cells and verdicts they share.

May import: ``phongfx.core``, ``phongfx.config``, ``phongfx.golden``, ``phongfx.hdl``,
``phongfx.sim``, ``phongfx.scene``, ``phongfx.render``.
"""
