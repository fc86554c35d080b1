"""Back end: Amaranth's own simulator (pure Python, no external tools)."""

from amaranth.sim import Simulator

__all__ = ["run"]


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

    sim = Simulator(component)
    sim.add_clock(1e-8)
    sim.add_testbench(testbench)
    if vcd:
        with sim.write_vcd(vcd):
            sim.run()
    else:
        sim.run()
    return out_valid, out_payload
