"""Difference vector and ``2x`` component, Lyon (1993) Figure 7c: ``2x = n·D·D``."""

from functools import cached_property

from phongfx.config import DifferenceConfig

from .block import PipelinedBlock
from .constant import shininess_product
from .dsp import product, split_product
from .fixed import cut, quantize_cut, stage

__all__ = ["Difference"]


class Difference(PipelinedBlock):
    """Subtractors, squared length and shininess scaling, as drawn in Figure 7c.

    Three subtractors feed three squaring multipliers (12×12 by default), an adder
    tree gives ``D·D``, and one 13×22 multiplier scales it by ``n``.  Bit growth and
    saturation are as in :func:`phongfx.golden.difference.difference`.

    Latency: ``4 + [pipeline ≥ 1] + 2·[pipeline ≥ 2] + 3·[pipeline ≥ 3] + 4·[pipeline ≥ 4]``
    (4, 5, 7, 10, 14); depth 4 registers both multiplier levels' inputs and products once
    more (so the DSPs meet only registers) and clamps by bit tests.  Depth 0: squares
    ``D_i²``; the saturated ``D·D``; the product ``n·D·D``; the rounded, saturated
    ``2x``: each multiplier level is registered before the adder or rounder behind
    it.  Depth 1 registers ``D`` before the squarers; depth 2 also cuts the
    subtractors from their saturation and the adder tree from its rounding; depth 3
    cuts the roundings of ``D·D`` and ``2x`` from their clamps and splits ``n·D·D`` (13×22,
    wider than one MULT18X18D) into two registered partial products and their sum.  ``n``
    waits (automatically) to meet ``D·D``.  With ``config.n_const`` there is no ``n`` port
    and the multiplier is a constant one, shifts and adds
    (:func:`~phongfx.hdl.constant.shininess_product`; none for a power of two), with the
    same codes, registers and latency.

    Ports: ``i.payload`` = ``r``, ``l`` (3 × ``config.vec``), ``n`` (``config.n``; absent
    when ``config.n_const`` is set); ``o.payload`` = ``x2`` (``config.x2``).
    """

    config_class = DifferenceConfig

    @cached_property
    def latency(self):
        depth = self.config.pipeline
        return 4 + (depth >= 1) + 2 * (depth >= 2) + 3 * (depth >= 3) + 4 * (depth >= 4)

    def datapath(self, m, i):
        cfg, depth = self.config, self.config.pipeline
        d = cut(m, i["r"] - i["l"], depth >= 2, "dsub").quantize(cfg.d, cfg.rounding, "saturate")
        d = cut(m, d, depth >= 1, "d")
        squares = product(m, d, d, name="squares", isolate=depth >= 4)
        total = cut(m, squares.sum(), depth >= 2, "total")
        dd = stage(m, quantize_cut(m, total, cfg.dd, cfg.rounding, "saturate", depth >= 3, "dd_round", depth >= 4),
                   "dd")
        p = shininess_product(m, cfg, i, dd, lambda n: split_product(m, n, dd, depth >= 3, "p", depth >= 4), "p",
                              split=depth >= 3)
        return {"x2": stage(m, quantize_cut(m, p, cfg.x2, cfg.rounding, "saturate", depth >= 3,
                                            "x2_round", depth >= 4), "x2")}
