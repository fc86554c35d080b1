"""Difference vector and ``2x`` component, Lyon (1993) Figure 7c: ``2x = n·D·D``."""

from functools import cached_property

from phongfx.config import DifferenceConfig
from phongfx.core.format import Format

from .block import PipelinedBlock
from .dsp import product, registered, split_product
from .fixed import cut, quantize_cut, stage

__all__ = ["Difference", "const_product", "signed_digits"]


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
    """``constant × value`` by shifts and adds, registered as :func:`split_product` registers
    the product with a ``constant`` port of the integer format ``fmt``: the same codes in the
    same format, the same cycles.  Without this a constant operand still becomes a DSP
    multiplier (Yosys' ``synth_ecp5`` maps a ``$mul`` by a constant that is not a power of
    two to MULT18X18D); here a power of two is wiring and ``c`` another constant takes
    one adder fewer than it has signed digits (:func:`signed_digits`).

    If ``on`` (pipeline depth 3) the digits are summed in two registered halves, then
    their sum registered, as :func:`split_product` splits a wide product.
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


class Difference(PipelinedBlock):
    """Subtractors, squared length and shininess scaling, as drawn in Figure 7c.

    Three subtractors feed three squaring multipliers (12×12 by default), an adder
    tree gives ``D·D``, and one 13×22 multiplier scales it by ``n``.  Bit growth and
    saturation are as in :func:`phongfx.golden.difference.difference`.

    Latency: ``4 + [pipeline ≥ 1] + 2·[pipeline ≥ 2] + 3·[pipeline ≥ 3] + 4·[pipeline ≥ 4]``
    (4, 5, 7, 10, 14); depth 4 registers both multiplier levels' inputs and products once
    more (so the DSPs meet only registers) and clamps by bit tests.  Depth 0: squares
    ``D_i²``; the saturated ``D·D``; the product ``n·D·D``; the rounded, saturated
    ``2x``: each multiplier level is registered before the adder or rounder behind
    it.  Depth 1 registers ``D`` before the squarers; depth 2 also cuts the
    subtractors from their saturation and the adder tree from its rounding; depth 3
    cuts the roundings of ``D·D`` and ``2x`` from their clamps and splits ``n·D·D`` (13×22,
    wider than one MULT18X18D) into two registered partial products and their sum.  ``n``
    waits (automatically) to meet ``D·D``.  With ``config.n_const`` there is no ``n`` port
    and the multiplier is a constant one, shifts and adds (:func:`const_product`; none for
    a power of two), with the same codes, registers and latency.

    Ports: ``i.payload`` = ``r``, ``l`` (3 × ``config.vec``), ``n`` (``config.n``; absent
    when ``config.n_const`` is set); ``o.payload`` = ``x2`` (``config.x2``).
    """

    config_class = DifferenceConfig

    @cached_property
    def latency(self):
        depth = self.config.pipeline
        return 4 + (depth >= 1) + 2 * (depth >= 2) + 3 * (depth >= 3) + 4 * (depth >= 4)

    def datapath(self, m, i):
        cfg, depth = self.config, self.config.pipeline
        d = cut(m, i["r"] - i["l"], depth >= 2, "dsub").quantize(cfg.d, cfg.rounding, "saturate")
        d = cut(m, d, depth >= 1, "d")
        squares = product(m, d, d, name="squares", isolate=depth >= 4)
        total = cut(m, squares.sum(), depth >= 2, "total")
        dd = stage(m, quantize_cut(m, total, cfg.dd, cfg.rounding, "saturate", depth >= 3, "dd_round", depth >= 4),
                   "dd")
        if cfg.n_const:
            p = const_product(m, registered(dd)[0] if depth >= 4 else dd, cfg.n_const, cfg.n, depth >= 3, "p")
            p = cut(m, p, depth >= 4, "p_out")  # as a multiplier's isolated product
        else:
            p = split_product(m, i["n"], dd, depth >= 3, "p", depth >= 4)
        return {"x2": stage(m, quantize_cut(m, p, cfg.x2, cfg.rounding, "saturate", depth >= 3,
                                            "x2_round", depth >= 4), "x2")}
