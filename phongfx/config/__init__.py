"""Datapath configurations: plain data saying which formats each block uses.

A configuration is a frozen dataclass of format strings (Lyon's ``n.m`` / ``Sn.m``),
integers and names.  It is validated when built, so both the golden function and the
Amaranth component of a block see only sound parameters, and it declares the block's
ports (:attr:`BlockConfig.inputs`, :attr:`BlockConfig.outputs`): name -> (format,
lanes), lanes being 3 for an X, Y, Z vector.  The golden model, the component's
payload layouts and the checking harness all take port widths from there.

The default formats are our reconstruction of Lyon's Figure 7, whose bit annotations
are lost from our copy; each block's docstring says why each default was chosen.
"""

from dataclasses import dataclass, fields, replace

from phongfx.core.format import Format, check_rounding

__all__ = [
    "BlockConfig", "LirpConfig", "NormalizeConfig", "ReflectConfig", "DifferenceConfig",
    "ShapeConfig", "DiffuseConfig", "RootConfig", "SchlickConfig", "SphericalConfig", "HalfwayConfig", "HALFWAY_VARIANTS",
    "EulerConfig", "GouraudConfig", "ConventionalConfig",
    "DatapathConfig", "SPECULAR_UNITS", "fig7_config", "fig8_config", "halfway_config",
    "MAX_PIPELINE",
]


def _fmt(name, value, *, signed=None, holds_one=False):
    try:
        fmt = Format.parse(value)
    except (TypeError, ValueError) as error:
        raise ValueError(f"{name}: {error}") from None
    if signed is True and not fmt.signed:
        raise ValueError(f"{name} must be a signed format (Sn.m), not {fmt}")
    if signed is False and fmt.signed:
        raise ValueError(f"{name} must be an unsigned format (n.m), not {fmt}")
    if holds_one and not fmt.holds_one():
        raise ValueError(f"{name} must hold exactly 1.0 (at least 1 integer bit), not {fmt}")
    return fmt


def _integer_fmt(name, value):
    fmt = _fmt(name, value, signed=False)
    if fmt.frac_bits:
        raise ValueError(f"{name} must be an integer format (m = 0), not {fmt}")
    return fmt


def _fraction_fmt(name, value):
    fmt = _fmt(name, value, signed=False)
    if fmt.int_bits:
        raise ValueError(f"{name} must be a fraction-only format (0.m), not {fmt}")
    return fmt


MAX_PIPELINE = 3


def _int(name, value, lo, hi):
    if not isinstance(value, int) or isinstance(value, bool) or not lo <= value <= hi:
        raise ValueError(f"{name} must be an integer in {lo}..{hi}, not {value!r}")
    return value


@dataclass(frozen=True)
class BlockConfig:
    """Base of block configurations: validation hook and port declarations.

    Leaf blocks carry a ``rounding`` field: the rounding of every quantize in the
    block that drops fraction bits.  The blocks of Lyon's datapaths also carry
    ``pipeline`` (``0..MAX_PIPELINE``, default 0): the depth of pipelining (GitHub
    issue 5, §1).  0 is the original design; 1 registers every multiplier's inputs
    and outputs; 2 also cuts the carry chains, so that no stage holds more than one
    multiplier or one long carry chain; 3 also puts a register between each
    saturating quantize's rounding adder and its clamp.  Only the latency changes with it (each
    component's docstring gives the formula); the function does not.
    """

    def __post_init__(self):
        if hasattr(self, "rounding"):
            check_rounding(self.rounding)
        self.validate()

    def validate(self):
        pass

    def fmt(self, name):
        """The :class:`Format` of the string field ``name``."""
        return Format.parse(getattr(self, name))

    def replace(self, **changes):
        return replace(self, **changes)

    def as_dict(self):
        return {f.name: getattr(self, f.name) for f in fields(self)}

    @property
    def inputs(self):
        raise NotImplementedError

    @property
    def outputs(self):
        raise NotImplementedError


@dataclass(frozen=True)
class LirpConfig(BlockConfig):
    """Figure 7a linear interpolator ``N' = (1-a)·N0 + a·N1``."""

    vec: str = "S1.10"
    a: str = "1.10"
    out: str = "S1.10"
    rounding: str = "round_half_up"
    pipeline: int = 0

    def validate(self):
        _int("pipeline", self.pipeline, 0, MAX_PIPELINE)
        _fmt("vec", self.vec, signed=True)
        _fmt("a", self.a, signed=False, holds_one=True)
        _fmt("out", self.out, signed=True)

    @property
    def inputs(self):
        return {"n0": (self.fmt("vec"), 3), "n1": (self.fmt("vec"), 3), "a": (self.fmt("a"), 1)}

    @property
    def outputs(self):
        return {"n": (self.fmt("out"), 3)}


