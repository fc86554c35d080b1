"""Multipliers with their pipeline registers, and their ECP5 MULT18X18D mapping.

Every variable × variable product of the Lyon blocks goes through :func:`product` (or
:func:`split_product`, the two-level form of the deepest pipeline).  Elaborated normally
they are ``a * b`` and :func:`~phongfx.hdl.fixed.stage` registers, as ever: the RTL the
simulators check and the other targets synthesize.

Yosys maps an ECP5 multiply to a MULT18X18D (``mul2dsp`` and ``dsp_map_18x18.v``) but sets
none of its ``REG_*`` parameters, and no Yosys version packs fabric flip-flops into the ECP5
DSP (that pass exists only for the Nexus family), so every pipelined product paid a
fabric register → DSP → fabric register path (4.45 ns of logic plus 4.3–4.8 of routing on
LFE5U-45F at depth 3).  Under :func:`dsp_mapping` ``("ecp5")`` the same call instantiates
the DSP itself and hands it the registers the RTL already has:

* an operand that is a register's output (:attr:`FixedValue.pre
  <phongfx.hdl.fixed.FixedValue.pre>` is what the register holds) is taken from before
  that register, into the DSP's input register (``REG_INPUTA_CLK`` / ``REG_INPUTB_CLK``);
  both operands or neither (nextpnr times a DSP with one input register as if it had
  none).  The fabric register stays where something else reads it;
* the register behind the product becomes the DSP's output register (``REG_OUTPUT_CLK``);
* a product wider than one DSP (18 × 18 signed) is split into 17-bit unsigned low parts and
  a signed top part, one DSP per pair, summed in the fabric.  That sum needs a register
  after the DSPs' outputs, so a split product keeps only its input registers in the DSPs
  and its output register in the fabric, except in :func:`split_product`'s two-level form,
  whose partial products are registered in the DSPs and summed a clock later.

The latency and the codes do not change (tests/hdl/test_dsp.py checks the mapped RTL
against the golden model with :data:`MODEL`, the DSP's behavioural twin).  Products of a
constant stay ``$mul`` cells, as before.

Under :func:`recording_products` every call of :func:`product` and :func:`split_product`
is listed as :class:`ProductCall` (operand formats and registers, the call's options), so
that :mod:`phongfx.sim.dsp_equivalence` can prove each distinct mapping a block uses equal
to ``*``; recording changes nothing the calls build.

Caveat on timing: nextpnr does not time the multiply between a DSP's own input and output
registers (its timing data puts that path at 3.5–3.9 ns), so a design whose worst path is
elsewhere reports that path's Fmax, and the DSP itself is bounded by
:data:`DSP_INTERNAL_NS`.
"""

import contextlib
import contextvars
import functools
import inspect
from dataclasses import dataclass
from pathlib import Path

from amaranth.hdl import Cat, ClockSignal, Const, Instance, ResetSignal, Signal

from phongfx.core.format import Format

from .context import scoped
from .fixed import FixedValue, FixedVector, align, fit, stage

__all__ = ["DSP_BITS", "DSP_TARGETS", "MODEL", "DSP_INTERNAL_NS", "ProductCall", "dsp_mapping", "dsp_target",
           "DSP_MAPPING", "DSP_MAPPING_DEPTH", "dsp_mapping_of",
           "product", "recording_products", "registered", "split_product"]

#: Unsigned bits of a MULT18X18D operand part (18-bit signed inputs hold 17 unsigned bits).
DSP_BITS = 17
#: Targets :func:`dsp_mapping` knows.
DSP_TARGETS = ("ecp5",)
#: The Verilog behavioural model of MULT18X18D, for simulating mapped RTL and netlists.
MODEL = Path(__file__).with_name("mult18x18d.v")
#: The multiply inside a MULT18X18D between its input and output registers, which nextpnr
#: does not time: the upper end of the 3.5–3.9 ns its timing data gives the combinational
#: A/B → P path (speed grade 6), i.e. at most 1000 / 3.9 = 256 MHz.
DSP_INTERNAL_NS = 3.9

