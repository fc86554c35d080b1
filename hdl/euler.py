"""Corrected Euler unit, Hast, Barrera & Bengtsson (equations 16–17), and the
forward-difference unit it shares with the Gouraud unit (the same recurrence one order lower,
Hast et al. §1)."""

from amaranth.hdl import Signal

from phongfx.config import EulerConfig

from .block import PipelinedBlock
from .fixed import FixedValue, stage

__all__ = ["Euler", "ForwardDifferenceUnit", "forward_differences"]


def forward_differences(m, valid, init, loads):
    """Registers stepped as forward differences; returns the first one's value this pixel.

    ``loads`` lists ``(name, load, format)`` from the output down to the constant
    step (``p, t, ds`` for Euler, ``p, dp`` for Gouraud).  On ``init`` the loads
    replace the registers at the adders' inputs (a multiplexer each).  On a valid
    pixel each register takes itself plus the next one, wrapping in its own width
    as the hardware adder does; the last one holds.  Idle cycles change nothing.
    The twin of :func:`phongfx.golden.euler.forward_differences`.
    """
    regs = [FixedValue(Signal(fmt.shape(), name=f"{name}_reg"), fmt) for name, _, fmt in loads]
    current = [load.where(init, reg) for (_, load, _), reg in zip(loads, regs)]
    with m.If(valid):
        for here, after, reg in zip(current, current[1:] + [None], regs):
            step = here if after is None else (here + after).quantize(reg.fmt, "truncate", "wrap")
            m.d.sync += reg.value.eq(step.value)
    return current[0]


class ForwardDifferenceUnit(PipelinedBlock):
    """A chain of adders and registers stepped as forward differences, with an output
    register: the corrected Euler unit (``p += t``, ``t += ds``, Hast, Barrera & Bengtsson
    equations 16–17) and the Gouraud unit (``p += dp``) differ only in the chain.

    The registers are state: they change only on a valid pixel, so idle cycles leave
    the scanline where it was.  On ``init`` the loads replace the registers at the
    adders' inputs (a multiplexer each), so the pixel outputs ``p0`` and each register
    takes its load plus the next one's.  Each sum keeps its register's width (wraps), as
    :func:`phongfx.golden.euler.forward_differences` models; ``level`` is the output
    register truncated and saturated to ``config.out`` (wiring and a clamp after the
    register).

    Latency: 1 (the output register).

    Ports: ``i.payload`` = ``init`` (``1.0``) and the loads of :attr:`LOADS`;
    ``o.payload`` = ``p`` (``config.p``), ``level`` (``config.out``).
    """

    cycle_tags = False  # hand-aligned registers, no pipeline depth
    #: ``(register, input port)`` from the output ``p`` down to the constant step; each
    #: register has the format of the config field of its name
    LOADS = ()

    @property
    def latency(self):
        return 1

    def datapath(self, m, i):
        cfg = self.config
        p = forward_differences(m, self.i.valid, i["init"].value[0],
                                [(name, i[port], cfg.fmt(name)) for name, port in self.LOADS])
        out = stage(m, p, "p_out")
        return {"p": out, "level": out.quantize(cfg.out, "truncate", "saturate")}


class Euler(ForwardDifferenceUnit):
    """Two adders and three registers: output ``p``, then ``p += t``, ``t += ds``
    (:class:`ForwardDifferenceUnit`; :func:`phongfx.golden.euler.euler`).

    Latency: 1 (the output register).

    Ports: ``i.payload`` = ``init`` (``1.0``), ``p0`` (``config.p``), ``t0`` (``config.t``),
    ``ds`` (``config.ds``); ``o.payload`` = ``p`` (``config.p``), ``level`` (``config.out``).
    """

    config_class = EulerConfig
    LOADS = (("p", "p0"), ("t", "t0"), ("ds", "ds"))
