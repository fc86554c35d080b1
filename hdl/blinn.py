"""The Blinn–Phong baseline: table-plus-Newton normalization and ``t^n`` by log/exp
tables (what Lyon 1993, "Background", says direct designs need)."""

from phongfx.config import BlinnConfig

from .block import PipelinedBlock
from .fixed import delay, stage
from .tables import (COSINE_STAGES, POWER_STAGES, RSQRT_STAGES, cosine, even_shift, length_squared,
                     reciprocal_sqrt, scaled, shaded)

__all__ = ["Blinn", "LATENCY"]

#: Registered stages: dot products; even shift; seed read and scaled dot products; y0²;
#: m·y0²; y1; cosines; log normalization; log tables; log2 t; n·log2 t; exp tables; 2^f;
#: shift and round (:mod:`phongfx.hdl.tables`: 7 to the cosines, 7 of the power).
LATENCY = COSINE_STAGES + POWER_STAGES


class Blinn(PipelinedBlock):
    """Nine ``vec × vec`` multipliers (``N·N``, ``N·L``, ``N·H``), a pair priority encoder and
    barrel shifter, the ``1/sqrt`` seed ROM, three Newton–Raphson multipliers
    (``y0²``, ``m·y0²``, ``y0·(3 - p)/2``), two cosine multipliers (``d'·y1``), a priority
    encoder and shifter for ``t``, the log ROMs and interpolation multiplier, the ``n·log2 t``
    multiplier, the exp ROMs and interpolation multiplier, and the output shifter.

    Multipliers at the defaults (operand bits): 9 × 17×17 (dot products), 18×18 (``y0²``),
    18×22 (``m·y0²``), 18×23 (``y0·(3 - p)/2``), 2 × 19×18 (cosines), 13×7 (log
    interpolation), 13×25 (``n·log2 t``), 11×12 (exp interpolation): 17 in all.  ROMs:
    512 × 18 (seed; the low quarter is never read but for ``q = 0``), 256 × 20 + 256 × 13
    (log value, step), 256 × 19 + 256 × 11 (exp value, step).

    Every multiplier reads registers and feeds a register, so the latency is a constant:
    :data:`LATENCY` = 14 for every config (one stage per step listed there).  The ROM
    words come from the golden model's own table functions; formats, rounding and error
    bounds are as in :func:`phongfx.golden.blinn.blinn`; the stages are those of
    :mod:`phongfx.hdl.tables`, shared with the conventional Phong unit.

    Ports: ``i.payload`` = ``normal``, ``light``, ``half`` (3 × ``config.vec``), ``n``
    (``config.n``); ``o.payload`` = ``diffuse``, ``specular`` (``config.out``).
    """

    config_class = BlinnConfig
    cycle_tags = False  # hand-aligned registers, no pipeline depth

    @property
    def latency(self):
        return LATENCY

    def datapath(self, m, i):
        cfg = self.config
        normal = i["normal"]
        q = length_squared(m, cfg, normal)
        dots = [stage(m, normal.dot(i[name]), f"d_{name}") for name in ("light", "half")]
        j, mant = even_shift(m, cfg, q)
        dots = [stage(m, d, f"d{index}") for index, d in enumerate(dots)]
        # the dot products scaled by 2^(j - h) beside the seed read
        s = []
        y1 = reciprocal_sqrt(m, cfg, mant, between=lambda: s.extend(
            scaled(m, cfg, d, j, f"s_{name}") for d, name in zip(dots, ("light", "half"))))
        s = [delay(m, value, RSQRT_STAGES - 1, f"s{index}") for index, value in enumerate(s)]

        diffuse, t = (cosine(m, cfg, value, y1, fmt) for value, fmt in zip(s, (cfg.out, cfg.t)))
        return shaded(m, cfg, diffuse, t, i["n"], COSINE_STAGES)
