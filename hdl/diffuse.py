"""Diffuse component: ``max(N·L, 0)``, Lambert's term with the backside test."""

from ..config import DiffuseConfig
from .block import PipelinedBlock
from .fixed import FixedValue, stage

__all__ = ["Diffuse"]


class Diffuse(PipelinedBlock):
    """Diffuse amount, Figure 6's diffuse reflection calculator, with the backside test.

    Three multipliers (12×12 by default) and an adder tree; the backside test is
    the sign of the sum selecting 0.  Bit growth and the formats (our
    reconstruction) are as in :func:`phongfx.golden.diffuse.diffuse`.

    Latency: 2 (products registered, then the clamped, rounded sum).

    Ports: ``i.payload`` = ``n``, ``l`` (3 × ``config.vec``);
    ``o.payload`` = ``diff`` (``config.out``).
    """

    config_class = DiffuseConfig
    latency = 2

    def datapath(self, m, i):
        cfg = self.config
        dot = stage(m, i["n"] * i["l"], "nl").sum()
        lit = dot.where(dot >= 0, FixedValue.const(0, dot.fmt))
        return {"diff": stage(m, lit.quantize(cfg.out, cfg.rounding, "saturate"), "diff")}
