"""Spherical interpolation unit, Szirmay-Kalos et al. (2000) Figure 12."""

from amaranth.hdl import Signal
from amaranth.lib.memory import Memory

from phongfx.config import SphericalConfig
from phongfx.golden.spherical import rom_contents

from .block import PipelinedBlock
from .fixed import FixedValue, FixedVector, stage

__all__ = ["Spherical"]


class Spherical(PipelinedBlock):
    """Two linear interpolators (specular ``θ``, diffuse ``θ_d``), a ``cos²`` and a ``cos``
    ROM, and four multipliers (``C``; ``C_r``, ``C_g``, ``C_b``), as Figure 12.

    The interpolator registers, their slopes and the constants are state: they change
    only on a valid pixel (``init``: load, else ``θ += s``), so idle cycles leave the
    scanline where it was.  The ROM words come from
    :func:`phongfx.golden.spherical.rom_contents`, the golden model's own function.
    Formats, the angle mapping and the ROM error bound are as in
    :func:`phongfx.golden.spherical.spherical`.

    Latency: 3 (the interpolator register, as in the paper's two-stage pipeline; the ROM
    word; the rounded product).

    Ports: ``i.payload`` = ``init`` (``1.0``), ``b``, ``s``, ``bd``, ``sd`` (``config.theta``),
    ``c`` (``config.c``), ``cd`` (3 × ``config.c``); ``o.payload`` = ``spec``, ``diff``
    (3 lanes), ``config.out``.
    """

    config_class = SphericalConfig
    cycle_tags = False  # hand-aligned registers, no pipeline depth

    @property
    def latency(self):
        return 3

    def _channel(self, m, name, init, start, slope, constants, function):
        cfg = self.config
        theta_fmt, valid = cfg.fmt("theta"), self.i.valid
        theta = Signal(theta_fmt.shape(), name=f"{name}_theta")
        step = Signal(theta_fmt.shape(), name=f"{name}_s")
        held = [Signal(cfg.fmt("c").shape(), name=f"{name}_c{index}") for index in range(len(constants))]
        with m.If(valid & init):
            m.d.sync += [theta.eq(start.value), step.eq(slope.value)]
            m.d.sync += [reg.eq(value.value) for reg, value in zip(held, constants)]
        with m.Elif(valid):
            # the adder keeps the register's width: it wraps modulo 2π, like the paper's
            m.d.sync += theta.eq(theta + step)
        rom = cfg.fmt("rom")
        memory = Memory(shape=rom.shape(), depth=1 << cfg.addr_bits,
                        init=[int(v) for v in rom_contents(cfg.addr_bits, rom, function)])
        m.submodules[f"{name}_rom"] = memory
        port = memory.read_port(domain="comb")
        m.d.comb += port.addr.eq(theta[theta_fmt.width - cfg.addr_bits:])
        word = stage(m, FixedValue(port.data, rom), f"{name}_word")
        products = []
        for index, reg in enumerate(held):
            c = stage(m, FixedValue(reg, cfg.c), f"{name}_c{index}_d")
            product = (c * word).tagged(self.latency - 1, m)  # the stage before the output
            products.append(stage(m, product.quantize(cfg.out, cfg.rounding, cfg.out_overflow),
                                  f"{name}_out{index}"))
        return products

    def datapath(self, m, i):
        init = i["init"].value[0]
        spec = self._channel(m, "spec", init, i["b"], i["s"], [i["c"]], "cos2")
        diff = self._channel(m, "diff", init, i["bd"], i["sd"], list(i["cd"]), "cos")
        return {"spec": spec[0], "diff": FixedVector(diff)}
