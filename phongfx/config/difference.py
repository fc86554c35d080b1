"""Configuration of the difference vector and ``2x = n·D·D`` of Lyon's Figure 7c."""

from dataclasses import dataclass

from .base import BlockConfig, ConstantShininess, check_format

__all__ = ["DifferenceConfig"]


@dataclass(frozen=True)
class DifferenceConfig(ConstantShininess, BlockConfig):
    """Figure 7c difference vector and ``2x = n·D·D``; ``n`` is an integer ``1..n_max``.

    ``n_const``: 0 (default) takes ``n`` per pixel on the ``n`` port, through a full
    ``n × D·D`` multiplier; ``1..n_max`` fixes ``n`` in the hardware, since a scene with
    a single shininess needs only a constant multiplier (or none): no ``n`` port, a
    multiplication by a constant in shifts and adds (a pure shift for a power of two; see
    :func:`phongfx.hdl.constant.const_product`), the same codes as feeding
    ``n = n_const`` on the port, in the same cycles (:class:`~.base.ConstantShininess`,
    shared with Figure 8's ``m_const``).
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

    SHININESS = "n"
    INPUTS = {"r": ("vec", 3), "l": ("vec", 3), "n": ("n", 1)}
    OUTPUTS = {"x2": ("x2", 1)}
    # D·D is held exactly: twice the fraction bits of D
    VECTOR_FIELDS = {"vec": (1, 0), "d": (1, 0), "dd": (2, 0)}

    def validate(self):
        check_format("vec", self.vec, signed=True)
        check_format("d", self.d, signed=True)
        check_format("dd", self.dd, signed=False)
        self.check_shininess()
        check_format("x2", self.x2, signed=False)
