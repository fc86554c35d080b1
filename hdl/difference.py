"""Difference vector and ``2x`` component, Lyon (1993) Figure 7c: ``2x = n·D·D``."""

from ..config import DifferenceConfig
from .block import PipelinedBlock
from .fixed import delay, stage

__all__ = ["Difference"]


class Difference(PipelinedBlock):
    """Subtractors, squared length and shininess scaling, as drawn in Figure 7c.

    Three subtractors feed three squaring multipliers (12×12 by default), an adder
    tree gives ``D·D``, and one 13×22 multiplier scales it by ``n``.  Bit growth and
    saturation are as in :func:`phongfx.golden.difference.difference`.

    Latency: 4 (squares ``D_i²``; the saturated ``D·D``; the product ``n·D·D``; the
    rounded, saturated ``2x``): each multiplier level is registered before the adder
    or rounder behind it.  ``n`` waits 2 cycles to meet ``D·D``.

    Ports: ``i.payload`` = ``r``, ``l`` (3 × ``config.vec``), ``n`` (``config.n``);
    ``o.payload`` = ``x2`` (``config.x2``).
    """

    config_class = DifferenceConfig
    latency = 4

    def datapath(self, m, i):
        cfg = self.config
        d = (i["r"] - i["l"]).quantize(cfg.d, cfg.rounding, "saturate")
        squares = stage(m, d * d, "squares")
        dd = stage(m, squares.sum().quantize(cfg.dd, cfg.rounding, "saturate"), "dd")
        p = stage(m, delay(m, i["n"], 2, "n") * dd, "p")
        return {"x2": stage(m, p.quantize(cfg.x2, cfg.rounding, "saturate"), "x2")}
