"""The Blinn–Phong baseline: table-plus-Newton normalization and ``t^n`` by log/exp
tables (what Lyon 1993, "Background", says direct designs need)."""

from amaranth.hdl import Const, Mux
from amaranth.lib.memory import Memory

from phongfx.config import BlinnConfig
from phongfx.core.format import Format
from phongfx.golden.blinn import exp2_tables, log2_tables, rsqrt_table

from .block import PipelinedBlock
from .fixed import FixedValue, delay, stage

__all__ = ["Blinn", "LATENCY"]

#: Registered stages: dot products; even shift; seed read and scaled dot products; y0²;
#: m·y0²; y1; cosines; log normalization; log tables; log2 t; n·log2 t; exp tables; 2^f;
#: shift and round.
LATENCY = 14


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
    bounds are as in :func:`phongfx.golden.blinn.blinn`.

    Ports: ``i.payload`` = ``normal``, ``light``, ``half`` (3 × ``config.vec``), ``n``
    (``config.n``); ``o.payload`` = ``diffuse``, ``specular`` (``config.out``).
    """

    config_class = BlinnConfig
    cycle_tags = False  # hand-aligned registers, no pipeline depth

    @property
    def latency(self):
        return LATENCY

    def _rom(self, m, name, words, fmt, address):
        memory = Memory(shape=fmt.shape(), depth=len(words), init=[int(w) for w in words])
        m.submodules[name] = memory
        port = memory.read_port(domain="comb")
        m.d.comb += port.addr.eq(address)
        return FixedValue(port.data, fmt)

    def _interpolate(self, m, name, tables, code, bits, addr_bits, fmt, cycle):
        """``V + D·phi`` from registers holding the two words at the top ``addr_bits`` of
        ``code`` and its low bits ``phi`` (one stage); ``cycle``: that stage's output cycle."""
        low = bits - addr_bits
        value = stage(m, self._rom(m, f"{name}_value", tables[0], fmt, code[low:]), f"{name}_v")
        slope = stage(m, self._rom(m, f"{name}_slope", tables[1], tables[2], code[low:]), f"{name}_d")
        phi = stage(m, FixedValue(code[:low], Format(0, low)), f"{name}_phi")
        step = (slope * phi).shift(-addr_bits).tagged(cycle, m)
        return value + step.quantize(fmt, self.config.rounding, "error")

    def datapath(self, m, i):
        cfg = self.config
        rounding, qfmt = cfg.rounding, cfg.q
        normal = i["normal"]
        q = stage(m, normal.dot(normal).tagged(0, m).quantize(qfmt, "truncate", "error"), "q")
        dots = [stage(m, normal.dot(i[name]), f"d_{name}") for name in ("light", "half")]

        # even shift: j leading all-zero bit pairs (a priority encoder), M = Q << 2j
        pairs = qfmt.width // 2
        j = Const(pairs - 1, range(pairs))
        for k in range(pairs):
            j = Mux(q.value[2 * k:2 * k + 2].any(), pairs - 1 - k, j)
        mant = FixedValue((q.value << (j << 1))[:qfmt.width], Format(0, qfmt.width))
        mant = stage(m, mant.quantize(cfg.m, rounding, "saturate"), "m")
        j, dots = stage(m, j, "j"), [stage(m, d, f"d{index}") for index, d in enumerate(dots)]

        # seed read; the dot products scaled by 2^(j - h) meanwhile
        mfmt = cfg.fmt("m")
        y0 = stage(m, self._rom(m, "rsqrt", rsqrt_table(cfg), cfg.fmt("y"),
                                mant.value[mfmt.frac_bits - cfg.rsqrt_addr:]), "y0")
        shift = qfmt.width // 2 - 1
        scaled = []
        for d, name in zip(dots, ("light", "half")):
            wide = Format.covering(d.fmt.min_raw << shift, d.fmt.max_raw << shift,
                                   d.fmt.frac_bits + qfmt.int_bits // 2)
            value = FixedValue((d.value << j)[:wide.width], wide)
            scaled.append(stage(m, value.quantize(cfg.dot, rounding, "saturate"), f"s_{name}"))
        mant = stage(m, mant, "m_d")

        # one Newton–Raphson step y1 = y0·(3 - m·y0²)/2
        square = stage(m, (y0 * y0).quantize(cfg.nr, rounding, "saturate"), "y0sq")
        y0, mant = stage(m, y0, "y0_d1"), stage(m, mant, "m_d2")
        p = stage(m, (mant * square).quantize(cfg.nr, rounding, "saturate"), "p")
        y0 = stage(m, y0, "y0_d2")
        r = (FixedValue.const(3, "2.0") - p).shift(-1)
        y1 = stage(m, (y0 * r).quantize(cfg.y, rounding, "saturate"), "y1")
        scaled = [delay(m, s, 3, f"s{index}") for index, s in enumerate(scaled)]

        cosines = []
        for s, fmt in zip(scaled, (cfg.fmt("out"), cfg.fmt("t"))):
            t = (s * y1).quantize(fmt, rounding, "saturate")
            cosines.append(stage(m, t.where(t < 1, FixedValue.const(1, fmt)), "cos"))
        diffuse, t = cosines
        n = delay(m, i["n"], 7, "n")
        return {"diffuse": delay(m, diffuse, LATENCY - 7, "diffuse"),
                "specular": self._power(m, t, n)}

    def _power(self, m, t, n):
        """``t^n`` (stages 8–14): the golden :func:`~phongfx.golden.blinn.power`."""
        cfg = self.config
        frac = t.fmt.frac_bits
        s = Const(frac, range(frac + 1))
        for k in range(frac + 1):  # leading zeros of t's code, up to its 2^0 bit
            s = Mux(t.value[k], frac - k, s)
        mantissa = stage(m, (t.value << s)[:frac], "mantissa")
        s = stage(m, s, "s")
        zero = delay(m, t.value == 0, 6, "zero")
        n = delay(m, n, 3, "n_log")

        log = self._interpolate(m, "log", log2_tables(cfg), mantissa, frac, cfg.log_addr,
                                cfg.fmt("log"), cycle=9)
        s = FixedValue(stage(m, s, "s_d"), Format.covering(0, frac, 0))
        lam = stage(m, log - s, "lam")
        x = stage(m, n * lam, "x")

        xf = x.fmt.frac_bits
        floor = x.value[xf:].as_signed()
        # the left shift flush - clip(-floor, 0, flush) that places 2^f·2^floor
        v = floor + cfg.flush
        lsh = stage(m, Mux(v < 0, 0, Mux(v > cfg.flush, cfg.flush, v))[:cfg.flush.bit_length()], "lsh")
        keep = stage(m, v >= 0, "keep")
        e = self._interpolate(m, "exp", exp2_tables(cfg), x.value[:xf], xf, cfg.exp_addr,
                              cfg.fmt("exp"), cycle=12)
        e = stage(m, e, "e")
        lsh, keep = stage(m, lsh, "lsh_d"), stage(m, keep, "keep_d")

        wide = Format(e.fmt.int_bits, e.fmt.frac_bits + cfg.flush)
        spec = FixedValue((e.value << lsh)[:wide.width], wide, LATENCY - 1, m)
        spec = spec.quantize(cfg.out, cfg.rounding, "error")
        spec = spec.where(keep & ~zero, FixedValue.const(0, cfg.out))
        return stage(m, spec, "specular")
