"""Reflect component, Lyon (1993) Figure 7b: ``R = 2(N·V)N - V``."""

from ..config import ReflectConfig
from .block import PipelinedBlock
from .fixed import delay, stage

__all__ = ["Reflect"]


class Reflect(PipelinedBlock):
    """Reflection of the viewpoint about the normal, as drawn in Figure 7b.

    Two multiplier levels: three 12×12 for ``N·V``, then three 14×12 for
    ``(2N·V)N`` (default formats); the doubling is a shift, so it is wiring.  Bit
    growth and the formats (our reconstruction) are as in
    :func:`phongfx.golden.reflect.reflect`.

    Latency: 4 (products ``N_i·V_i``; the rounded ``N·V``; products ``2(N·V)·N_i``;
    the rounded ``R``).  ``N`` waits 2 cycles and ``V`` 3 to meet the second level.

    Ports: ``i.payload`` = ``n``, ``v`` (3 × ``config.vec``);
    ``o.payload`` = ``r`` (3 × ``config.out``).
    """

    config_class = ReflectConfig
    latency = 4

    def datapath(self, m, i):
        cfg = self.config
        nv = stage(m, i["n"] * i["v"], "nv")
        dot = stage(m, nv.sum().quantize(cfg.dot, cfg.rounding, "saturate"), "dot")
        p = stage(m, delay(m, i["n"], 2, "n") * (dot << 1), "p")
        r = (p - delay(m, i["v"], 3, "v")).quantize(cfg.out, cfg.rounding, "saturate")
        return {"r": stage(m, r, "r")}