@dataclass(frozen=True)
class NormalizeConfig(BlockConfig):
    """Figure 7a approximate normalizer ``N = g(N'·N')·N'`` with ``g1`` or ``g2``."""

    vec: str = "S1.10"
    order: int = 2
    z: str = "1.12"
    y2: str = "1.12"
    g: str = "1.12"
    out: str = "S1.10"
    rounding: str = "round_half_up"
    pipeline: int = 0

    def validate(self):
        _int("pipeline", self.pipeline, 0, MAX_PIPELINE)
        _fmt("vec", self.vec, signed=True)
        _int("order", self.order, 1, 2)
        _fmt("z", self.z, signed=False, holds_one=True)
        _fmt("y2", self.y2, signed=False, holds_one=True)
        _fmt("g", self.g, signed=False, holds_one=True)
        _fmt("out", self.out, signed=True)

    @property
    def y2_overflow(self):
        """Overflow policy of the ``y²`` quantize: ``"error"`` where it provably cannot overflow.

        ``z`` saturates below 2 when it has one integer bit, so ``y > -1`` and
        ``y² <= 1``, which ``y2`` holds by validation.  A wider ``z`` lets junk
        reach ``y = 1 - 2**int_bits`` and ``y²`` well past 1: saturate there.
        """
        return "error" if self.fmt("z").int_bits == 1 else "saturate"

    @property
    def inputs(self):
        return {"n": (self.fmt("vec"), 3)}

    @property
    def outputs(self):
        return {"n": (self.fmt("out"), 3)}


@dataclass(frozen=True)
class ReflectConfig(BlockConfig):
    """Figure 7b reflection ``R = 2(N·V)N - V``."""

    vec: str = "S1.10"
    dot: str = "S1.12"
    out: str = "S1.10"
    rounding: str = "round_half_up"
    pipeline: int = 0

    def validate(self):
        _int("pipeline", self.pipeline, 0, MAX_PIPELINE)
        _fmt("vec", self.vec, signed=True)
        _fmt("dot", self.dot, signed=True, holds_one=True)
        _fmt("out", self.out, signed=True)

    @property
    def inputs(self):
        return {"n": (self.fmt("vec"), 3), "v": (self.fmt("vec"), 3)}

    @property
    def outputs(self):
        return {"r": (self.fmt("out"), 3)}


@dataclass(frozen=True)
class DifferenceConfig(BlockConfig):
    """Figure 7c difference vector and ``2x = n·D·D``; ``n`` is an integer ``1..n_max``.

    ``n_const``: 0 (default) takes ``n`` per pixel on the ``n`` port, through a full
    ``n × D·D`` multiplier; ``1..n_max`` fixes ``n`` in the hardware (issue 7 §2.2, "a
    constant multiplier (or none) for a single n"): no ``n`` port, a multiplication
    by a constant in shifts and adds (a pure shift for a power of two; see
    :func:`phongfx.hdl.difference.const_product`), the same codes as feeding
    ``n = n_const`` on the port, in the same cycles.
    """

    vec: str = "S1.10"
    d: str = "S1.10"
    dd: str = "2.20"
    n: str = "13.0"
    n_max: int = 8000
    x2: str = "13.12"
    rounding: str = "round_half_up"
    pipeline: int = 0
    n_const: int = 0

    def validate(self):
        _int("pipeline", self.pipeline, 0, MAX_PIPELINE)
        _fmt("vec", self.vec, signed=True)
        _fmt("d", self.d, signed=True)
        _fmt("dd", self.dd, signed=False)
        _int("n_max", self.n_max, 1, _integer_fmt("n", self.n).max_raw)
        _int("n_const", self.n_const, 0, self.n_max)
        _fmt("x2", self.x2, signed=False)

    @property
    def inputs(self):
        ports = {"r": (self.fmt("vec"), 3), "l": (self.fmt("vec"), 3)}
        if not self.n_const:
            ports["n"] = (self.fmt("n"), 1)
        return ports

    @property
    def outputs(self):
        return {"x2": (self.fmt("x2"), 1)}


