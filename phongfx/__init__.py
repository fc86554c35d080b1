"""phongfx: bit-accurate fixed-point Phong-shading datapaths with HDL generation.

The package is a house of layers; each may import only the layers before it:

========================  ===============================================================
``phongfx.core``          formats (Lyon's ``n.m`` / ``Sn.m``), atomic files, the block registry
``phongfx.config``        one configuration module per block: plain data, validated
``phongfx.golden``        what the numbers must be: numpy models on raw integer codes
``phongfx.hdl``           the hardware: Amaranth twins of the golden models
``phongfx.sim``           checking one against the other, cycle by cycle; stimulus
``phongfx.scene``         Lyon's scene, scene files, meshes, per-frame geometry, span inputs
``phongfx.render``        pictures: shading scenes and meshes through the blocks
``phongfx.deliver``       what ships with a compiled core: input contract, constraints, cores
``phongfx.papers``        the seed papers' claims and tables, measured
``phongfx.explore``       synthesis, cost models, sweeps, reports and the scene compiler's parts
``phongfx.certify``       sound bounds on a design's error over a scene's input domain
``phongfx.compiler``      the scene compiler: ``compile_scene`` on a ``CompileRequest``, certified
``phongfx.cli``           the ``phongfx`` command line
========================  ===============================================================

``golden/``, ``hdl/`` and ``sim/`` are top-level folders of the repository, installed as
``phongfx.golden``, ``phongfx.hdl`` and ``phongfx.sim``.  The registry, ``core``, loads
each block's faces by name on first use, so it sits at the bottom without importing the
layers above it.  ``phongfx.certify`` bounds a design through the compile room of
``phongfx.explore`` (how a method is fitted to a scene), and ``phongfx.compiler`` above it puts
that room and the certificates together; ``phongfx.explore``'s own rooms are layered the same
way (its ``__init__.py`` lists them).

The names below are the everyday entry points, imported on first use (importing
``phongfx`` itself loads nothing else): :func:`get_block` and :func:`block_names` (the
registry), :class:`Format`, the datapath configurations of Lyon's Figures 7, 8 and 5, and
:func:`load_core` (a compiled output folder as an Amaranth component with stream interfaces).
"""

from importlib import import_module

#: public name -> the module it lives in
_HOMES = {"Format": "phongfx.core.format", "get_block": "phongfx.core.registry",
          "block_names": "phongfx.core.registry", "DatapathConfig": "phongfx.config",
          "fig7_config": "phongfx.config", "fig8_config": "phongfx.config",
          "halfway_config": "phongfx.config", "load_core": "phongfx.deliver.component"}
__all__ = list(_HOMES)


def __getattr__(name):
    if name not in _HOMES:
        raise AttributeError(f"module 'phongfx' has no attribute {name!r}")
    return getattr(import_module(_HOMES[name]), name)
