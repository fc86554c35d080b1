"""LIRP component, Lyon (1993) Figure 7a: ``N' = (1-a)·N0 + a·N1``."""

from functools import cached_property

from phongfx.config import LirpConfig

from .block import PipelinedBlock
from .dsp import product
from .fixed import FixedValue, cut, stage

__all__ = ["Lirp"]


class Lirp(PipelinedBlock):
    """Linear interpolator of direction vectors, as drawn in Figure 7a.

    Six multipliers (``vec × a``, 12×11 by default) and a "1-" block; the merged
    form ``N0 + a(N1-N0)`` would save three, but this is the figure's structure.
    Bit growth is as in :func:`phongfx.golden.lirp.lirp`.

    Latency: ``2 + min(pipeline, 2) + 2·[pipeline ≥ 4]`` (products registered, then the
    rounded sum; depth 1 registers the multiplier inputs ``N0``, ``N1``, ``a``, ``1-a``;
    depth 2 also the sum before its rounding adder; depth 3 adds nothing: no quantize here
    clamps; depth 4 registers the multiplier inputs and products once more, so the DSPs meet
    only registers).

    Ports: ``i.payload`` = ``n0``, ``n1`` (3 × ``config.vec``), ``a`` (``config.a``);
    ``o.payload`` = ``n`` (3 × ``config.out``).
    """

    config_class = LirpConfig

    @cached_property
    def latency(self):
        return 2 + min(self.config.pipeline, 2) + 2 * (self.config.pipeline >= 4)

    def datapath(self, m, i):
        cfg, depth = self.config, self.config.pipeline
        b = (FixedValue.const(1, cfg.a) - i["a"]).quantize(cfg.a, "truncate", "error")
        n0, b = cut(m, i["n0"], depth >= 1, "n0_in"), cut(m, b, depth >= 1, "b")
        n1, a = cut(m, i["n1"], depth >= 1, "n1_in"), cut(m, i["a"], depth >= 1, "a_in")
        p0 = product(m, n0, b, name="p0", isolate=depth >= 4)
        p1 = product(m, n1, a, name="p1", isolate=depth >= 4)
        total = cut(m, p0 + p1, depth >= 2, "sum")
        return {"n": stage(m, total.quantize(cfg.out, cfg.rounding, "error"), "n")}