@dataclass(frozen=True)
class ShapeConfig(BlockConfig):
    """Figure 7d shape function ``f_k(x) = (1 - x/2^k)^(2^k)``, zero for ``x/2^k >= 1``."""

    x2: str = "13.12"
    k: int = 2
    t: str = "1.15"
    rounding: str = "round_half_up"
    pipeline: int = 0

    def validate(self):
        _int("pipeline", self.pipeline, 0, MAX_PIPELINE)
        x2 = _fmt("x2", self.x2, signed=False)
        _int("k", self.k, 0, 4)
        if x2.int_bits < self.k + 2:
            raise ValueError(f"x2 must have at least k+2 = {self.k + 2} integer bits so that "
                             f"x/2^k reaches 1, not {x2}")
        _fmt("t", self.t, signed=False, holds_one=True)

    @property
    def inputs(self):
        return {"x2": (self.fmt("x2"), 1)}

    @property
    def outputs(self):
        return {"spec": (self.fmt("t"), 1)}


@dataclass(frozen=True)
class DiffuseConfig(BlockConfig):
    """Diffuse ``max(N·L, 0)`` (the backside test zeroes it)."""

    vec: str = "S1.10"
    out: str = "1.10"
    rounding: str = "round_half_up"
    pipeline: int = 0

    def validate(self):
        _int("pipeline", self.pipeline, 0, MAX_PIPELINE)
        _fmt("vec", self.vec, signed=True)
        _fmt("out", self.out, signed=False, holds_one=True)

    @property
    def inputs(self):
        return {"n": (self.fmt("vec"), 3), "l": (self.fmt("vec"), 3)}

    @property
    def outputs(self):
        return {"diff": (self.fmt("out"), 1)}


@dataclass(frozen=True)
class RootConfig(BlockConfig):
    """Figure 8 root-shininess specular unit: ``|D|·m``, fraction-only dot product,
    augmented comparator, shape ``f_k`` (``k = 1`` by default); ``m = √n`` in ``1..m_max``.

    ``frac`` is the fraction of each ``u_i = m|D_i|/2^s`` that the dot product sees;
    :attr:`shift` is ``s`` and :attr:`shape` the Figure 7d config fed with ``2x``
    (see :mod:`phongfx.golden.root`).  ``m_const``: 0 (default) takes ``m`` per pixel on
    the ``m`` port; ``1..m_max`` fixes it in the hardware (no ``m`` port; the three
    ``m × |D_i|`` become constant multiplications), with the codes and latency of
    feeding ``m = m_const``, as :attr:`DifferenceConfig.n_const` does for ``n``.
    """

    vec: str = "S1.10"
    d: str = "S1.10"
    m: str = "6.0"
    m_max: int = 63
    frac: str = "0.9"
    k: int = 1
    t: str = "1.15"
    rounding: str = "round_half_up"
    pipeline: int = 0
    m_const: int = 0

    def validate(self):
        _int("pipeline", self.pipeline, 0, MAX_PIPELINE)
        _fmt("vec", self.vec, signed=True)
        _fmt("d", self.d, signed=True)
        _int("m_max", self.m_max, 1, _integer_fmt("m", self.m).max_raw)
        _int("m_const", self.m_const, 0, self.m_max)
        frac = _fmt("frac", self.frac, signed=False)
        if frac.int_bits:
            raise ValueError(f"frac must be a fraction-only format (0.m), not {frac}")
        _int("k", self.k, 0, 4)
        _fmt("t", self.t, signed=False, holds_one=True)

    @property
    def shift(self):
        """``s = ceil((k+1)/2)``: ``u_i = m|D_i|/2^s`` and ``x/2^k = 2^(2s-1-k)·Σu_i²``.

        The smallest ``s`` with ``2s >= k+1``, so that ``c = 2^(2s-1-k)`` is 1 or 2, never
        below 1 (an integer part of any ``u_i`` then proves ``x/2^k >= 1``), while ``u_i``
        keeps the most significant bits of ``m|D_i|`` in its fraction.
        """
        return (self.k + 2) // 2

    @property
    def shape(self):
        """The Figure 7d :class:`ShapeConfig` behind the dot product: its ``x2`` is the
        exact format of ``Σ frac_i²`` with the point moved ``2s`` places (``2x = 2^(2s)·Σu_i²``)."""
        frac = self.fmt("frac")
        square = frac.mul(frac)
        x2 = square.add(square).add(square).shift(2 * self.shift)
        return ShapeConfig(x2=str(x2), k=self.k, t=self.t, rounding=self.rounding,
                           pipeline=self.pipeline)

    @property
    def inputs(self):
        ports = {"r": (self.fmt("vec"), 3), "l": (self.fmt("vec"), 3)}
        if not self.m_const:
            ports["m"] = (self.fmt("m"), 1)
        return ports

    @property
    def outputs(self):
        return {"spec": (self.fmt("t"), 1)}


