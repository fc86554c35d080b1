"""Table-driven arithmetic of the exact-Phong units (Lyon 1993, "Background": the direct
designs' 16-bit normalization and exponentiation), shared by the Blinn–Phong baseline
(:mod:`phongfx.hdl.blinn`) and the conventional Phong unit (:mod:`phongfx.hdl.conventional`).

Each function builds registered stages into ``m`` (hand-aligned, like the units: values
carry no cycle tags except where an ``overflow="error"`` quantize must be aligned with
``valid``) and is the twin of a function of :mod:`phongfx.golden.blinn`, whose tables it
reads:

* :func:`length_squared` (1 stage), :func:`even_shift` (1 stage) and
  :func:`reciprocal_sqrt` (4 stages): ``q = X·X``, ``q = m·4^(h-j)`` and ``y1 ~ 1/sqrt(m)``
  by the seed ROM and one Newton–Raphson step (the golden ``inverse_length``);
* :func:`scaled` (1 stage) and :func:`cosine` (1 stage): a dot product times ``2^(j-h)``,
  rounded to ``dot``, then times ``y1``, rounded and clamped to 1 (:func:`clamp_one`);
* :func:`power` (7 stages): ``t^n`` by the log2 and exp2 ROMs with linear interpolation,
  and :func:`shaded`, a unit's two outputs: the diffuse cosine delayed beside it;
* :func:`rom` and :func:`interpolate`, the table reads under them.

``config`` is a :class:`~phongfx.config.BlinnConfig` (or a subclass); ``prefix`` keeps
the registers and ROMs of a second copy apart from the first.
"""

from amaranth.hdl import Const, Mux
from amaranth.lib.memory import Memory

from phongfx.core.format import Format
from phongfx.golden.blinn import exp2_tables, log2_tables, rsqrt_table

from .fixed import FixedValue, delay, stage

__all__ = ["POWER_STAGES", "RSQRT_STAGES", "COSINE_STAGES", "rom", "interpolate", "length_squared",
           "even_shift", "reciprocal_sqrt", "scaled", "clamp_one", "cosine", "power", "shaded"]

#: Registered stages of :func:`power`: log normalization; log tables; log2 t; n·log2 t;
#: exp tables; 2^f; shift and round.
POWER_STAGES = 7
#: Registered stages of :func:`reciprocal_sqrt`: seed read; y0²; m·y0²; y1.
RSQRT_STAGES = 4
#: Registered stages from a vector to its cosines ``d·2^(j-h)·y1``: dot products (with
#: ``q``); :func:`even_shift`; :func:`reciprocal_sqrt` (:func:`scaled` beside its seed
#: read); :func:`cosine`.
COSINE_STAGES = 2 + RSQRT_STAGES + 1


def rom(m, name, words, fmt, address):
    """An asynchronous ROM of ``words`` (raw codes of ``fmt``) read at ``address``."""
    memory = Memory(shape=fmt.shape(), depth=len(words), init=[int(w) for w in words])
    m.submodules[name] = memory
    port = memory.read_port(domain="comb")
    m.d.comb += port.addr.eq(address)
    return FixedValue(port.data, fmt)


def interpolate(m, config, name, tables, code, bits, addr_bits, fmt, cycle):
    """``V + D·phi`` from registers holding the two words at the top ``addr_bits`` of
    ``code`` and its low bits ``phi`` (one stage); ``cycle``: that stage's output cycle."""
    low = bits - addr_bits
    value = stage(m, rom(m, f"{name}_value", tables[0], fmt, code[low:]), f"{name}_v")
    slope = stage(m, rom(m, f"{name}_slope", tables[1], tables[2], code[low:]), f"{name}_d")
    phi = stage(m, FixedValue(code[:low], Format(0, low)), f"{name}_phi")
    step = (slope * phi).shift(-addr_bits).tagged(cycle, m)
    return value + step.quantize(fmt, config.rounding, "error")


def length_squared(m, config, x, prefix=""):
    """Registered ``q = X·X`` of a ``vec`` vector, exact in ``config.q`` (1 stage, beside a
    unit's other dot products): the start of :func:`phongfx.golden.blinn.inverse_length`, the
    normalization of ``N`` (Blinn 1977, Phong 1975) and of a local ``L`` or ``V``.  Tagged
    with cycle 0 so that its ``overflow="error"`` quantize is aligned with ``valid``."""
    return stage(m, x.dot(x).tagged(0, m).quantize(config.q, "truncate", "error"), f"{prefix}q")


def even_shift(m, config, q, prefix=""):
    """Registered ``(j, m)`` of :func:`phongfx.golden.blinn.even_shift`: a priority encoder
    of ``q``'s leading all-zero bit pairs and a barrel shifter, ``m`` rounded (1 stage)."""
    qfmt = config.q
    pairs = qfmt.width // 2
    j = Const(pairs - 1, range(pairs))
    for k in range(pairs):
        j = Mux(q.value[2 * k:2 * k + 2].any(), pairs - 1 - k, j)
    mant = FixedValue((q.value << (j << 1))[:qfmt.width], Format(0, qfmt.width))
    mant = stage(m, mant.quantize(config.m, config.rounding, "saturate"), f"{prefix}m")
    return stage(m, j, f"{prefix}j"), mant


