"""The hardware: Amaranth components, twins of the golden models, and their Verilog.

One module per block, named like its config, golden and stimulus modules: a
:class:`~phongfx.hdl.block.PipelinedBlock` whose ports come from the block's
configuration (:mod:`.block`), built from the fixed-point values of :mod:`.fixed` (the
same formats and rounding as :mod:`phongfx.golden.fixed`, narrowed by :mod:`.quantize`,
with pipeline registers placed by cycle tags) and carrying the simulation-only overflow assertions of :mod:`.overflow`; every variable
product goes through :mod:`.dsp`, which maps it onto an ECP5 MULT18X18D with the pipeline's
registers inside when synthesis asks (``mult18x18d.v`` is that primitive's behavioural
model).  :mod:`.emit` writes a component as Verilog; :mod:`.identity` names a design without
elaborating it (its class, config and the digest of these sources), for the caches' keys.

Installed as ``phongfx.hdl`` from the ``hdl/`` folder, so a module reaches another layer
by an absolute ``phongfx.`` import.  May import: ``phongfx.core``, ``phongfx.config``,
``phongfx.golden`` (ROM and table contents are the golden model's own functions).
"""
