"""Configuration of the difference vector and ``2x = n·D·D`` of Lyon's Figure 7c."""

from dataclasses import dataclass

from .base import BlockConfig, check_format, check_int, check_integer_format

__all__ = ["DifferenceConfig"]


@dataclass(frozen=True)
class DifferenceConfig(BlockConfig):
    """Figure 7c difference vector and ``2x = n·D·D``; ``n`` is an integer ``1..n_max``.

    ``n_const``: 0 (default) takes ``n`` per pixel on the ``n`` port, through a full
    ``n × D·D`` multiplier; ``1..n_max`` fixes ``n`` in the hardware, since a scene with
    a single shininess needs only a constant multiplier (or none): no ``n`` port, a
    multiplication by a constant in shifts and adds (a pure shift for a power of two; see
    :func:`phongfx.hdl.difference.const_product`), the same codes as feeding
    ``n = n_const`` on the port, in the same cycles.
    """

    vec: str = "S1.10"
    d: str = "S1.10"
    dd: str = "2.20"
    n: str = "13.0"
    n_max: int = 8000
    x2: str = "13.12"
    rounding: str = "round_half_up"
    pipeline: int = 0
    n_const: int = 0

    INPUTS = {"r": ("vec", 3), "l": ("vec", 3), "n": ("n", 1)}
    OUTPUTS = {"x2": ("x2", 1)}
    # D·D is held exactly: twice the fraction bits of D
    VECTOR_FIELDS = {"vec": (1, 0), "d": (1, 0), "dd": (2, 0)}

    def validate(self):
        check_format("vec", self.vec, signed=True)
        check_format("d", self.d, signed=True)
        check_format("dd", self.dd, signed=False)
        check_int("n_max", self.n_max, 1, check_integer_format("n", self.n).max_raw)
        check_int("n_const", self.n_const, 0, self.n_max)
        check_format("x2", self.x2, signed=False)

    @property
    def inputs(self):
        ports = super().inputs
        if self.n_const:
            del ports["n"]  # the constant is wired into the multiplier
        return ports
