"""Schlick's rational specular unit (Schlick 1994): ``S_n(t) = t / (n - n·t + t)``."""

from amaranth.hdl import Cat, Const, Mux

from phongfx.config import SchlickConfig
from phongfx.core.format import Format

from .block import PipelinedBlock
from .fixed import FixedValue, stage

__all__ = ["Schlick"]


class Schlick(PipelinedBlock):
    """Divisor ``n(1 - t) + t`` (one multiplier, one adder), then a pipelined restoring
    divider with one registered stage per quotient bit: one quotient per clock.

    Stage ``k`` (``k = 0 .. Q-1``) holds the partial remainder ``r_k < 2D`` (``r_0 = t``,
    since ``t <= D``): quotient bit ``b_k = (r_k >= D)`` of weight ``2^-k``, then
    ``r_(k+1) = 2(r_k - b_k·D)``.  ``Q`` is :attr:`SchlickConfig.quotient_bits`
    (``F + 1``, ``F + 2`` for ``round_half_up``, ``F`` the fraction bits of ``out``).
    Formats, rounding and the error bound are as in :func:`phongfx.golden.schlick.schlick`.

    Latency: ``1 + Q`` (the divisor, then each quotient bit): 17 for the defaults.
    ``round_half_up``'s ``(q + 1) >> 1`` follows the last register (a quantize).

    Ports: ``i.payload`` = ``t`` (``config.t``), ``n`` (``config.n``); ``o.payload`` =
    ``spec`` (``config.out``).
    """

    config_class = SchlickConfig
    cycle_tags = False  # hand-aligned registers, no pipeline depth

    @property
    def latency(self):
        return 1 + self.config.quotient_bits

    def datapath(self, m, i):
        cfg = self.config
        t, bits = i["t"].tagged(0, m), cfg.quotient_bits
        unsigned_t = Format(t.fmt.int_bits, t.fmt.frac_bits)
        u = (FixedValue.const(1, "1.0") - t).quantize(unsigned_t, "truncate", "error")
        den = stage(m, (i["n"] * u + t).quantize(cfg.den, "truncate", "error").value, "den")
        # r < 2D needs one bit more than D; a valid t <= 1 <= D survives zero-extension
        # or the truncation of integer bits it never sets
        width = cfg.den.width + 1
        r = stage(m, Cat(t.value, Const(0, width))[:width], "r0")
        q = None
        for k in range(bits):
            ge = r >= den
            q = ge if q is None else Cat(ge, q)  # the new bit is the least significant
            q = stage(m, q, f"q{k}")
            if k < bits - 1:
                # r - D < D < 2^(width-1) when ge: doubling fits in width bits
                r = stage(m, (Mux(ge, r - den, r) << 1)[:width], f"r{k + 1}")
                den = stage(m, den, f"den{k + 1}")
        # quotient bits weigh 2^0 .. 2^-(Q-1); round_half_up drops the extra one
        q = FixedValue(q, Format(1, bits - 1), self.latency, m)
        return {"spec": q.quantize(cfg.out, cfg.rounding, "error")}