def reciprocal_sqrt(m, config, mant, prefix="", between=None):
    """``y1 ~ 1/sqrt(m)`` of :func:`phongfx.golden.blinn.reciprocal_sqrt`, :data:`RSQRT_STAGES`
    after ``mant``: the seed ROM, then ``y1 = y0·(3 - m·y0²)/2``.  ``between()`` is called
    after the seed read, so that a unit's registers of that stage keep their order."""
    rounding, mfmt = config.rounding, config.fmt("m")
    y0 = stage(m, rom(m, f"{prefix}rsqrt", rsqrt_table(config), config.fmt("y"),
                      mant.value[mfmt.frac_bits - config.rsqrt_addr:]), f"{prefix}y0")
    if between is not None:
        between()
    mant = stage(m, mant, f"{prefix}m_d")
    square = stage(m, (y0 * y0).quantize(config.nr, rounding, "saturate"), f"{prefix}y0sq")
    y0, mant = stage(m, y0, f"{prefix}y0_d1"), stage(m, mant, f"{prefix}m_d2")
    p = stage(m, (mant * square).quantize(config.nr, rounding, "saturate"), f"{prefix}p")
    y0 = stage(m, y0, f"{prefix}y0_d2")
    r = (FixedValue.const(3, "2.0") - p).shift(-1)
    return stage(m, (y0 * r).quantize(config.y, rounding, "saturate"), f"{prefix}y1")


def scaled(m, config, d, j, name):
    """``d·2^(j-h)`` rounded to ``config.dot`` and saturated (1 stage): the shift of
    :func:`phongfx.golden.blinn.cosine` before its multiply by ``y1``."""
    qfmt = config.q
    shift = qfmt.width // 2 - 1
    wide = Format.covering(d.fmt.min_raw << shift, d.fmt.max_raw << shift,
                           d.fmt.frac_bits + qfmt.int_bits // 2)
    value = FixedValue((d.value << j)[:wide.width], wide)
    return stage(m, value.quantize(config.dot, config.rounding, "saturate"), name)


def clamp_one(value):
    """``min(value, 1)`` in ``value``'s format (a multiplexer): the clamp of
    :func:`phongfx.golden.blinn.clamp_one`, on a rounded cosine."""
    return value.where(value < 1, FixedValue.const(1, value.fmt))


def cosine(m, config, s, y1, fmt, name="cos"):
    """``s·y1`` rounded to ``fmt`` (saturated: an unsigned ``fmt`` also clamps at 0) and
    clamped to 1, registered: the multiply of :func:`phongfx.golden.blinn.cosine`."""
    fmt = Format.parse(fmt)
    return stage(m, clamp_one((s * y1).quantize(fmt, config.rounding, "saturate")), name)


def power(m, config, t, n, cycle):
    """``t^n`` of :func:`phongfx.golden.blinn.power`, registered :data:`POWER_STAGES` after
    ``t`` and ``n`` (both valid at ``cycle``): leading zeros of ``t``, log tables, ``n·log2 t``,
    exp tables, the shift by the integer part and the output rounding."""
    frac = t.fmt.frac_bits
    s = Const(frac, range(frac + 1))
    for k in range(frac + 1):  # leading zeros of t's code, up to its 2^0 bit
        s = Mux(t.value[k], frac - k, s)
    mantissa = stage(m, (t.value << s)[:frac], "mantissa")
    s = stage(m, s, "s")
    zero = delay(m, t.value == 0, POWER_STAGES - 1, "zero")
    n = delay(m, n, 3, "n_log")

    log = interpolate(m, config, "log", log2_tables(config), mantissa, frac, config.log_addr,
                      config.fmt("log"), cycle=cycle + 2)
    s = FixedValue(stage(m, s, "s_d"), Format.covering(0, frac, 0))
    lam = stage(m, log - s, "lam")
    x = stage(m, n * lam, "x")

    xf = x.fmt.frac_bits
    floor = x.value[xf:].as_signed()
    flush = config.flush
    # the left shift flush - clip(-floor, 0, flush) that places 2^f·2^floor
    v = floor + flush
    lsh = stage(m, Mux(v < 0, 0, Mux(v > flush, flush, v))[:flush.bit_length()], "lsh")
    keep = stage(m, v >= 0, "keep")
    e = interpolate(m, config, "exp", exp2_tables(config), x.value[:xf], xf, config.exp_addr,
                    config.fmt("exp"), cycle=cycle + 5)
    e = stage(m, e, "e")
    lsh, keep = stage(m, lsh, "lsh_d"), stage(m, keep, "keep_d")

    wide = Format(e.fmt.int_bits, e.fmt.frac_bits + flush)
    spec = FixedValue((e.value << lsh)[:wide.width], wide, cycle + POWER_STAGES - 1, m)
    spec = spec.quantize(config.out, config.rounding, "error")
    spec = spec.where(keep & ~zero, FixedValue.const(0, config.out))
    return stage(m, spec, "specular")


def shaded(m, config, diffuse, t, n, cycle):
    """A table unit's outputs ``{"diffuse", "specular"}``, :data:`POWER_STAGES` after
    ``cycle``: ``t^n`` by :func:`power` (Blinn's ``(N·H)^n``, Phong's ``(R·V)^n``) and the
    diffuse cosine delayed beside it.  ``diffuse`` and ``t`` are valid at ``cycle``, ``n``
    is the unit's input (cycle 0), delayed to meet ``t``."""
    n = delay(m, n, cycle, "n")
    return {"diffuse": delay(m, diffuse, POWER_STAGES, "diffuse"), "specular": power(m, config, t, n, cycle)}
