"""Checking the hardware against the golden models, cycle by cycle.

:mod:`.harness` drives a block's component with stimulus (:mod:`.stimulus`), valid
bubbles included (and, in its stream mode, back-pressure and a reset), and compares every
output cycle with the golden model, on one of three back ends: Amaranth's simulator
(:mod:`.amaranth_backend`), the emitted Verilog under cocotb and Verilator
(:mod:`.verilator_backend`, :mod:`.cocotb_tb`), and Verilator with a compiled checker
(:mod:`.fast_backend`); the two Verilator back ends share the build cache of
:mod:`.build_cache`.

Installed as ``phongfx.sim`` from the ``sim/`` folder, so a module reaches another layer
by an absolute ``phongfx.`` import.  May import: ``phongfx.core``, ``phongfx.config``,
``phongfx.golden``, ``phongfx.hdl``.
"""
