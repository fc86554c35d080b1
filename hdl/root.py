"""Root-shininess specular unit component, Lyon (1993) Figure 8."""

from amaranth.hdl import Cat

from ..config import RootConfig
from ..format import Format
from .block import PipelinedBlock
from .fixed import FixedValue, FixedVector, delay, stage
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

    Latency: ``3 + (1 + k)``: the products ``m|D_i|``; the squares and the comparator
    flag; their sum ``2x``; then the shape's ``1 + k``.  Each multiplier level is
    registered before the adder behind it, as in Figure 7c.  The flag is delayed
    alongside the sum and the shape, and its multiplexer follows the shape's.

    Ports: ``i.payload`` = ``r``, ``l`` (3 × ``config.vec``), ``m`` (``config.m``);
    ``o.payload`` = ``spec`` (``config.t``).
    """

    config_class = RootConfig

    def __init__(self, config):
        super().__init__(config)
        self._shape = Shape(config.shape)
        self._shape._MustUse__silence = True  # owned by this block: only an unused Root should warn

    @property
    def latency(self):
        return 3 + self._shape.latency

    def datapath(self, m, i):
        cfg = self.config
        m.submodules.shape = self._shape
        d = (i["r"] - i["l"]).quantize(cfg.d, cfg.rounding, "saturate")
        md = stage(m, FixedVector(_rectify(di, cfg.rounding) for di in d) * i["m"], "md")
        u = md.shift(-cfg.shift)
        big = stage(m, Cat(*(ui >= 1 for ui in u)).any(), "big")
        frac = u.quantize(cfg.frac, "truncate", "wrap")
        squares = stage(m, frac * frac, "squares")
        x2 = stage(m, squares.sum(), "sum").shift(2 * cfg.shift)
        self._shape.feed(m, delay(m, self.i.valid, 3, "valid"), {"x2": x2})
        big = delay(m, big, 1 + self._shape.latency, "big")
        return {"spec": FixedValue.const(0, cfg.t).where(big, self._shape.results()["spec"]),
                "valid": self._shape.o.valid}


def _rectify(d, rounding):
    """``|d|`` in the unsigned twin of ``d``'s format: negator, multiplexer, saturation
    of the one code (``-2^int_bits``) whose magnitude the format cannot hold."""
    neg = -d
    wide = d.quantize(neg.fmt, rounding, "error")
    return neg.where(d < 0, wide).quantize(Format(d.fmt.int_bits, d.fmt.frac_bits), rounding, "saturate")
