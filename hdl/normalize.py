"""Approximate normalizer component, Lyon (1993) Figure 7a: ``N = g(N'·N')·N'``."""

from functools import cached_property

from phongfx.config import NormalizeConfig

from .block import PipelinedBlock
from .dsp import product
from .fixed import FixedValue, cut, quantize_cut, stage

__all__ = ["Normalize"]


class Normalize(PipelinedBlock):
    """Approximate normalizer with ``g1 = 1 + y/2`` or ``g2 = 1 + (y + y²)/2``, ``y = 1 - N'·N'``.

    Three squarers (12×12 by default), the ``y²`` multiplier (14×14, order 2
    only) and three ``g × N'`` multipliers (13×12): no table, no divide, no square
    root, as Lyon's "Approximate Normalization" section promises.  Bit growth and
    the formats (our reconstruction) are as in :func:`phongfx.golden.normalize.normalize`.

    Latency: ``4 + 3·[pipeline ≥ 1] + 4·[pipeline ≥ 2] + 4·[pipeline ≥ 3] + 6·[pipeline ≥ 4]``
    (4, 7, 11, 15, 21)
    for either order, so
    the orders are interchangeable in a pipeline (order 1 only skips a multiplier).
    Depth 0: squares | ``z``, ``y``, ``y²`` | ``g`` | ``g·N'``.  Depth 1 registers
    ``N'``, ``y`` (the ``y²`` input), ``y·y`` and ``g·N'`` before their rounding.  Depth
    2 also cuts after the three-square sum, the rounded ``z``, the rounded ``y²`` and
    ``y + y²``, so each stage holds one multiplier or one carry chain.  Depth 3 cuts
    the rounding of ``z``, ``y²``, ``g`` and the output from their clamps.  Depth 4 registers
    each multiplier's inputs and product once more (three levels), so that its DSP meets
    only registers, and clamps by bit tests.

    Ports: ``i.payload`` = ``n`` (3 × ``config.vec``); ``o.payload`` = ``n`` (3 × ``config.out``).
    """

    config_class = NormalizeConfig

    @cached_property
    def latency(self):
        depth = self.config.pipeline
        return 4 + 3 * (depth >= 1) + 4 * (depth >= 2) + 4 * (depth >= 3) + 6 * (depth >= 4)

    def datapath(self, m, i):
        cfg, depth = self.config, self.config.pipeline
        n = cut(m, i["n"], depth >= 1, "n_in")
        squares = product(m, n, n, name="squares", isolate=depth >= 4)
        total = cut(m, squares.sum(), depth >= 2, "total")
        z = cut(m, quantize_cut(m, total, cfg.z, cfg.rounding, "saturate", depth >= 3, "z_round", depth >= 4),
                depth >= 2, "z")
        y = cut(m, FixedValue.const(1, cfg.z) - z, depth >= 1, "y")
        # depth 0 registers y² after its rounding, depth 1 only the product, depth 2 both
        y2_cycle = y.cycle + (depth >= 1) + (depth != 1) + (depth >= 3) + 2 * (depth >= 4)
        if cfg.order == 1:
            half = y.at(y2_cycle)  # waits as long as y² would: same latency for both orders
        else:
            yy = product(m, y, y, depth >= 1, "yy", depth >= 4)
            y2 = quantize_cut(m, yy, cfg.y2, cfg.rounding, cfg.y2_overflow, depth >= 3, "y2_round", depth >= 4)
            y2 = cut(m, y2, depth != 1, "y2")
            half = y + y2
        half = cut(m, half, depth >= 2, "half")
        g = stage(m, quantize_cut(m, FixedValue.const(1, cfg.g) + half.shift(-1), cfg.g,
                                  cfg.rounding, "saturate", depth >= 3, "g_round", depth >= 4), "g")
        ng = product(m, n, g, depth >= 1, "ng", depth >= 4)
        return {"n": stage(m, quantize_cut(m, ng, cfg.out, cfg.rounding, "saturate",
                                           depth >= 3, "out_round", depth >= 4), "out")}