_TARGET = contextvars.ContextVar("phongfx_dsp_target", default=None)
# the list recording_products appends to; None outside it and inside a recorded call
_RECORDING = contextvars.ContextVar("phongfx_dsp_recording", default=None)


@dataclass(frozen=True)
class ProductCall:
    """One scalar product as :func:`product` or :func:`split_product` (``function``) was
    asked for it: the operand formats; whether each operand, once aligned to the other, is
    a register's output (``pre`` set: what a DSP input register can absorb); and the
    call's ``output``, ``on`` and ``isolate`` (``output`` True and ``on`` False where the
    function has no such argument).  A vector call is one record per element pair."""

    function: str
    a: Format
    b: Format
    a_registered: bool
    b_registered: bool
    output: bool
    on: bool
    isolate: bool
    name: str


@contextlib.contextmanager
def recording_products():
    """Inside, every outermost :func:`product` / :func:`split_product` call with two
    variable operands (a constant one is never mapped) is appended, as
    :class:`ProductCall`, to the list this yields; the calls they make themselves are not."""
    with scoped(_RECORDING, []) as calls:
        yield calls


def _recorded(function):
    signature = inspect.signature(function)

    @functools.wraps(function)
    def call(*args, **kwargs):
        calls = _RECORDING.get()
        if calls is None:
            return function(*args, **kwargs)
        arguments = signature.bind(*args, **kwargs)
        arguments.apply_defaults()
        calls.extend(_calls(function.__name__, arguments.arguments))
        with scoped(_RECORDING, None):  # product inside split_product, vectors' elements
            return function(*args, **kwargs)
    return call


def _calls(function, arguments):
    a, b = arguments["a"], arguments["b"]
    vector = isinstance(a, FixedVector) or isinstance(b, FixedVector)
    pairs = zip(_items(a), _items(b)) if vector else [(a, b)]
    for x, y in pairs:
        if x.cycle is None or y.cycle is None:
            continue
        # align() delays the earlier operand by registers, which a DSP can absorb too
        cycle = max(x.cycle, y.cycle)
        yield ProductCall(function, x.fmt, y.fmt, x.pre is not None or x.cycle < cycle,
                          y.pre is not None or y.cycle < cycle, arguments.get("output", True),
                          arguments.get("on", False), arguments["isolate"], arguments["name"])


@contextlib.contextmanager
def dsp_mapping(target):
    """Elaborate blocks inside with their products mapped onto ``target``'s DSPs
    (``"ecp5"``), or as plain ``*`` (``None``, the default)."""
    if target is not None and target not in DSP_TARGETS:
        raise ValueError(f"DSP target must be one of {', '.join(map(repr, DSP_TARGETS))} or None, "
                         f"not {target!r}")
    with scoped(_TARGET, target):
        yield


def dsp_target():
    """The target of the :func:`dsp_mapping` in force (None: plain multiplies)."""
    return _TARGET.get()


#: Targets whose products synthesis maps onto DSP instances under :func:`dsp_mapping` (with
#: the pipeline's registers inside them) rather than leaving them to Yosys: ECP5, where no Yosys
#: pass packs registers into MULT18X18D.  (Yosys' ``ice40_dsp`` packs SB_MAC16 registers
#: itself, but only reset-less ones.)
DSP_MAPPING = {"ecp5": "ecp5"}


#: The shallowest pipeline depth synthesized with its products mapped under :func:`dsp_mapping`.
#: Measured on LFE5U-45F (median of 3 seeds): at depth 2 the mapping costs fig7 85.1 →
#: 52.7 MHz, because the register it moves into the DSP was fed by a rounding and a clamp,
#: which then share a clock with the 7–14 ns route into the DSP; at depth 3 it gains
#: (102.6 → 107.7), at depth 4 every DSP meets registers only (189.5 MHz).  Shallower
#: depths keep Yosys' own mapping, so their figures stand.
DSP_MAPPING_DEPTH = 3