HALFWAY_VARIANTS = ("d1", "d2", "d3", "g2proj", "g2")


@dataclass(frozen=True)
class HalfwayConfig(BlockConfig):
    """Halfway-vector difference (Lyon Figure 5, Figure 9 rows 7–10): ``D = p - q`` with

    * ``d1``: ``p = (2V·N)N``, ``q = H``;  ``d2``: ``p = (2L·N)N``, ``q = H`` (``|D2| = |D1|``);
    * ``d3``: ``p = (H·N)N``, ``q = H`` (no normalization of H);
    * ``g2proj``: ``p = (H*·N)N``, ``q = H*``;  ``g2``: ``p = N``, ``q = H*``;
      with ``H* = g2(H·H)·H`` from the :class:`NormalizeConfig` ``normalize``.

    ``h`` is ``"sum"`` (``H = V + L``, the text) or ``"mean"`` (``H = (L + V)/2``, the
    code; default).  ``"mean"`` halves every term, so d1/d2 project ``V`` and ``L``
    rather than ``2V`` and ``2L``: ``D1 = (R - L)/2``, and ``x = (4n/2)·D·D`` is the
    appendix's, as its ``n4`` scales it.

    Formats (our reconstruction; see :mod:`phongfx.golden.halfway`): ``hvec`` holds
    ``V + L`` (``S2.10``) and ``(V + L)/2`` (``S1.11``) exactly, so ``h`` changes without
    touching a format; ``dot`` has two integer bits for ``H·N = 2`` (``"sum"``, ``V = L = N``)
    and two guard bits; ``out`` holds ``|D|`` up to 2; ``normalize.vec`` must be ``hvec``.
    ``pipeline`` raises ``normalize.pipeline`` to at least its own depth.
    """

    vec: str = "S1.10"
    variant: str = "g2proj"
    h: str = "mean"
    hvec: str = "S2.11"
    dot: str = "S2.12"
    out: str = "S2.10"
    normalize: NormalizeConfig = NormalizeConfig(vec="S2.11", out="S2.11")
    rounding: str = "round_half_up"
    pipeline: int = 0

    def __post_init__(self):
        _inherit_pipeline(self, ("normalize",))
        super().__post_init__()

    def validate(self):
        _int("pipeline", self.pipeline, 0, MAX_PIPELINE)
        if self.variant not in HALFWAY_VARIANTS:
            raise ValueError(f"variant must be one of {', '.join(HALFWAY_VARIANTS)}, not {self.variant!r}")
        if self.h not in ("sum", "mean"):
            raise ValueError(f"h must be one of sum, mean, not {self.h!r}")
        _fmt("vec", self.vec, signed=True)
        hvec = _fmt("hvec", self.hvec, signed=True)
        _fmt("dot", self.dot, signed=True, holds_one=True)
        _fmt("out", self.out, signed=True)
        if not isinstance(self.normalize, NormalizeConfig):
            raise TypeError(f"normalize must be a NormalizeConfig, not {self.normalize!r}")
        if self.normalize.fmt("vec") != hvec:
            raise ValueError(f"normalize.vec ({self.normalize.vec}) must equal hvec ({self.hvec}): "
                             f"the normalizer takes H")

    @property
    def inputs(self):
        return {"n": (self.fmt("vec"), 3), "l": (self.fmt("vec"), 3), "v": (self.fmt("vec"), 3)}

    @property
    def outputs(self):
        return {"p": (self.fmt("out"), 3), "q": (self.fmt("out"), 3)}


