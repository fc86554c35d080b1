"""Configuration of the linear interpolator of Lyon's Figure 7a."""

from dataclasses import dataclass

from .base import BlockConfig, check_format

__all__ = ["LirpConfig"]


@dataclass(frozen=True)
class LirpConfig(BlockConfig):
    """Figure 7a linear interpolator ``N' = (1-a)·N0 + a·N1``."""

    vec: str = "S1.10"
    a: str = "1.10"
    out: str = "S1.10"
    rounding: str = "round_half_up"
    pipeline: int = 0

    INPUTS = {"n0": ("vec", 3), "n1": ("vec", 3), "a": ("a", 1)}
    OUTPUTS = {"n": ("out", 3)}
    # a has the vector's fraction bits: it steps across the span at the vector's precision
    VECTOR_FIELDS = {"vec": (1, 0), "a": (1, 0), "out": (1, 0)}

    def validate(self):
        check_format("vec", self.vec, signed=True)
        check_format("a", self.a, signed=False, holds_one=True)
        check_format("out", self.out, signed=True)
