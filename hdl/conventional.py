"""The conventional Phong unit: normalize ``N`` (and a local ``L``, ``V``), reflect, raise
``R·V`` to ``n`` by log/exp tables (Phong 1975, the direct design of Lyon 1993, "Background")."""

from phongfx.config import ConventionalConfig

from .block import PipelinedBlock
from .fixed import FixedValue, FixedVector, delay, stage
from .tables import (COSINE_STAGES, POWER_STAGES, RSQRT_STAGES, clamp_one, cosine, even_shift, length_squared,
                     reciprocal_sqrt, scaled, shaded)

__all__ = ["Conventional", "LATENCY", "LOCAL_LATENCY"]

#: Registered stages with ``L`` and ``V`` at infinity: dot products (``N·N``, ``N·L``,
#: ``N·V``, ``L·V``); even shift; seed read and scaled ``N·L``, ``N·V``; y0²; m·y0²; y1;
#: cosines ``c_L``, ``c_V``; ``R·V = 2·c_L·c_V - L·V`` and diffuse; log normalization; log
#: tables; log2 t; n·log2 t; exp tables; 2^f; shift and round.
LATENCY = COSINE_STAGES + 1 + POWER_STAGES
#: With a local ``L`` or ``V``: its normalizer's 7 stages (``X·X``; even shift; seed read;
#: y0²; m·y0²; y1; ``X̂``), ``N``'s even shift and ``1/sqrt`` beside them; then the dot
#: products with ``X̂``; scaled ``N·L̂``, ``N·V̂``; cosines; ``R·V``; the 7 of the power.
LOCAL_LATENCY = COSINE_STAGES + 3 + 1 + POWER_STAGES


