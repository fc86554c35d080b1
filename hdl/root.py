"""Root-shininess specular unit component, Lyon (1993) Figure 8."""

from functools import cached_property

from amaranth.hdl import Cat

from phongfx.config import RootConfig
from phongfx.core.format import Format

from .block import PipelinedBlock, unbuilt
from .constant import shininess_product
from .dsp import product
from .fixed import FixedValue, FixedVector, cut, delay, stage
from .shape import Shape

__all__ = ["Root"]


class Root(PipelinedBlock):
    """Subtractors, rectifiers, ``m`` multipliers, fraction-only dot product, augmented
    comparator, then Figure 7d (Lyon 1993, Figure 8).

    Three ``m × |D_i|`` multipliers (6×11 by default, the paper's "7×11") and three
    squarers of the first ``frac`` fraction bits of ``u_i = m|D_i|/2^s`` (9×9); the
    shift by ``s`` and the one by ``2s`` into ``2x`` are wiring.  The shape function is
    a :class:`~phongfx.hdl.shape.Shape` submodule built from :attr:`RootConfig.shape`.
    Formats, rounding and the error bound are as in :func:`phongfx.golden.root.root`.

    Latency: ``3 + [pipeline ≥ 1] + 2·[pipeline ≥ 2] + 4·[pipeline ≥ 4] + shape`` (depth 4
    registers both multiplier levels' inputs and products once more, so the DSPs meet only registers), ``shape`` being the
    Shape latency at the same depth (``1 + k`` at depth 0).  Depth 0: the products
    ``m|D_i|``; the squares and the comparator flag; their sum ``2x``; then the shape.
    Each multiplier level is registered before the adder behind it, as in Figure 7c.
    Depth 1 registers ``|D_i|`` and ``m`` before the multipliers (the squarers' inputs
    are bits of the registered products already); depth 2 also cuts the subtractors
    from their saturation and that from the rectifiers; depth 3 adds nothing here (the
    saturations follow a subtractor or negator already cut off, with nothing to round).
    The flag waits (automatically) alongside the sum and the shape, and its multiplexer
    follows the shape's.

    With ``config.m_const`` there is no ``m`` port and the three multipliers are constant
    ones, shifts and adds (:func:`~phongfx.hdl.constant.shininess_product`, as Figure 7c's
    ``n_const``; none for a power of two), with the same codes, registers and latency.

    Ports: ``i.payload`` = ``r``, ``l`` (3 × ``config.vec``), ``m`` (``config.m``; absent
    when ``config.m_const`` is set); ``o.payload`` = ``spec`` (``config.t``).
    """

    config_class = RootConfig

    def __init__(self, config):
        super().__init__(config)
        # owned by this block: only an unused Root should warn
        self._shape = unbuilt(Shape(config.shape))

    @cached_property
    def latency(self):
        depth = self.config.pipeline
        return 3 + (depth >= 1) + 2 * (depth >= 2) + 4 * (depth >= 4) + self._shape.latency

    def datapath(self, m, i):
        cfg, depth = self.config, self.config.pipeline
        m.submodules.shape = self._shape
        d = cut(m, i["r"] - i["l"], depth >= 2, "dsub").quantize(cfg.d, cfg.rounding, "saturate")
        d = cut(m, d, depth >= 2, "d")
        magnitude = cut(m, FixedVector(_rectify(di, cfg.rounding) for di in d), depth >= 1, "abs")
        md = shininess_product(m, cfg, i, magnitude,
                               lambda port: product(m, magnitude, cut(m, port, depth >= 1, "m_in"), name="md",
                                                  isolate=depth >= 4), "md")
        u = md.shift(-cfg.shift)
        big = md[0].flag(Cat(*(ui >= 1 for ui in u)).any(), "big")
        frac = u.quantize(cfg.frac, "truncate", "wrap")
        squares = product(m, frac, frac, name="squares", isolate=depth >= 4)
        x2 = stage(m, squares.sum(), "sum").shift(2 * cfg.shift)
        self._shape.feed(m, delay(m, self.i.valid, x2.cycle, "valid"), {"x2": x2})
        return {"spec": FixedValue.const(0, cfg.t).where(big, self._shape.results()["spec"]),
                "valid": self._shape.o.valid}


def _rectify(d, rounding):
    """``|d|`` in the unsigned twin of ``d``'s format: negator, multiplexer, saturation
    of the one code (``-2^int_bits``) whose magnitude the format cannot hold."""
    neg = -d
    wide = d.quantize(neg.fmt, rounding, "error")
    return neg.where(d < 0, wide).quantize(Format(d.fmt.int_bits, d.fmt.frac_bits), rounding, "saturate")
