"""Configuration of the diffuse term of Lyon's datapaths."""

from dataclasses import dataclass

from .base import BlockConfig, check_format

__all__ = ["DiffuseConfig"]


@dataclass(frozen=True)
class DiffuseConfig(BlockConfig):
    """Diffuse ``max(N·L, 0)`` (the backside test zeroes it)."""

    vec: str = "S1.10"
    out: str = "1.10"
    rounding: str = "round_half_up"
    pipeline: int = 0

    INPUTS = {"n": ("vec", 3), "l": ("vec", 3)}
    OUTPUTS = {"diff": ("out", 1)}
    VECTOR_FIELDS = {"vec": (1, 0)}

    def validate(self):
        check_format("vec", self.vec, signed=True)
        check_format("out", self.out, signed=False, holds_one=True)
