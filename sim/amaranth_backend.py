"""Back end: Amaranth's own simulator (pure Python, no external tools)."""

from amaranth.hdl import ClockDomain, Module
from amaranth.sim import Simulator

__all__ = ["run", "run_stream"]


def run(component, in_valid, in_payload, cycles, *, vcd=None):
    """Drive ``component.i`` for ``cycles`` clocks; sample ``component.o`` each cycle.

    Inputs of cycle ``t`` are set, outputs are read once they settle, then the clock
    ticks: a registered output that reflects an input after ``latency`` ticks is read
    at cycle ``t + latency``.  ``vcd`` names a waveform file to write.
    """
    out_valid = [0] * cycles
    out_payload = [0] * cycles
    i_payload = component.i.payload.as_value()
    o_payload = component.o.payload.as_value()

    async def testbench(ctx):
        for cycle in range(cycles):
            ctx.set(component.i.valid, in_valid[cycle])
            ctx.set(i_payload, in_payload[cycle])
            out_valid[cycle] = ctx.get(component.o.valid)
            out_payload[cycle] = ctx.get(o_payload) & ((1 << len(o_payload)) - 1)
            await ctx.tick()

    _simulate(component, testbench, vcd)
    return out_valid, out_payload


def _simulate(design, testbench, vcd):
    """Run ``testbench`` on ``design`` with a 100 MHz clock, writing waveform ``vcd`` if given."""
    sim = Simulator(design)
    sim.add_clock(1e-8)
    sim.add_testbench(testbench)
    if vcd:
        with sim.write_vcd(vcd):
            sim.run()
    else:
        sim.run()


def run_stream(component, checker, *, vcd=None):
    """Run a :class:`~phongfx.hdl.handshake.Handshake` ``component`` under ``checker``, a
    :class:`~phongfx.sim.stream.StreamChecker`, until it says the run is over.

    The driver must see each cycle's ``i.ready`` before the edge (whether its vector is
    taken decides the next cycle's input), so inputs and outputs cannot be fixed lists as
    in :func:`run`.  The ``sync`` domain is declared here, not implied, so that its reset
    is a signal the testbench can drive.
    """
    top = Module()
    top.domains.sync = domain = ClockDomain("sync")
    top.submodules.dut = component
    i_payload = component.i.payload.as_value()
    o_payload = component.o.payload.as_value()
    mask = (1 << len(o_payload)) - 1

    async def testbench(ctx):
        cycle = 0
        going = True
        while going:
            rst, valid, payload, ready = checker.drive(cycle)
            ctx.set(domain.rst, rst)
            ctx.set(component.i.valid, valid)
            ctx.set(i_payload, payload)
            ctx.set(component.o.ready, ready)
            going = checker.observe(cycle, ctx.get(component.i.ready), ctx.get(component.o.valid),
                                    ctx.get(o_payload) & mask)
            await ctx.tick()
            cycle += 1

    _simulate(top, testbench, vcd)
