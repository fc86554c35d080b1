"""Gouraud unit: one adder, ``p += dp`` (Gouraud 1971; Hast et al. §1)."""

from phongfx.config import GouraudConfig

from .block import PipelinedBlock
from .euler import forward_differences
from .fixed import stage

__all__ = ["Gouraud"]


class Gouraud(PipelinedBlock):
    """One adder and two registers: output ``p``, then ``p += dp``.

    Control as :class:`phongfx.hdl.euler.Euler`: registers change only on valid
    pixels, ``init`` multiplexes the loads in, the sum wraps in ``p``'s width, and
    ``level`` is the output register truncated and saturated to ``config.out``;
    see :func:`phongfx.golden.gouraud.gouraud`.

    Latency: 1 (the output register).

    Ports: ``i.payload`` = ``init`` (``1.0``), ``p0`` (``config.p``), ``dp`` (``config.dp``);
    ``o.payload`` = ``p`` (``config.p``), ``level`` (``config.out``).
    """

    config_class = GouraudConfig
    cycle_tags = False  # hand-aligned registers, no pipeline depth

    @property
    def latency(self):
        return 1

    def datapath(self, m, i):
        cfg = self.config
        p = forward_differences(m, self.i.valid, i["init"].value[0], [
            ("p", i["p0"], cfg.fmt("p")), ("dp", i["dp"], cfg.fmt("dp"))])
        out = stage(m, p, "p_out")
        return {"p": out, "level": out.quantize(cfg.out, "truncate", "saturate")}