@dataclass(frozen=True)
class SchlickConfig(BlockConfig):
    """Schlick (1994) rational specular unit ``S_n(t) = t / (n - n·t + t)``, ``t = cos α``
    in ``0..1``, ``n`` an integer ``1..n_max``; a pipelined restoring divider.

    ``rounding`` is ``truncate`` (the divider's floor) or ``round_half_up`` (one more
    quotient bit, then ``(q + 1) >> 1``).  Defaults: ``t`` and ``out`` ``1.15`` (1.0
    exact, as the shape function's), ``n`` ``13.0`` up to 8000 (Lyon's range).
    """

    t: str = "1.15"
    n: str = "13.0"
    n_max: int = 8000
    out: str = "1.15"
    rounding: str = "truncate"

    def validate(self):
        if self.rounding not in ("truncate", "round_half_up"):
            raise ValueError(f"rounding must be one of truncate, round_half_up (the divider "
                             f"floors), not {self.rounding!r}")
        t = _fmt("t", self.t, signed=False, holds_one=True)
        _int("n_max", self.n_max, 1, _integer_fmt("n", self.n).max_raw)
        _fmt("out", self.out, signed=False, holds_one=True)
        # the golden model forms t << (quotient bits - 1) in int64
        if t.width + self.quotient_bits - 1 > 62:
            raise ValueError(f"t ({t}) shifted by {self.quotient_bits - 1} quotient bits "
                             f"exceeds 62 bits")

    @property
    def quotient_bits(self):
        """Quotient bits the divider produces: weights ``2^0 .. 2^-F`` (``F`` fraction bits
        of ``out``), one more for ``round_half_up``."""
        return self.fmt("out").frac_bits + 1 + (self.rounding == "round_half_up")

    @property
    def den(self):
        """Format of the divisor ``n(1 - t) + t``: exact, from ``1.0`` (``t = 1`` or
        ``n = 1``) to ``n_max`` (``t = 0``)."""
        t = self.fmt("t")
        return Format.covering(0, self.n_max * t.one, t.frac_bits)

    @property
    def inputs(self):
        return {"t": (self.fmt("t"), 1), "n": (self.fmt("n"), 1)}

    @property
    def outputs(self):
        return {"spec": (self.fmt("out"), 1)}


@dataclass(frozen=True)
class SphericalConfig(BlockConfig):
    """Szirmay-Kalos et al. (2000) Figure 12 spherical interpolation unit: per scanline
    ``θ(X) = θ(X-1) + s`` from ``θ = b`` at ``init``, then ``C·cos²θ`` from a ROM (specular,
    one channel) and ``C_rgb·max(cos θ_d, 0)`` from a second ROM (diffuse, three channels).

    ``theta`` is the angle register in units of π (``S0.11``: 12 bits, the paper's
    ``bit_v_12``, ``θ ∈ [-π, π)``, wrapping); its top ``addr_bits`` (6) address both ROMs,
    whose words have the format ``rom`` (``0.6``: the paper's 6 × 6 bits).  ``c`` holds the
    per-scanline constants, ``out`` the products.  See :mod:`phongfx.golden.spherical`.
    """

    theta: str = "S0.11"
    addr_bits: int = 6
    rom: str = "0.6"
    c: str = "1.11"
    out: str = "1.11"
    rounding: str = "round_half_up"

    def validate(self):
        theta = _fmt("theta", self.theta, signed=True)
        if theta.int_bits:
            raise ValueError(f"theta must be a fraction-only format (S0.m, units of π), not {theta}")
        _int("addr_bits", self.addr_bits, 2, min(theta.width, 16))
        rom = _fmt("rom", self.rom, signed=False)
        if rom.int_bits:
            raise ValueError(f"rom must be a fraction-only format (0.m), not {rom}")
        _fmt("c", self.c, signed=False)
        _fmt("out", self.out, signed=False)

    @property
    def out_overflow(self):
        """``"error"`` where ``out`` holds every code of ``c``: a ROM word is below 1, so
        ``C·w < C``, and rounding to a grid that holds ``C`` cannot pass it; else saturate."""
        c, out = self.fmt("c"), self.fmt("out")
        return "error" if out.int_bits >= c.int_bits and out.frac_bits >= c.frac_bits else "saturate"

    @property
    def inputs(self):
        theta, c = self.fmt("theta"), self.fmt("c")
        return {"init": (Format(1, 0), 1), "b": (theta, 1), "s": (theta, 1), "c": (c, 1),
                "bd": (theta, 1), "sd": (theta, 1), "cd": (c, 3)}

    @property
    def outputs(self):
        return {"spec": (self.fmt("out"), 1), "diff": (self.fmt("out"), 3)}


@dataclass(frozen=True)
class EulerConfig(BlockConfig):
    """Hast, Barrera & Bengtsson corrected Euler unit: per pixel output ``p``, then
    ``p += t``, ``t += ds`` (equations 16–17); ``init`` loads ``p0``, ``t0``, ``ds``.

    ``p``, ``t``, ``ds`` are the register formats (signed); fraction bits must not fall
    from ``ds`` to ``t`` to ``p`` so both adders are exact and only the register widths
    wrap.  ``out`` is the intensity taken from ``p`` by truncation, saturated (``0.8``:
    ``floor(256·p)`` clamped to 0..255).  See :mod:`phongfx.golden.euler`.
    """

    p: str = "S1.30"
    t: str = "S3.30"
    ds: str = "S3.30"
    out: str = "0.8"

    def validate(self):
        _step_formats(self, ("ds", "t", "p"))
        _fmt("out", self.out)

    @property
    def inputs(self):
        return {"init": (Format(1, 0), 1), "p0": (self.fmt("p"), 1), "t0": (self.fmt("t"), 1),
                "ds": (self.fmt("ds"), 1)}

    @property
    def outputs(self):
        return {"p": (self.fmt("p"), 1), "level": (self.fmt("out"), 1)}