def dsp_mapping_of(block, target):
    """The :func:`dsp_mapping` target under which ``block`` is synthesized for ``target``
    (the synthesis flow and the DSP proofs ask the same question): the DSP target where there is one and the block is pipelined to
    :data:`DSP_MAPPING_DEPTH` or deeper, else None."""
    deep = getattr(block.config, "pipeline", 0) >= DSP_MAPPING_DEPTH
    return DSP_MAPPING.get(target) if deep else None


@_recorded
def product(m, a, b, output=True, name="product", isolate=False):
    """``a * b`` (:class:`FixedValue` or :class:`FixedVector`, elementwise), registered once
    if ``output``; the same codes at the same cycle whether mapped onto DSPs or not.

    ``isolate`` (pipeline depth 4) registers both operands once more before the multiplier
    and the product once more after it, two clocks more: a DSP then takes its operands
    register to register and hands its product to a register, with nothing but routing on
    either side.  The routing between the fabric and the DSP rows takes 4–6 ns on
    LFE5U-45F, too much to share a clock with any logic at 150 MHz."""
    if isolate:
        a, b = registered(a, b)
        return stage(m, product(m, a, b, output, name), f"{name}_out")
    if dsp_target() is None:
        return stage(m, a * b, name) if output else a * b
    if isinstance(a, FixedVector) or isinstance(b, FixedVector):
        pairs = zip(_items(a), _items(b), "xyz")
        return FixedVector(product(m, x, y, output, f"{name}_{axis}") for x, y, axis in pairs)
    mapped = _mapped(a, b)
    if mapped is None or not (output or mapped[2]):  # no register to give the DSP: Yosys maps it
        return stage(m, a * b, name) if output else a * b
    a, b, absorbed = mapped
    fmt = a.fmt.mul(b.fmt)
    parts = _parts(a, b)
    inner = output and len(parts) == 1  # a sum of parts needs the register after it
    total = _sum(fmt, [(shift, _mult18x18d(m, x, y, absorbed, inner, f"{name}_dsp{index}"))
                       for index, (shift, x, y) in enumerate(parts)])
    result = FixedValue(total, fmt, a.cycle + absorbed + inner, m, name)
    return stage(m, result, name) if output and not inner else result


def registered(*values):
    """``values`` (:class:`FixedValue` / :class:`FixedVector`) aligned, then each one clock
    later (shared delay registers; constants as they are)."""
    values = align(*values)
    cycles = [value.cycle for value in values if value.cycle is not None]
    return values if not cycles else [value.at(max(cycles) + 1) for value in values]


@_recorded
def split_product(m, a, b, on, name="product", isolate=False):
    """``a * b`` registered; if ``on``, in two clocks: the products of ``a`` with the low
    :data:`DSP_BITS` bits of the wider operand and with the rest, each registered, then
    their sum.  Yosys splits a multiplier wider than a MULT18X18D the same way, but
    with the adder right behind the DSPs, in the same stage.  Same codes either way.
    Mapped, each partial product's register is its DSP's output register.  ``isolate`` as
    for :func:`product`: the operands and each partial product registered once more.
    """
    if not on:
        return product(m, a, b, True, name, isolate)
    a, b = registered(a, b) if isolate else align(a, b)
    if a.fmt.width > b.fmt.width:
        a, b = b, a
    fmt = a.fmt.mul(b.fmt)
    if b.fmt.width <= DSP_BITS + 1:  # one DSP: a second register keeps the latency
        p = product(m, a, b, True, name)
        return stage(m, stage(m, p, f"{name}_out") if isolate else p, f"{name}_sum")
    mapped = _mapped(a, b)
    if mapped is not None:
        a, b, absorbed = mapped
        terms = [(shift, _mult18x18d(m, x, y, absorbed, True, f"{name}_dsp{index}"))
                 for index, (shift, x, y) in enumerate(_parts(a, b))]
        if isolate:
            terms = [(shift, stage(m, value, f"{name}_out{index}")) for index, (shift, value) in enumerate(terms)]
        total = FixedValue(_sum(fmt, terms), fmt, a.cycle + absorbed + 1 + isolate, m)
        return stage(m, total, f"{name}_sum")
    low = stage(m, a.value * b.value[:DSP_BITS], f"{name}_lo")
    high = b.value[DSP_BITS:]
    high = stage(m, a.value * (high.as_signed() if b.fmt.signed else high), f"{name}_hi")
    if isolate:
        low, high = stage(m, low, f"{name}_lo_out"), stage(m, high, f"{name}_hi_out")
    cycle = None if a.cycle is None else a.cycle + 1 + isolate
    total = FixedValue(fit((high << DSP_BITS) + low, fmt), fmt, cycle, m)
    return stage(m, total, f"{name}_sum")


