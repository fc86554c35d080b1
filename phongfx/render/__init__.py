"""Pictures: scenes and meshes shaded through the blocks, golden model and RTL.

* :mod:`.lyon`: ``make sim`` — Lyon's scene through the Figure 7 datapath, every pixel
  checked against the RTL, composed as in his appendix code; also the chunked shade
  (golden plus cycle check) the other renderers share;
* :mod:`.mesh`: a mesh frame by method (Phong, Gouraud, Euler, the spherical unit, …)
  with its error against Phong, and Szirmay-Kalos et al.'s Figures 14 and 15;
* :mod:`.frames`: full frames through the RTL of the scanline units.

May import: ``phongfx.core``, ``phongfx.config``, ``phongfx.golden``, ``phongfx.sim``,
``phongfx.scene``.
"""
