"""Configuration of the shape function of Lyon's Figure 7d."""

from dataclasses import dataclass

from phongfx.core.limits import K_MAX

from .base import BlockConfig, SpecularUnit, check_format, check_int

__all__ = ["K_MAX", "ShapeConfig", "Figure7Unit", "FIG7"]

# K_MAX, the largest k of f_k (phongfx.core.limits): 2^k = n makes f_k(n·D²/2) Phong's
# (R·L)^n, so k = 10 reaches n = 1024; each k adds one squarer to the chain (and its
# latency), and the default x2 (13 integer bits) holds x/2^k up to k = 11.


@dataclass(frozen=True)
class ShapeConfig(BlockConfig):
    """Figure 7d shape function ``f_k(x) = (1 - x/2^k)^(2^k)``, zero for ``x/2^k >= 1``."""

    x2: str = "13.12"
    k: int = 2
    t: str = "1.15"
    rounding: str = "round_half_up"
    pipeline: int = 0

    INPUTS = {"x2": ("x2", 1)}
    OUTPUTS = {"spec": ("t", 1)}

    def validate(self):
        x2 = check_format("x2", self.x2, signed=False)
        check_int("k", self.k, 0, K_MAX)
        if x2.int_bits < self.k + 2:
            raise ValueError(f"x2 must have at least k+2 = {self.k + 2} integer bits so that "
                             f"x/2^k reaches 1, not {x2}")
        check_format("t", self.t, signed=False, holds_one=True)


class Figure7Unit(SpecularUnit):
    """Figure 7b–d: reflect → difference/x (``n``) → shape."""

    parts = ("reflect", "difference", "shape")

    def links(self, c):
        return [(*self.vec(c), "reflect.vec", c.reflect.vec),
                ("reflect.out", c.reflect.out, "difference.vec", c.difference.vec),
                (*self.vec(c), "difference.vec", c.difference.vec),
                ("difference.x2", c.difference.x2, "shape.x2", c.shape.x2)]

    def sweep(self, c, p):
        """``x2_frac``: the fraction bits of ``difference.x2`` = ``shape.x2``; ``shape_t_frac``
        those of ``shape.t``; ``k``."""
        difference, shape = c.difference, c.shape
        return c.replace(difference=difference.replace(**difference.frac_changes(x2=p["x2_frac"])),
                         shape=shape.replace(**shape.frac_changes(x2=p["x2_frac"], t=p["shape_t_frac"]),
                                             k=p["k"]))


#: The ``unit`` face of the ``fig7`` method.
FIG7 = Figure7Unit()
