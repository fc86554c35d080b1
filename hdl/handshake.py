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
        super().__init__({
            "i": In(stream.Signature(payload_layout(block.config.inputs))),
            "o": Out(stream.Signature(payload_layout(checked_outputs(block.config)))),
        })

    def elaborate(self, platform):
        m = Module()
        enable = Signal()
        m.submodules.block = EnableInserter(enable)(self.block)
        m.d.comb += [
            enable.eq(self.o.ready | ~self.o.valid),
            self.i.ready.eq(enable),
            self.block.i.valid.eq(self.i.valid),
            self.block.i.payload.eq(self.i.payload),
            self.o.valid.eq(self.block.o.valid),
            self.o.payload.eq(self.block.o.payload),
        ]
        return m
