"""Checking the hardware against the golden models, cycle by cycle.

:mod:`.harness` drives a block's component with stimulus (:mod:`.stimulus`), valid
bubbles included (and, in its stream mode, back-pressure and a reset), and compares every
output cycle with the golden model, on one of three back ends: Amaranth's simulator
(:mod:`.amaranth_backend`), the emitted Verilog under cocotb and Verilator
(:mod:`.verilator_backend`, :mod:`.cocotb_tb`), and Verilator with a compiled checker
(:mod:`.fast_backend`); the two Verilator back ends share the build cache of
:mod:`.build_cache`.  Below the harness, what every back end shares: :mod:`.vectors`
(payload words, the per-cycle schedule), :mod:`.result` (what a check found) and
:mod:`.stream` (the stream mode's plan and driver).

:mod:`.testbench` writes a self-checking Verilog testbench of a block's shipped top (its
text: :mod:`.verilog_tb`), :mod:`.simulators` runs it under Icarus Verilog or Verilator.
:mod:`.prove` proves the overflow checks with SymbiYosys, :mod:`.dsp_equivalence` the
ECP5 DSP mapping of the products.

Installed as ``phongfx.sim`` from the ``sim/`` folder, so a module reaches another layer
by an absolute ``phongfx.`` import.  May import: ``phongfx.core``, ``phongfx.config``,
``phongfx.golden``, ``phongfx.hdl``.
"""
