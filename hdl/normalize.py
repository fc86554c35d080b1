"""Approximate normalizer component, Lyon (1993) Figure 7a: ``N = g(N'·N')·N'``."""

from ..config import NormalizeConfig
from .block import PipelinedBlock
from .fixed import FixedValue, delay, stage

__all__ = ["Normalize"]


class Normalize(PipelinedBlock):
    """Approximate normalizer with ``g1 = 1 + y/2`` or ``g2 = 1 + (y + y²)/2``, ``y = 1 - N'·N'``.

    Three squarers (12×12 by default), the ``y²`` multiplier (14×14, order 2
    only) and three ``g × N'`` multipliers (13×12): no table, no divide, no square
    root, as Lyon's "Approximate Normalization" section promises.  Bit growth and
    the formats (our reconstruction) are as in :func:`phongfx.golden.normalize.normalize`.

    Latency: 4 for either order, so the orders are interchangeable in a pipeline
    (squares | ``z``, ``y``, ``y²`` | ``g`` | ``g·N'``; order 1 only skips a multiplier).

    Ports: ``i.payload`` = ``n`` (3 × ``config.vec``); ``o.payload`` = ``n`` (3 × ``config.out``).
    """

    config_class = NormalizeConfig
    latency = 4

    def datapath(self, m, i):
        cfg = self.config
        n = i["n"]
        squares = stage(m, n * n, "squares")
        z = squares.sum().quantize(cfg.z, cfg.rounding, "saturate")
        y = FixedValue.const(1, cfg.z) - z
        if cfg.order == 1:
            half = stage(m, y, "y")
        else:
            y2 = (y * y).quantize(cfg.y2, cfg.rounding, cfg.y2_overflow)
            half = stage(m, y, "y") + stage(m, y2, "y2")
        g = stage(m, (FixedValue.const(1, cfg.g) + half.shift(-1))
                  .quantize(cfg.g, cfg.rounding, "saturate"), "g")
        n = delay(m, n, 3, "n")
        return {"n": stage(m, (n * g).quantize(cfg.out, cfg.rounding, "saturate"), "out")}
