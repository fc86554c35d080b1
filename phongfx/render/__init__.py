"""Pictures: scenes and meshes shaded through the blocks, golden model and RTL.

* :mod:`.lyon`: ``make sim`` — Lyon's scene through the Figure 7 datapath, every pixel
  checked against the RTL, composed as in his appendix code; also the chunked shade
  (golden plus cycle check) the other renderers share;
* :mod:`.mesh`: a mesh frame by method (Phong, Gouraud, Euler, the spherical unit, …)
  with its error against Phong, and Szirmay-Kalos et al.'s Figures 14 and 15;
* :mod:`.frames`: full frames through the RTL of the scanline units;
* :mod:`.figure`: pictures a person can read (titled, enlarged, error with a colour bar in
  8-bit levels, contact sheets), for these and for the scene compiler.

May import: ``phongfx.core``, ``phongfx.config``, ``phongfx.golden``, ``phongfx.sim``,
``phongfx.scene``.
"""
