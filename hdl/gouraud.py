"""Gouraud unit: one adder, ``p += dp`` (Gouraud 1971; Hast et al. §1)."""

from phongfx.config import GouraudConfig

from .euler import ForwardDifferenceUnit

__all__ = ["Gouraud"]


class Gouraud(ForwardDifferenceUnit):
    """One adder and two registers: output ``p``, then ``p += dp``: Hast, Barrera &
    Bengtsson's Euler recurrence without its second difference, so control, wrapping and
    ``level`` are those of :class:`phongfx.hdl.euler.ForwardDifferenceUnit`; see
    :func:`phongfx.golden.gouraud.gouraud`.

    Latency: 1 (the output register).

    Ports: ``i.payload`` = ``init`` (``1.0``), ``p0`` (``config.p``), ``dp`` (``config.dp``);
    ``o.payload`` = ``p`` (``config.p``), ``level`` (``config.out``).
    """

    config_class = GouraudConfig
    LOADS = (("p", "p0"), ("dp", "dp"))
