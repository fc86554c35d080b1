"""LIRP component, Lyon (1993) Figure 7a: ``N' = (1-a)·N0 + a·N1``."""

from ..config import LirpConfig
from .block import PipelinedBlock
from .fixed import FixedValue, stage

__all__ = ["Lirp"]


class Lirp(PipelinedBlock):
    """Linear interpolator of direction vectors, as drawn in Figure 7a.

    Six multipliers (``vec × a``, 12×11 by default) and a "1-" block; the merged
    form ``N0 + a(N1-N0)`` would save three, but this is the figure's structure.
    Bit growth is as in :func:`phongfx.golden.lirp.lirp`.

    Latency: 2 (products registered, then the rounded sum).

    Ports: ``i.payload`` = ``n0``, ``n1`` (3 × ``config.vec``), ``a`` (``config.a``);
    ``o.payload`` = ``n`` (3 × ``config.out``).
    """

    config_class = LirpConfig
    latency = 2

    def datapath(self, m, i):
        cfg = self.config
        b = (FixedValue.const(1, cfg.a) - i["a"]).quantize(cfg.a, "truncate", "error")
        p0 = stage(m, i["n0"] * b, "p0")
        p1 = stage(m, i["n1"] * i["a"], "p1")
        return {"n": stage(m, (p0 + p1).quantize(cfg.out, cfg.rounding, "error"), "n")}
