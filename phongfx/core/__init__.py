"""The floor everything stands on: fixed-point formats, atomic output files, the block registry.

* :mod:`.format`: :class:`~phongfx.core.format.Format`, Lyon's ``n.m`` / ``Sn.m``
  notation, the single source of truth for widths in the golden models and the HDL, and
  the rounding and overflow policies every narrowing names;
* :mod:`.files`: :func:`~phongfx.core.files.atomic_write`, so that no command leaves a
  half-written output;
* :mod:`.registry`: every block by name, its config, golden model, component, stimulus
  and extreme rows;
* :mod:`.words`: amounts in words, "1 level" and "2 levels".

May import: nothing of phongfx at module level.  The registry imports the faces of a
block (``phongfx.config``, ``phongfx.golden``, ``phongfx.hdl``, ``phongfx.sim``) by name
when a block is asked for, which keeps this layer at the bottom.
"""
