"""Diffuse component: ``max(N·L, 0)``, Lambert's term with the backside test."""

from functools import cached_property

from phongfx.config import DiffuseConfig

from .block import PipelinedBlock
from .dsp import product
from .fixed import FixedValue, cut, quantize_cut, stage

__all__ = ["Diffuse"]


class Diffuse(PipelinedBlock):
    """Diffuse amount, Figure 6's diffuse reflection calculator, with the backside test.

    Three multipliers (12×12 by default) and an adder tree; the backside test is
    the sign of the sum selecting 0.  Bit growth and the formats (our
    reconstruction) are as in :func:`phongfx.golden.diffuse.diffuse`.

    Latency: ``2 + pipeline + [pipeline ≥ 4]`` (products registered, then the clamped, rounded sum;
    depth 1 registers ``N`` and ``L`` first, depth 2 also the sum before its rounding,
    depth 3 the rounding before its clamp, depth 4 ``N``, ``L`` and the products once more,
    so the DSPs meet only registers, and clamps by bit tests).

    Ports: ``i.payload`` = ``n``, ``l`` (3 × ``config.vec``);
    ``o.payload`` = ``diff`` (``config.out``).
    """

    config_class = DiffuseConfig

    @cached_property
    def latency(self):
        return 2 + self.config.pipeline + (self.config.pipeline >= 4)

    def datapath(self, m, i):
        cfg, depth = self.config, self.config.pipeline
        n, l = cut(m, i["n"], depth >= 1, "n_in"), cut(m, i["l"], depth >= 1, "l_in")
        dot = cut(m, product(m, n, l, name="nl", isolate=depth >= 4).sum(), depth >= 2, "dot")
        lit = dot.where(dot >= 0, FixedValue.const(0, dot.fmt))
        return {"diff": stage(m, quantize_cut(m, lit, cfg.out, cfg.rounding, "saturate", depth >= 3,
                                              "diff_round", depth >= 4), "diff")}
