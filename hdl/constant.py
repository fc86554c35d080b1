"""Multiplying by a constant in shifts and adds, and the shininess product that uses it.

Lyon (1993) multiplies by the shininess twice over: Figure 7c's ``n × D·D`` and Figure 8's
three ``m × |D_i|``.  With the shininess fixed in the hardware
(:class:`~phongfx.config.base.ConstantShininess`) either multiplier is by a constant:
:func:`shininess_product` builds that choice once for both blocks, and :func:`const_product`
the constant multiplier, in canonical signed digits (:func:`signed_digits`).
"""

from phongfx.core.format import Format

from .dsp import registered
from .fixed import FixedVector, cut, stage

__all__ = ["signed_digits", "const_product", "shininess_product"]


def signed_digits(constant):
    """``constant`` (> 0) in canonical signed digits: ``[(sign, shift)]``, ``constant =
    Σ sign·2^shift``, the fewest non-zero digits (no two adjacent), lowest first."""
    digits, shift = [], 0
    while constant:
        if constant & 1:
            sign = 2 - (constant & 3)  # ...01 -> +1, ...11 -> -1 (and carry)
            digits.append((sign, shift))
            constant -= sign
        constant >>= 1
        shift += 1
    return digits


def const_product(m, value, constant, fmt, on, name):
    """``constant × value`` by shifts and adds, registered as :func:`~phongfx.hdl.dsp.split_product` registers
    the product with a ``constant`` port of the integer format ``fmt``: the same codes in the
    same format, the same cycles.  Without this a constant operand still becomes a DSP
    multiplier (Yosys' ``synth_ecp5`` maps a ``$mul`` by a constant that is not a power of
    two to MULT18X18D); here a power of two is wiring and ``c`` another constant takes
    one adder fewer than it has signed digits (:func:`signed_digits`).

    If ``on`` (pipeline depth 3) the digits are summed in two registered halves, then
    their sum registered, as :func:`~phongfx.hdl.dsp.split_product` splits a wide product.
    """
    fmt = Format.parse(fmt).mul(value.fmt)

    def total(digits):
        terms = [value.shift(shift) if sign > 0 else -value.shift(shift) for sign, shift in digits]
        result = terms[0]
        for term in terms[1:]:
            result = result + term
        return result

    digits = sorted(signed_digits(constant), key=lambda digit: -digit[0])  # a positive one first
    if not on:
        return stage(m, total(digits).quantize(fmt, "truncate", "wrap"), name)
    if len(digits) == 1:  # a shift: the second register keeps the latency
        return stage(m, stage(m, total(digits), name).quantize(fmt, "truncate", "wrap"), f"{name}_sum")
    half = len(digits) // 2
    low, high = stage(m, total(digits[:half]), f"{name}_lo"), stage(m, total(digits[half:]), f"{name}_hi")
    return stage(m, (low + high).quantize(fmt, "truncate", "wrap"), f"{name}_sum")


def shininess_product(m, config, i, value, fed, name, split=False):
    """``value`` (a :class:`~phongfx.hdl.fixed.FixedValue`, or a
    :class:`~phongfx.hdl.fixed.FixedVector` multiplied lane by lane) times the shininess of
    the block ``config`` (a ``ConstantShininess``): ``fed(port)`` of the input port's value
    ``i[config.SHININESS]`` when it is a port, else the constant's :func:`const_product`
    (summed in two registered halves if ``split``, as ``fed`` splits its product), with the
    registers a multiplier isolated at pipeline depth 4 has around it (``product``'s
    ``isolate``): the same codes, registers and latency as ``fed``.
    """
    constant = config.shininess_const
    if not constant:
        return fed(i[config.SHININESS])
    isolate = config.pipeline >= 4
    if isolate:
        value = registered(value)[0]
    fmt = config.fmt(config.SHININESS)
    if isinstance(value, FixedVector):
        p = FixedVector(const_product(m, lane, constant, fmt, split, f"{name}_{axis}")
                        for lane, axis in zip(value, "xyz"))
    else:
        p = const_product(m, value, constant, fmt, split, name)
    return cut(m, p, isolate, f"{name}_out")