@dataclass(frozen=True)
class GouraudConfig(BlockConfig):
    """Gouraud unit: per pixel output ``p``, then ``p += dp``; ``init`` loads ``p0``, ``dp``.

    Formats as :class:`EulerConfig`: ``dp`` may not have more fraction bits than ``p``.
    """

    p: str = "S1.30"
    dp: str = "S3.30"
    out: str = "0.8"

    def validate(self):
        _step_formats(self, ("dp", "p"))
        _fmt("out", self.out)

    @property
    def inputs(self):
        return {"init": (Format(1, 0), 1), "p0": (self.fmt("p"), 1), "dp": (self.fmt("dp"), 1)}

    @property
    def outputs(self):
        return {"p": (self.fmt("p"), 1), "level": (self.fmt("out"), 1)}


def _step_formats(config, names):
    """Signed register formats whose fraction bits never fall along the adder chain
    ``names`` (each added into the next), so the recurrence adds exactly."""
    fmts = [_fmt(name, getattr(config, name), signed=True) for name in names]
    for (a, fa), (b, fb) in zip(zip(names, fmts), zip(names[1:], fmts[1:])):
        if fa.frac_bits > fb.frac_bits:
            raise ValueError(f"{a} ({fa}) may not have more fraction bits than {b} ({fb}): "
                             f"{a} is added into {b} exactly")


