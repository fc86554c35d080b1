"""Shape function component, Lyon (1993) Figure 7d: ``f_k(x) = (1 - x/2^k)^(2^k)``."""

from functools import cached_property

from phongfx.config import ShapeConfig
from phongfx.core.format import Format

from .block import PipelinedBlock
from .dsp import product
from .fixed import FixedValue, stage

__all__ = ["Shape"]


class Shape(PipelinedBlock):
    """Shifter, comparator, "1-" block, ``k`` squarers and output multiplexer (Figure 7d).

    The shift by ``k+1`` is wiring; the comparator and the "1-" block see only the
    shifted bits.  ``k`` squaring multipliers (16×16 for ``t`` = ``1.15``) follow.
    Formats, rounding and the error bound are as in :func:`phongfx.golden.shape.shape`.

    Latency: ``1 + k·(1 + [pipeline ≥ 1] + 2·[pipeline ≥ 4])``: ``1 - u``; then each
    squarer's rounded output, with depth ≥ 1 registering each product before its rounding
    adder (depth 2 and 3 add nothing: every stage already holds one multiplier or one carry
    chain; depth 4 registers each squarer's input and product once more, so the DSPs meet
    only registers).
    ``ge1`` waits (automatically) alongside the squarers; the multiplexer after the
    last register selects 0 or ``t``.

    Ports: ``i.payload`` = ``x2`` (``config.x2``); ``o.payload`` = ``spec`` (``config.t``).
    """

    config_class = ShapeConfig

    @cached_property
    def latency(self):
        depth = self.config.pipeline
        return 1 + self.config.k * (1 + (depth >= 1) + 2 * (depth >= 4))

    def datapath(self, m, i):
        cfg = self.config
        v = i["x2"] >> (cfg.k + 1)
        ge1 = v.flag(v >= 1, "ge1")
        u = v.quantize(Format(0, v.fmt.frac_bits), "truncate", "wrap")
        t = stage(m, (FixedValue.const(1, "1.0") - u).quantize(cfg.t, cfg.rounding, "error"), "t0")
        for index in range(cfg.k):
            square = product(m, t, t, cfg.pipeline >= 1, f"tt{index + 1}", cfg.pipeline >= 4)
            t = stage(m, square.quantize(cfg.t, cfg.rounding, "error"), f"t{index + 1}")
        return {"spec": FixedValue.const(0, cfg.t).where(ge1, t)}
