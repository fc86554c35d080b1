"""Configuration of the Blinn–Phong baseline: exact normalization, true power."""

from dataclasses import dataclass

from phongfx.core.format import Format

from .base import BlockConfig, check_format, check_fraction_format, check_int, check_integer_format

__all__ = ["BlinnConfig"]


@dataclass(frozen=True)
class BlinnConfig(BlockConfig):
    """The Blinn–Phong baseline Lyon (1993, "Background") argues against: exact
    normalization by ``1/sqrt(N·N)`` and true exponentiation ``t^n`` at 16-bit precision.

    Per pixel: ``diffuse = max(N·L, 0)/|N|`` and ``specular = (max(N·H, 0)/|N|)^n`` for an
    un-normalized ``N`` and unit ``L``, ``H`` (all ``vec``), shininess ``n`` an integer
    ``1..n_max``.  Stages (bit growth in :mod:`phongfx.golden.blinn`):

    * ``q = N·N`` exact in :attr:`q`; an even left shift ``2j`` brings it to ``m`` in
      ``[1/4, 1)`` (``q = m·4^(h - j)``, ``h`` = half the integer bits of :attr:`q`),
      rounded to ``m`` [``0.18``];
    * ``y0`` from a ``2^rsqrt_addr``-word table [9 address bits] of ``y`` [``1.17``]
      words, then one Newton–Raphson step ``y1 = y0·(3 - m·y0²)/2`` with ``y0²`` and
      ``m·y0²`` in ``nr`` [``2.20``];
    * each dot product scaled by ``2^(j-h)`` (a shift) to ``dot`` [``S1.17``], times
      ``y1``, clamped to ``0..1``: ``diffuse`` in ``out``, the specular cosine in ``t``
      [both ``1.15``: 16 bits, 1.0 exact];
    * ``log2 t`` from a ``2^log_addr``-word table [8] with linear interpolation, in
      ``log`` [``0.20``]; ``x = n·log2 t`` exact; ``2^x`` from a ``2^exp_addr``-word table
      [8] with linear interpolation in ``exp`` [``1.18``], shifted by the integer part of
      ``x`` and rounded to ``out``.

    ``rounding`` is that of every quantize that drops bits (the tables are always
    rounded half up).  Zero-length ``N`` (``q = 0``) gives 0 for both outputs.
    """

    vec: str = "S1.15"
    n: str = "13.0"
    n_max: int = 8000
    m: str = "0.18"
    rsqrt_addr: int = 9
    y: str = "1.17"
    nr: str = "2.20"
    dot: str = "S1.17"
    t: str = "1.15"
    log_addr: int = 8
    log: str = "0.20"
    exp_addr: int = 8
    exp: str = "1.18"
    out: str = "1.15"
    rounding: str = "round_half_up"

    INPUTS = {"normal": ("vec", 3), "light": ("vec", 3), "half": ("vec", 3), "n": ("n", 1)}
    OUTPUTS = {"diffuse": ("out", 1), "specular": ("out", 1)}
    SHADES = {"diff": "diffuse", "spec": "specular"}
    #: ``(diffuse port, lane, specular port)`` of the light it computes, as a shader's blend
    #: takes it (:func:`phongfx.config.shader.unit_terms`)
    TERMS = ("diffuse", None, "specular")
    #: The inputs that depend on the light: one per copy in a shader; the others (N, ``n``)
    #: enter a shader once and fan out to every copy (:attr:`phongfx.config.ShaderConfig.shared`)
    PER_LIGHT = ("light", "half")

    def validate(self):
        check_format("vec", self.vec, signed=True)
        check_int("n_max", self.n_max, 1, check_integer_format("n", self.n).max_raw)
        m = check_fraction_format("m", self.m)
        check_int("rsqrt_addr", self.rsqrt_addr, 2, min(m.frac_bits, 16))
        check_format("y", self.y, signed=False, holds_one=True)
        nr = check_format("nr", self.nr, signed=False)
        if nr.int_bits < 2:
            raise ValueError(f"nr must have at least 2 integer bits (y0² < 4), not {nr}")
        check_format("dot", self.dot, signed=True, holds_one=True)
        t = check_format("t", self.t, signed=False)
        if t.int_bits != 1 or t.frac_bits < 2:
            raise ValueError(f"t must be 1.m with m >= 2 (a cosine in 0..1, 1.0 exact), not {t}")
        log = check_fraction_format("log", self.log)
        check_int("log_addr", self.log_addr, 1, min(t.frac_bits - 1, log.frac_bits - 1, 16))
        exp = check_format("exp", self.exp, signed=False, holds_one=True)
        check_int("exp_addr", self.exp_addr, 1, min(log.frac_bits - 1, exp.frac_bits - 1, 16))
        check_format("out", self.out, signed=False, holds_one=True)
        # the golden model holds the scaled dot product D·2^j in int64
        if self.q.width + self.q.width // 2 > 62:
            raise ValueError(f"vec ({self.vec}) is too wide: N·N scaled by its even shift "
                             f"exceeds 62 bits")

    @property
    def q(self):
        """Exact format of ``q = N·N`` (up to ``3·min²``), integer bits rounded up to even so
        that ``q = m·4^(h - j)`` with ``m = Q·4^j/2^width`` and ``h = int_bits/2``."""
        vec = self.fmt("vec")
        q = Format.covering(0, 3 * vec.min_raw ** 2, 2 * vec.frac_bits)
        return Format(q.int_bits + q.int_bits % 2, q.frac_bits)

    @property
    def flush(self):
        """Largest right shift of ``2^frac(x)`` kept: ``F + 2`` (``F`` fraction bits of
        ``out``); a larger one leaves under ``2^-(F+1)``, which every rounding takes to 0."""
        return self.fmt("out").frac_bits + 2