class Conventional(PipelinedBlock):
    """Twelve ``vec × vec`` multipliers (``N·N``, ``N·L``, ``N·V``, ``L·V``), the normalizer of
    :mod:`phongfx.hdl.tables` for ``N`` (pair priority encoder and barrel shifter, seed ROM,
    three Newton–Raphson multipliers), two cosine multipliers (``d'·y1``), the ``c_L × c_V``
    multiplier and a subtracter for ``R·V``, and the power of :mod:`phongfx.hdl.tables`
    (log ROMs and interpolation multiplier, ``n·log2 t``, exp ROMs and interpolation
    multiplier, output shifter).  ``R·V`` is formed as ``2(N̂·L)(N̂·V) - L·V``, the exact
    algebra of :mod:`phongfx.golden.conventional`: no vector ``N̂`` or ``R`` is built.

    Multipliers at the defaults (operand bits): 12 × 17×17 (dot products), 18×18
    (``y0²``), 18×22 (``m·y0²``), 18×23 (``y0·(3 - p)/2``), 2 × 19×18 (cosines), 19×19
    (``c_L·c_V``), 13×7 (log interpolation), 13×25 (``n·log2 t``), 11×12 (exp
    interpolation): 21 in all.  ROMs as the Blinn–Phong baseline's (512 × 18 seed, 256 × 20
    + 256 × 13 log, 256 × 19 + 256 × 11 exp).  Each of ``local_light``, ``local_viewer``
    adds a normalizer of its own: 3 × 17×17 (``X·X``), the three Newton–Raphson
    multipliers, 3 × 19×18 (``X̂``) and a seed ROM: 9 multipliers.

    Every multiplier reads registers and feeds a register, so the latency is a constant of
    the config: :data:`LATENCY` = 15 with ``L`` and ``V`` at infinity, :data:`LOCAL_LATENCY`
    = 18 with either local (one stage per step listed there; ``N``'s normalizer runs beside
    the local one, so only the dot products with ``X̂`` and what follows wait for it).  The
    ROM words come from the golden model's own table functions; formats, rounding and
    error bounds are as in :func:`phongfx.golden.conventional.conventional`.

    Ports: ``i.payload`` = ``normal``, ``light``, ``view`` (3 × ``config.vec``), ``n``
    (``config.n``); ``o.payload`` = ``diffuse``, ``specular`` (``config.out``).
    """

    config_class = ConventionalConfig
    cycle_tags = False  # hand-aligned registers, no pipeline depth

    @property
    def local(self):
        return self.config.local_light or self.config.local_viewer

    @property
    def latency(self):
        return LOCAL_LATENCY if self.local else LATENCY

    def _unit_length(self, m, x, name):
        """``X/|X|`` in ``vec``, :data:`~phongfx.hdl.tables.COSINE_STAGES` after ``x``: the
        golden :func:`~phongfx.golden.conventional.unit_length`."""
        cfg = self.config
        q = length_squared(m, cfg, x, f"{name}_")
        j, mant = even_shift(m, cfg, q, f"{name}_")
        lanes = [delay(m, lane, 2, f"{name}_{axis}") for lane, axis in zip(x, "xyz")]
        y1 = reciprocal_sqrt(m, cfg, mant, f"{name}_")
        lanes = [delay(m, scaled(m, cfg, lane, j, f"{name}_s{axis}"), RSQRT_STAGES - 1, f"{name}_s{axis}")
                 for lane, axis in zip(lanes, "xyz")]
        return FixedVector(cosine(m, cfg, lane, y1, cfg.vec, f"{name}_unit{axis}")
                           for lane, axis in zip(lanes, "xyz"))

    def datapath(self, m, i):
        cfg = self.config
        # the cycle of the unit L and V: the inputs, or the local normalizers' outputs
        start = COSINE_STAGES if self.local else 0
        light, view = (self._unit_length(m, i[name], name) if local else delay(m, i[name], start, name)
                       for name, local in (("light", cfg.local_light), ("view", cfg.local_viewer)))
        normal = i["normal"]
        q = length_squared(m, cfg, normal)
        normal = delay(m, normal, start, "normal")
        dots = [stage(m, normal.dot(x), f"d_{name}") for x, name in ((light, "light"), (view, "view"))]
        light_view = stage(m, light.dot(view), "d_lv")
        j, mant = even_shift(m, cfg, q)
        y1 = reciprocal_sqrt(m, cfg, mant)

        # dot products and j meet at cycle 2 (infinity) or start + 1; the cosines' inputs and
        # y1 at RSQRT_STAGES + 2 or one stage after the scaling
        meet = max(2, start + 1)
        dots = [delay(m, d, meet - start - 1, f"d{index}") for index, d in enumerate(dots)]
        j = delay(m, j, meet - 2, "j")
        front = stage(m, dots[0].value > 0, "front")  # the light in front: N·L > 0
        late = max(meet + 1, RSQRT_STAGES + 2)
        s = [delay(m, scaled(m, cfg, d, j, f"s_{name}"), late - meet - 1, f"s{index}")
             for index, (d, name) in enumerate(zip(dots, ("light", "view")))]
        y1 = delay(m, y1, late - RSQRT_STAGES - 2, "y1")
        c_light, c_view = (cosine(m, cfg, value, y1, cfg.cos, f"c_{name}") for value, name in
                           zip(s, ("light", "view")))
        cycle = late + 1  # the cosines'
        light_view = delay(m, light_view, cycle - start - 1, "lv")
        front = delay(m, front, cycle - meet - 1, "front")

        # R·V = 2(N̂·L)(N̂·V) - L·V, rounded once and clamped; zero t (so t^n) for N·L <= 0
        rv = clamp_one(((c_light * c_view).shift(1) - light_view).quantize(cfg.t, cfg.rounding, "saturate"))
        t = stage(m, rv.where(front, FixedValue.const(0, cfg.t)), "t")
        diffuse = stage(m, c_light.quantize(cfg.out, cfg.rounding, "saturate"), "diffuse")
        return shaded(m, cfg, diffuse, t, i["n"], cycle + 1)
