"""Configuration of the approximate normalizer of Lyon's Figure 7a."""

from dataclasses import dataclass

from .base import BlockConfig, check_format, check_int

__all__ = ["NormalizeConfig"]


@dataclass(frozen=True)
class NormalizeConfig(BlockConfig):
    """Figure 7a approximate normalizer ``N = g(N'·N')·N'`` with ``g1`` or ``g2``."""

    vec: str = "S1.10"
    order: int = 2
    z: str = "1.12"
    y2: str = "1.12"
    g: str = "1.12"
    out: str = "S1.10"
    rounding: str = "round_half_up"
    pipeline: int = 0

    INPUTS = {"n": ("vec", 3)}
    OUTPUTS = {"n": ("out", 3)}
    # z, y² and g carry two guard bits over the vector: g multiplies every lane
    VECTOR_FIELDS = {"vec": (1, 0), "z": (1, 2), "y2": (1, 2), "g": (1, 2), "out": (1, 0)}

    def validate(self):
        check_format("vec", self.vec, signed=True)
        check_int("order", self.order, 1, 2)
        check_format("z", self.z, signed=False, holds_one=True)
        check_format("y2", self.y2, signed=False, holds_one=True)
        check_format("g", self.g, signed=False, holds_one=True)
        check_format("out", self.out, signed=True)

    @property
    def y2_overflow(self):
        """Overflow policy of the ``y²`` quantize: ``"error"`` where it provably cannot overflow.

        ``z`` saturates below 2 when it has one integer bit, so ``y > -1`` and
        ``y² <= 1``, which ``y2`` holds by validation.  A wider ``z`` lets junk
        reach ``y = 1 - 2**int_bits`` and ``y²`` well past 1: saturate there.
        """
        return "error" if self.fmt("z").int_bits == 1 else "saturate"