def _items(x):
    return list(x) if isinstance(x, FixedVector) else [x, x, x]


def _mapped(a, b):
    """``(a, b, absorbed)`` as the DSP takes them, or None where the product stays ``*``:
    no mapping in force, or a constant operand.  ``absorbed``: both operands are register
    outputs, replaced by what their registers hold (the DSP's input registers hold it)."""
    if dsp_target() is None:
        return None
    a, b = align(a, b)
    if a.cycle is None or b.cycle is None:
        return None
    if a.pre is not None and b.pre is not None:
        return a.pre, b.pre, True
    return a, b, False


def _chunks(value, fmt):
    """``[(shift, 18-bit value)]``: ``value`` as 17-bit unsigned parts and a top part of its
    own signedness, each sign- or zero-extended to a DSP operand."""
    value = fit(value, fmt)
    if fmt.width <= DSP_BITS + fmt.signed:
        return [(0, fit(value, Format(18, 0, True)))]
    chunks = []
    for start in range(0, fmt.width, DSP_BITS):
        part = value[start:start + DSP_BITS]
        top = start + DSP_BITS >= fmt.width
        part = part.as_signed() if top and fmt.signed else part.as_unsigned()
        chunks.append((start, fit(part, Format(18, 0, True))))
    return chunks


def _parts(a, b):
    """``[(shift, a part, b part)]`` whose shifted products sum to ``a * b``."""
    return [(sa + sb, x, y) for sa, x in _chunks(a.value, a.fmt) for sb, y in _chunks(b.value, b.fmt)]


def _sum(fmt, terms):
    total = None
    for shift, value in terms:
        value = value.as_signed() << shift
        total = value if total is None else total + value
    return fit(total, fmt)


def _mult18x18d(m, a, b, inputs, output, name):
    """A MULT18X18D of two 18-bit signed operands, with its input and output registers if
    asked; its 36-bit signed product."""
    p = Signal(36, name=name)
    clock = "CLK0" if inputs else "NONE"
    ports = {f"i_A{bit}": a[bit] for bit in range(18)}
    ports.update({f"i_B{bit}": b[bit] for bit in range(18)})
    ports.update({f"i_C{bit}": Const(0, 1) for bit in range(18)})
    ports.update({f"o_P{bit}": p[bit] for bit in range(36)})
    # SRIA/SRIB stay unconnected: nextpnr cannot route a constant to them
    m.submodules[name] = Instance(
        "MULT18X18D",
        p_REG_INPUTA_CLK=clock, p_REG_INPUTB_CLK=clock,
        p_REG_OUTPUT_CLK="CLK0" if output else "NONE",
        p_RESETMODE="SYNC",
        i_SIGNEDA=Const(1, 1), i_SIGNEDB=Const(1, 1), i_SOURCEA=Const(0, 1), i_SOURCEB=Const(0, 1),
        i_CLK0=ClockSignal("sync"), i_CE0=Const(1, 1), i_RST0=ResetSignal("sync"),
        **ports)
    return Cat(p).as_signed()
