"""Configuration of the reflection unit of Lyon's Figure 7b."""

from dataclasses import dataclass

from .base import BlockConfig, check_format

__all__ = ["ReflectConfig"]


@dataclass(frozen=True)
class ReflectConfig(BlockConfig):
    """Figure 7b reflection ``R = 2(N·V)N - V``."""

    vec: str = "S1.10"
    dot: str = "S1.12"
    out: str = "S1.10"
    rounding: str = "round_half_up"
    pipeline: int = 0

    INPUTS = {"n": ("vec", 3), "v": ("vec", 3)}
    OUTPUTS = {"r": ("out", 3)}
    # N·V carries two guard bits: 2(N·V) scales every lane of N
    VECTOR_FIELDS = {"vec": (1, 0), "dot": (1, 2), "out": (1, 0)}

    def validate(self):
        check_format("vec", self.vec, signed=True)
        check_format("dot", self.dot, signed=True, holds_one=True)
        check_format("out", self.out, signed=True)
