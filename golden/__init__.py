"""What the numbers must be: the golden models, numpy functions on raw integer codes.

One module per block, named like its config, hdl and stimulus modules: each takes the
block's configuration and its inputs as ``int64`` arrays of raw fixed-point codes and
returns the outputs bit for bit as the hardware must give them (Lyon 1993, Figures 5–8;
Szirmay-Kalos et al. 2000; Hast et al.; Schlick 1994), together with the float
references (:mod:`.reference`) and the scanline setups the units are fed from.
:mod:`.fixed` is the shared arithmetic: :class:`~phongfx.golden.fixed.Fixed` arrays whose
every narrowing names its rounding and overflow policy, raising on an undeclared overflow.

Installed as ``phongfx.golden`` from the ``golden/`` folder, so a module reaches another
layer by an absolute ``phongfx.`` import.  May import: ``phongfx.core``, ``phongfx.config``.
"""
