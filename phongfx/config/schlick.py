"""Configuration of Schlick's (1994) rational specular unit."""

from dataclasses import dataclass

from phongfx.core.format import Format

from .base import BlockConfig, check_format, check_int, check_integer_format

__all__ = ["SchlickConfig"]


@dataclass(frozen=True)
class SchlickConfig(BlockConfig):
    """Schlick (1994) rational specular unit ``S_n(t) = t / (n - n·t + t)``, ``t = cos α``
    in ``0..1``, ``n`` an integer ``1..n_max``; a pipelined restoring divider.

    ``rounding`` is ``truncate`` (the divider's floor) or ``round_half_up`` (one more
    quotient bit, then ``(q + 1) >> 1``).  Defaults: ``t`` and ``out`` ``1.15`` (1.0
    exact, as the shape function's), ``n`` ``13.0`` up to 8000 (Lyon's range).
    """

    t: str = "1.15"
    n: str = "13.0"
    n_max: int = 8000
    out: str = "1.15"
    rounding: str = "truncate"

    INPUTS = {"t": ("t", 1), "n": ("n", 1)}
    OUTPUTS = {"spec": ("out", 1)}
    SHADES = {"spec": "spec"}  # Schlick's rational term is the specular alone
    #: ``(diffuse port, lane, specular port)`` of the light it computes, as a shader's blend
    #: takes it: no diffuse output (:func:`phongfx.config.shader.unit_terms`)
    TERMS = (None, None, "spec")
    #: The inputs that depend on the light: the cosine; ``n`` enters a shader once
    #: (:attr:`phongfx.config.ShaderConfig.shared`)
    PER_LIGHT = ("t",)

    def validate(self):
        if self.rounding not in ("truncate", "round_half_up"):
            raise ValueError(f"rounding must be one of truncate, round_half_up (the divider "
                             f"floors), not {self.rounding!r}")
        t = check_format("t", self.t, signed=False, holds_one=True)
        check_int("n_max", self.n_max, 1, check_integer_format("n", self.n).max_raw)
        check_format("out", self.out, signed=False, holds_one=True)
        # the golden model forms t << (quotient bits - 1) in int64
        if t.width + self.quotient_bits - 1 > 62:
            raise ValueError(f"t ({t}) shifted by {self.quotient_bits - 1} quotient bits "
                             f"exceeds 62 bits")

    @property
    def quotient_bits(self):
        """Quotient bits the divider produces: weights ``2^0 .. 2^-F`` (``F`` fraction bits
        of ``out``), one more for ``round_half_up``."""
        return self.fmt("out").frac_bits + 1 + (self.rounding == "round_half_up")

    @property
    def den(self):
        """Format of the divisor ``n(1 - t) + t``: exact, from ``1.0`` (``t = 1`` or
        ``n = 1``) to ``n_max`` (``t = 0``)."""
        t = self.fmt("t")
        return Format.covering(0, self.n_max * t.one, t.frac_bits)
