"""A stream driver for :class:`~phongfx.deliver.component.ShadingCore` on Amaranth's simulator,
checking :mod:`amaranth.lib.stream`'s rules on every cycle as it goes.

The source side keeps the rules a source must (``valid`` held with its payload until taken,
whatever ``ready`` does; ``valid`` low in seeded bubbles between vectors); the sink side
drops ``o.ready`` on seeded stalls.  Every cycle it checks what the core must:

* ``o.valid`` does not depend on ``o.ready`` and ``i.ready`` not on ``i.valid`` (each read
  with the other at 0 and at 1 in the same cycle, settled);
* an ``o`` offer not taken (``o.valid & ~o.ready``) is offered again, unchanged, next cycle;
* two vectors taken are at least ``interval`` cycles apart.
"""

import json
from pathlib import Path

import numpy as np
from amaranth.sim import Simulator

from phongfx.sim.vectors import pack, unpack

__all__ = ["TWO_LIGHTS", "Run", "drive", "golden_words", "mismatches"]

#: The design fields of the manifest of ``phongfx compile scenes/two-lights.toml --methods
#: conventional --throughput 20`` (two lights taking turns on one conventional unit): the
#: default tier's compiled folders are made from them, without compiling.
TWO_LIGHTS = json.loads((Path(__file__).resolve().parent / "two_lights.json").read_text())


class Run:
    """What :func:`drive` saw: the output words in order, the cycles, the rule breaks."""

    def __init__(self):
        self.words, self.cycles, self.breaks, self.stalled = [], 0, [], 0
        self.taken = []  # the cycle each input vector was taken


def golden_words(core, raw):
    """``(input words, expected output words)`` of raw input codes ``raw`` for ``core``."""
    expected = core.block.golden(raw)
    return pack(core.config.inputs, raw), pack(core.config.outputs, expected)


def drive(core, words, *, stalls=0.3, bubbles=0.2, seed=1, limit=None):
    """Stream input words (packed ``i.payload`` integers) through ``core`` until as many
    outputs are taken (or ``limit`` cycles); a :class:`Run`."""
    run = Run()
    i_bits, o_bits = core.i.payload.as_value(), core.o.payload.as_value()
    limit = limit or 20 * (len(words) * core.interval + core.latency) + 100

    async def bench(ctx):
        rng = np.random.default_rng(seed)
        sent, offering, held = 0, False, None
        while len(run.words) < len(words) and run.cycles < limit:
            if not offering and sent < len(words):
                offering = rng.random() >= bubbles
            ctx.set(i_bits, words[sent] if offering else 0)
            ready = bool(rng.random() >= stalls)
            for name, probe, other in (("o.valid", core.o.valid, core.o.ready),
                                       ("i.ready", core.i.ready, core.i.valid)):
                seen = set()
                for level in (0, 1):
                    ctx.set(other, level)
                    seen.add(ctx.get(probe))
                if len(seen) > 1:
                    run.breaks.append(f"cycle {run.cycles}: {name} depends on its partner")
            ctx.set(core.i.valid, offering)
            ctx.set(core.o.ready, ready)
            valid, word, in_ready = ctx.get(core.o.valid), ctx.get(o_bits), ctx.get(core.i.ready)
            if held is not None and (not valid or word != held):
                run.breaks.append(f"cycle {run.cycles}: an output offered and not taken changed")
            held = word if valid and not ready else None
            run.stalled += bool(valid and not ready)
            if valid and ready:
                run.words.append(word)
            if offering and in_ready:
                run.taken.append(run.cycles)
                sent, offering = sent + 1, False
            await ctx.tick()
            run.cycles += 1

    sim = Simulator(core)
    sim.add_clock(1e-8)
    sim.add_testbench(bench)
    sim.run()
    gaps = np.diff(run.taken)
    if len(gaps) and gaps.min() < core.interval:
        run.breaks.append(f"two vectors taken {gaps.min()} cycle(s) apart, interval {core.interval}")
    return run


def mismatches(core, got, expected):
    """Output rows where ``got`` and ``expected`` words differ, as ``(index, got, expected)``
    with the fields unpacked (the first 5)."""
    bad = [k for k, (g, e) in enumerate(zip(got, expected)) if g != e]
    rows = []
    for k in bad[:5]:
        rows.append((k, {n: int(v[0]) for n, v in unpack(core.config.outputs, [got[k]]).items()},
                     {n: int(v[0]) for n, v in unpack(core.config.outputs, [expected[k]]).items()}))
    return len(bad) + abs(len(got) - len(expected)), rows
