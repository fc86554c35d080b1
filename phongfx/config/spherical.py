"""Configuration of the spherical interpolation unit of Szirmay-Kalos et al. (2000)."""

from dataclasses import dataclass

from phongfx.core.format import Format

from .base import BlockConfig, check_format, check_fraction_format, check_int

__all__ = ["SphericalConfig"]


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

    INPUTS = {"init": (Format(1, 0), 1), "b": ("theta", 1), "s": ("theta", 1), "c": ("c", 1),
              "bd": ("theta", 1), "sd": ("theta", 1), "cd": ("c", 3)}
    OUTPUTS = {"spec": ("out", 1), "diff": ("out", 3)}
    SHADES = {"diff": "diff", "spec": "spec"}
    #: ``(diffuse port, lane, specular port)`` of the light it computes, as a shader's blend
    #: takes it: the ``diff`` vector's first lane (:func:`phongfx.config.shader.unit_terms`)
    TERMS = ("diff", 0, "spec")
    #: The inputs that depend on the light (its angles and constants); ``init``, the
    #: scanline's start, enters a shader once (:attr:`phongfx.config.ShaderConfig.shared`)
    PER_LIGHT = ("b", "s", "c", "bd", "sd", "cd")

    def validate(self):
        theta = check_format("theta", self.theta, signed=True)
        if theta.int_bits:
            raise ValueError(f"theta must be a fraction-only format (S0.m, units of π), not {theta}")
        check_int("addr_bits", self.addr_bits, 2, min(theta.width, 16))
        check_fraction_format("rom", self.rom)
        check_format("c", self.c, signed=False)
        check_format("out", self.out, signed=False)

    @property
    def out_overflow(self):
        """``"error"`` where ``out`` holds every code of ``c``: a ROM word is below 1, so
        ``C·w < C``, and rounding to a grid that holds ``C`` cannot pass it; else saturate."""
        c, out = self.fmt("c"), self.fmt("out")
        return "error" if out.int_bits >= c.int_bits and out.frac_bits >= c.frac_bits else "saturate"
