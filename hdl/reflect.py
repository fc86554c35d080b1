"""Reflect component, Lyon (1993) Figure 7b: ``R = 2(N·V)N - V``."""

from functools import cached_property

from phongfx.config import ReflectConfig

from .block import PipelinedBlock
from .dsp import product
from .fixed import cut, quantize_cut, stage

__all__ = ["Reflect"]


class Reflect(PipelinedBlock):
    """Reflection of the viewpoint about the normal, as drawn in Figure 7b.

    Two multiplier levels: three 12×12 for ``N·V``, then three 14×12 for
    ``(2N·V)N`` (default formats); the doubling is a shift, so it is wiring.  Bit
    growth and the formats (our reconstruction) are as in
    :func:`phongfx.golden.reflect.reflect`.

    Latency: ``4 + [pipeline ≥ 1] + 2·[pipeline ≥ 2] + 2·[pipeline ≥ 3] + 4·[pipeline ≥ 4]``
    (4, 5, 7, 9, 13); depth 4 registers both multiplier levels' inputs and products once
    more (so the DSPs meet only registers) and clamps by bit tests.  Depth 0: products
    ``N_i·V_i``; the rounded ``N·V``; products ``2(N·V)·N_i``; the rounded ``R``.
    Depth 1 registers ``N`` and ``V`` first (the rounded ``N·V`` is already a
    register); depth 2 also cuts the adder tree from its rounding and ``2(N·V)N - V``
    from its; depth 3 cuts both roundings from their clamps.  ``N`` and ``V`` wait (automatically) to meet the second level.

    Ports: ``i.payload`` = ``n``, ``v`` (3 × ``config.vec``);
    ``o.payload`` = ``r`` (3 × ``config.out``).
    """

    config_class = ReflectConfig

    @cached_property
    def latency(self):
        depth = self.config.pipeline
        return 4 + (depth >= 1) + 2 * (depth >= 2) + 2 * (depth >= 3) + 4 * (depth >= 4)

    def datapath(self, m, i):
        cfg, depth = self.config, self.config.pipeline
        n, v = cut(m, i["n"], depth >= 1, "n_in"), cut(m, i["v"], depth >= 1, "v_in")
        nv = product(m, n, v, name="nv", isolate=depth >= 4)
        total = cut(m, nv.sum(), depth >= 2, "total")
        dot = stage(m, quantize_cut(m, total, cfg.dot, cfg.rounding, "saturate", depth >= 3, "dot_round", depth >= 4),
                    "dot")
        p = product(m, n, dot << 1, name="p", isolate=depth >= 4)
        r = quantize_cut(m, cut(m, p - v, depth >= 2, "diff"), cfg.out, cfg.rounding, "saturate",
                         depth >= 3, "r_round", depth >= 4)
        return {"r": stage(m, r, "r")}
