"""Back-pressure for a pipelined block: AXI-Stream ``valid``/``ready`` by a clock enable.

Every :class:`~phongfx.hdl.block.PipelinedBlock` takes one input per clock and never
stalls.  A user's design downstream may not take one output per clock, so
:class:`Handshake` wraps a block in Amaranth's :mod:`amaranth.lib.stream` conventions:
a transfer happens on a clock edge where ``valid`` and ``ready`` are both high, a
source holds ``valid`` and its payload until it is taken, and ``valid`` never waits
for ``ready``.

The simplest sound way is a clock enable on the whole pipeline (every register and
memory read port of the block and its sub-blocks, by
:class:`~amaranth.hdl.EnableInserter`)::

    enable = o.ready | ~o.valid
    i.ready = enable

When the output is valid and not taken, the pipeline holds: its registers keep their
values, so the output stays valid and stable, and no input is taken.  When the output
is empty the pipeline moves whatever ``o.ready`` says, so a bubble never blocks.
Nothing is lost or repeated.  ``i.ready`` follows ``o.ready`` through one gate (ready may
depend on ready, never on valid alone); ``o.valid`` comes from registers only.

The reset (the ``sync`` domain's, synchronous and active high) is not gated by the
enable: it clears the valid pipeline whatever ``o.ready`` is, and what was in flight
is dropped.

A block that takes an input at most once per ``interval`` clocks
(:attr:`~phongfx.hdl.block.PipelinedBlock.interval`, a shader whose lights take turns on one
unit) gets a counter of the cycles to wait, moved by the same enable::

    i.ready = enable & (wait == 0)

so ``i.ready`` is low while the block is busy with the turns of the last input, although
its pipeline moves; the reset clears the counter with everything else.

Latency: the block's own, counted in cycles where the pipeline moves.
"""

from amaranth.hdl import EnableInserter, Module, Signal
from amaranth.lib import stream, wiring
from amaranth.lib.wiring import In, Out

from .block import PipelinedBlock, checked_outputs, payload_layout

__all__ = ["Handshake"]


class Handshake(wiring.Component):
    """``block`` with ``i`` and ``o`` as :class:`amaranth.lib.stream.Signature` streams.

    Parameters
    ----------
    block : PipelinedBlock
        The block to wrap (at least one cycle of latency, so that ``o.valid`` comes
        from a register and the enable has no combinational loop).

    The payloads are the block's own: ``i.payload`` its inputs, ``o.payload`` its
    outputs and the overflow flag (:data:`~phongfx.hdl.block.OVERFLOW`).
    """

    def __init__(self, block):
        if not isinstance(block, PipelinedBlock):
            raise TypeError(f"block must be a PipelinedBlock, not {block!r}")
        if block.latency < 1:
            raise ValueError(f"block must have a latency of at least 1 cycle, not {block.latency}")
        self.block = block
        self.latency = block.latency
        self.interval = block.interval
        super().__init__({
            "i": In(stream.Signature(payload_layout(block.config.inputs))),
            "o": Out(stream.Signature(payload_layout(checked_outputs(block.config)))),
        })

    def elaborate(self, platform):
        m = Module()
        enable = Signal()
        m.submodules.block = EnableInserter(enable)(self.block)
        ready, valid = enable, self.i.valid
        if self.interval > 1:
            # cycles (where the pipeline moves) before the block takes its next input
            wait = Signal(range(self.interval), name="wait")
            with m.If(enable & self.i.valid & self.i.ready):
                m.d.sync += wait.eq(self.interval - 1)
            with m.Elif(enable & (wait != 0)):
                m.d.sync += wait.eq(wait - 1)
            ready = enable & (wait == 0)
            valid = self.i.valid & ready
        m.d.comb += [
            enable.eq(self.o.ready | ~self.o.valid),
            self.i.ready.eq(ready),
            self.block.i.valid.eq(valid),
            self.block.i.payload.eq(self.i.payload),
            self.o.valid.eq(self.block.o.valid),
            self.o.payload.eq(self.block.o.payload),
        ]
        return m