@dataclass(frozen=True)
class ConventionalConfig(BlockConfig):
    """The conventional Phong baseline Lyon (1993, "Background") argues against: exact
    normalization by ``1/sqrt(N·N)`` and true exponentiation ``t^n`` at 16-bit precision.

    Per pixel: ``diffuse = max(N·L, 0)/|N|`` and ``specular = (max(N·H, 0)/|N|)^n`` for an
    un-normalized ``N`` and unit ``L``, ``H`` (all ``vec``), shininess ``n`` an integer
    ``1..n_max``.  Stages (bit growth in :mod:`phongfx.golden.conventional`):

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

    def validate(self):
        _fmt("vec", self.vec, signed=True)
        _int("n_max", self.n_max, 1, _integer_fmt("n", self.n).max_raw)
        m = _fraction_fmt("m", self.m)
        _int("rsqrt_addr", self.rsqrt_addr, 2, min(m.frac_bits, 16))
        _fmt("y", self.y, signed=False, holds_one=True)
        nr = _fmt("nr", self.nr, signed=False)
        if nr.int_bits < 2:
            raise ValueError(f"nr must have at least 2 integer bits (y0² < 4), not {nr}")
        _fmt("dot", self.dot, signed=True, holds_one=True)
        t = _fmt("t", self.t, signed=False)
        if t.int_bits != 1 or t.frac_bits < 2:
            raise ValueError(f"t must be 1.m with m >= 2 (a cosine in 0..1, 1.0 exact), not {t}")
        log = _fraction_fmt("log", self.log)
        _int("log_addr", self.log_addr, 1, min(t.frac_bits - 1, log.frac_bits - 1, 16))
        exp = _fmt("exp", self.exp, signed=False, holds_one=True)
        _int("exp_addr", self.exp_addr, 1, min(log.frac_bits - 1, exp.frac_bits - 1, 16))
        _fmt("out", self.out, signed=False, holds_one=True)
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

    @property
    def inputs(self):
        vec = self.fmt("vec")
        return {"normal": (vec, 3), "light": (vec, 3), "half": (vec, 3), "n": (self.fmt("n"), 1)}

    @property
    def outputs(self):
        return {"diffuse": (self.fmt("out"), 1), "specular": (self.fmt("out"), 1)}


def _inherit_pipeline(config, names):
    """Raise the ``pipeline`` of the sub-configs ``names`` of ``config`` to at least its own
    (validated first; a sub-config of the wrong type is left for ``validate`` to name)."""
    depth = _int("pipeline", config.pipeline, 0, MAX_PIPELINE)
    for name in names:
        sub = getattr(config, name)
        if isinstance(sub, BlockConfig) and getattr(sub, "pipeline", depth) < depth:
            object.__setattr__(config, name, replace(sub, pipeline=depth))


SPECULAR_UNITS = ("fig7", "fig8", "halfway")


@dataclass(frozen=True)
class DatapathConfig(BlockConfig):
    """A whole shading datapath (Lyon 1993, Figures 6–8 and 5): interpolated, approximately
    normalized N, then one specular unit and the diffuse term, for ``lights`` lights.

    ``specular`` picks the unit after the normalizer:

    * ``"fig7"``: reflect → difference/x (``n``) → shape (Figure 7b–d);
    * ``"fig8"``: reflect → root-shininess unit (``m = √n``, Figure 8);
    * ``"halfway"``: halfway difference vector → difference/x with ``4n`` → shape
      (Figure 5; Figure 9 rows 7–10, as the appendix code scales ``n``).

    ``local_lights`` / ``local_viewer``: L / V are interpolated across the span with the
    same ``a`` and approximately normalized (``direction_normalize``, g1 or g2) like N;
    otherwise they are constant inputs and no LIRP or normalizer is built for them.
    Blocks that depend on L are repeated per light.  All direction vectors after the
    normalizers share the format ``normalize.out``; connected formats must agree.

    ``pipeline`` raises the pipeline depth of every block config to at least its value
    (``fig7_config(pipeline=2)``, ``--set pipeline=2``); a block's own field may go deeper.

    A single shininess is fixed in the unit's own config: ``difference.n_const`` (Figure 7;
    for the halfway unit the scaled ``n·2^halfway_shift``) or ``root.m_const`` (Figure 8).
    Then :attr:`inputs` has no ``n`` / ``m`` port, :attr:`shininess` is None and
    :attr:`shininess_const` gives the constant.
    """

    specular: str = "fig7"
    lirp: LirpConfig = LirpConfig()
    normalize: NormalizeConfig = NormalizeConfig()
    reflect: ReflectConfig = ReflectConfig()
    difference: DifferenceConfig = DifferenceConfig()
    shape: ShapeConfig = ShapeConfig()
    root: RootConfig = RootConfig()
    halfway: HalfwayConfig = HalfwayConfig()
    diffuse: DiffuseConfig = DiffuseConfig()
    lights: int = 2
    local_lights: bool = False
    local_viewer: bool = False
    direction_normalize: NormalizeConfig = NormalizeConfig()
    pipeline: int = 0

    def __post_init__(self):
        _inherit_pipeline(self, ("lirp", "normalize", "reflect", "difference", "shape", "root",
                                 "halfway", "diffuse", "direction_normalize"))
        super().__post_init__()

    def validate(self):
        for name, cls in (("lirp", LirpConfig), ("normalize", NormalizeConfig),
                          ("reflect", ReflectConfig), ("difference", DifferenceConfig),
                          ("shape", ShapeConfig), ("root", RootConfig), ("halfway", HalfwayConfig),
                          ("diffuse", DiffuseConfig), ("direction_normalize", NormalizeConfig)):
            if not isinstance(getattr(self, name), cls):
                raise TypeError(f"{name} must be a {cls.__name__}, not {getattr(self, name)!r}")
        if self.specular not in SPECULAR_UNITS:
            raise ValueError(f"specular must be one of {', '.join(SPECULAR_UNITS)}, not {self.specular!r}")
        _int("lights", self.lights, 1, 8)
        for name in ("local_lights", "local_viewer"):
            if not isinstance(getattr(self, name), bool):
                raise ValueError(f"{name} must be True or False, not {getattr(self, name)!r}")
        vec = ("normalize.out", self.normalize.out)
        links = [
            ("lirp.out", self.lirp.out, "normalize.vec", self.normalize.vec),
            (*vec, "diffuse.vec", self.diffuse.vec),
        ]
        if self.local_lights or self.local_viewer:
            links += [("lirp.out", self.lirp.out, "direction_normalize.vec", self.direction_normalize.vec),
                      (*vec, "direction_normalize.out", self.direction_normalize.out)]
        if self.specular == "fig7":
            links += [(*vec, "reflect.vec", self.reflect.vec),
                      ("reflect.out", self.reflect.out, "difference.vec", self.difference.vec),
                      (*vec, "difference.vec", self.difference.vec),
                      ("difference.x2", self.difference.x2, "shape.x2", self.shape.x2)]
        elif self.specular == "fig8":
            links += [(*vec, "reflect.vec", self.reflect.vec),
                      ("reflect.out", self.reflect.out, "root.vec", self.root.vec),
                      (*vec, "root.vec", self.root.vec)]
        else:
            links += [(*vec, "halfway.vec", self.halfway.vec),
                      ("halfway.out", self.halfway.out, "difference.vec", self.difference.vec),
                      ("difference.x2", self.difference.x2, "shape.x2", self.shape.x2)]
            if self.difference.fmt("n").int_bits < self.halfway_shift + 1:
                raise ValueError(f"difference.n must have at least {self.halfway_shift + 1} integer "
                                 f"bits to take n·2^{self.halfway_shift}, not {self.difference.n}")
            if self.difference.n_const % (1 << self.halfway_shift):
                raise ValueError(f"difference.n_const must be a multiple of {1 << self.halfway_shift} "
                                 f"(it is n·2^{self.halfway_shift}), not {self.difference.n_const}")
        for a_name, a, b_name, b in links:
            if Format.parse(a) != Format.parse(b):
                raise ValueError(f"{a_name} ({a}) must equal {b_name} ({b}): they are connected")

    @property
    def shininess(self):
        """(port name, format, largest value) of the per-pixel shininess input, or None when
        the shininess is a constant of the hardware (:attr:`shininess_const`): no such port.

        The port is ``m = √n`` for Figure 8, else ``n``; for the halfway unit, ``n`` before
        its scaling by ``2^halfway_shift``.
        """
        if self.shininess_const:
            return None
        if self.specular == "fig8":
            return "m", self.root.fmt("m"), self.root.m_max
        n = self.difference.fmt("n")
        if self.specular == "halfway":
            shift = self.halfway_shift
            return "n", Format(n.int_bits - shift, 0), self.difference.n_max >> shift
        return "n", n, self.difference.n_max

    @property
    def shininess_const(self):
        """The shininess fixed in the hardware, in the port's terms (``m`` for Figure 8, else
        ``n``), or 0 when it is a per-pixel input.

        From ``root.m_const`` (Figure 8) or ``difference.n_const`` (Figure 7, halfway).  The
        halfway unit's difference block multiplies by ``n·2^halfway_shift``, so its
        ``n_const`` is that product (validated a multiple of ``2^halfway_shift``): the pixel
        sees ``n = difference.n_const >> halfway_shift``, bit for bit as if fed on the port.
        """
        if self.specular == "fig8":
            return self.root.m_const
        return self.difference.n_const >> (self.halfway_shift if self.specular == "halfway" else 0)

    @property
    def halfway_shift(self):
        """log2 of the shininess scale into the halfway unit's difference block.

        The appendix uses ``4n`` with ``H = (L+V)/2`` (``h="mean"``), whose difference
        vectors are half as long as with ``H = V + L``: ``x = (4n/2)|D/2|²`` equals
        ``(n/2)|D|²``.  So ``h="mean"`` shifts ``n`` by 2 (free wiring), ``h="sum"`` by 0.
        """
        return 2 if self.halfway.h == "mean" else 0

    @property
    def inputs(self):
        vec, end = self.normalize.fmt("out"), self.lirp.fmt("vec")
        ports = {"n0": (end, 3), "n1": (end, 3), "a": (self.lirp.fmt("a"), 1)}
        if self.shininess is not None:
            name, fmt, _ = self.shininess
            ports[name] = (fmt, 1)
        if self.local_viewer:
            ports.update({"v0": (end, 3), "v1": (end, 3)})
        else:
            ports["v"] = (vec, 3)
        for i in range(self.lights):
            if self.local_lights:
                ports.update({f"l{i}_0": (end, 3), f"l{i}_1": (end, 3)})
            else:
                ports[f"l{i}"] = (vec, 3)
        return ports

    @property
    def outputs(self):
        t = self.root.fmt("t") if self.specular == "fig8" else self.shape.fmt("t")
        ports = {f"spec{i}": (t, 1) for i in range(self.lights)}
        ports.update({f"diff{i}": (self.diffuse.fmt("out"), 1) for i in range(self.lights)})
        return ports


def fig7_config(**changes):
    """Lyon's Figure 7 datapath (the default :class:`DatapathConfig`)."""
    return DatapathConfig(specular="fig7", **changes)


def fig8_config(**changes):
    """Figure 8: the root-shininess unit after reflect (``k = 1``, ``m = √n``)."""
    return DatapathConfig(specular="fig8", **changes)


def halfway_config(**changes):
    """A halfway-vector datapath (default: Lyon's row 8, ``g2proj``, ``k = 2``, ``4n``)."""
    changes.setdefault("difference", DifferenceConfig(vec="S2.10", n="15.0", n_max=32000))
    return DatapathConfig(specular="halfway", **changes)
