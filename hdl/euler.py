"""Corrected Euler unit, Hast, Barrera & Bengtsson (equations 16–17)."""

from amaranth.hdl import Signal

from ..config import EulerConfig
from .block import PipelinedBlock
from .fixed import FixedValue, stage

__all__ = ["Euler"]


class Euler(PipelinedBlock):
    """Two adders and three registers: output ``p``, then ``p += t``, ``t += ds``.

    The registers are state: they change only on a valid pixel, so idle cycles leave
    the scanline where it was.  On ``init`` the loads replace the registers at the
    adders' inputs (a multiplexer each), so the pixel outputs ``p0`` and the registers
    take ``p0 + t0`` and ``t0 + ds``.  Each sum keeps its register's width (wraps), as
    :func:`phongfx.golden.euler.euler` models; ``level`` is the output register
    truncated and saturated to ``config.out`` (wiring and a clamp after the register).

    Latency: 1 (the output register).

    Ports: ``i.payload`` = ``init`` (``1.0``), ``p0`` (``config.p``), ``t0`` (``config.t``),
    ``ds`` (``config.ds``); ``o.payload`` = ``p`` (``config.p``), ``level`` (``config.out``).
    """

    config_class = EulerConfig

    @property
    def latency(self):
        return 1

    def datapath(self, m, i):
        cfg = self.config
        init, valid = i["init"].value[0], self.i.valid
        regs = {name: FixedValue(Signal(cfg.fmt(name).shape(), name=f"{name}_reg"), cfg.fmt(name))
                for name in ("p", "t", "ds")}
        p, t, ds = (load.where(init, regs[name])
                    for name, load in (("p", i["p0"]), ("t", i["t0"]), ("ds", i["ds"])))
        with m.If(valid):
            m.d.sync += [regs["p"].value.eq((p + t).quantize(cfg.p, "truncate", "wrap").value),
                         regs["t"].value.eq((t + ds).quantize(cfg.t, "truncate", "wrap").value),
                         regs["ds"].value.eq(ds.value)]
        out = stage(m, p, "p_out")
        return {"p": out, "level": out.quantize(cfg.out, "truncate", "saturate")}
