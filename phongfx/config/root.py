"""Configuration of the root-shininess specular unit of Lyon's Figure 8."""

from dataclasses import dataclass

from .base import (BlockConfig, ConstantShininess, SpecularUnit, check_format, check_fraction_format, check_int,
                   floor_sqrt)
from .shape import K_MAX, ShapeConfig

__all__ = ["RootConfig", "Figure8Unit", "FIG8"]


@dataclass(frozen=True)
class RootConfig(ConstantShininess, BlockConfig):
    """Figure 8 root-shininess specular unit: ``|D|·m``, fraction-only dot product,
    augmented comparator, shape ``f_k`` (``k = 1`` by default); ``m = √n`` in ``1..m_max``.

    ``frac`` is the fraction of each ``u_i = m|D_i|/2^s`` that the dot product sees;
    :attr:`shift` is ``s`` and :attr:`shape` the Figure 7d config fed with ``2x``
    (see :mod:`phongfx.golden.root`).  ``m_const``: 0 (default) takes ``m`` per pixel on
    the ``m`` port; ``1..m_max`` fixes it in the hardware (no ``m`` port; the three
    ``m × |D_i|`` become constant multiplications), with the codes and latency of
    feeding ``m = m_const``, as :attr:`DifferenceConfig.n_const` does for ``n``
    (:class:`~.base.ConstantShininess`, shared by both).
    """

    vec: str = "S1.10"
    d: str = "S1.10"
    m: str = "6.0"
    m_max: int = 63
    frac: str = "0.9"
    k: int = 1
    t: str = "1.15"
    rounding: str = "round_half_up"
    pipeline: int = 0
    m_const: int = 0

    SHININESS = "m"
    INPUTS = {"r": ("vec", 3), "l": ("vec", 3), "m": ("m", 1)}
    OUTPUTS = {"spec": ("t", 1)}
    VECTOR_FIELDS = {"vec": (1, 0), "d": (1, 0)}

    def validate(self):
        check_format("vec", self.vec, signed=True)
        check_format("d", self.d, signed=True)
        self.check_shininess()
        check_fraction_format("frac", self.frac)
        check_int("k", self.k, 0, K_MAX)
        check_format("t", self.t, signed=False, holds_one=True)

    @property
    def shift(self):
        """``s = ceil((k+1)/2)``: ``u_i = m|D_i|/2^s`` and ``x/2^k = 2^(2s-1-k)·Σu_i²``.

        The smallest ``s`` with ``2s >= k+1``, so that ``c = 2^(2s-1-k)`` is 1 or 2, never
        below 1 (an integer part of any ``u_i`` then proves ``x/2^k >= 1``), while ``u_i``
        keeps the most significant bits of ``m|D_i|`` in its fraction.
        """
        return (self.k + 2) // 2

    @property
    def shape(self):
        """The Figure 7d :class:`ShapeConfig` behind the dot product: its ``x2`` is the
        exact format of ``Σ frac_i²`` with the point moved ``2s`` places (``2x = 2^(2s)·Σu_i²``)."""
        frac = self.fmt("frac")
        square = frac.mul(frac)
        x2 = square.add(square).add(square).shift(2 * self.shift)
        return ShapeConfig(x2=str(x2), k=self.k, t=self.t, rounding=self.rounding,
                           pipeline=self.pipeline)


class Figure8Unit(SpecularUnit):
    """Figure 8: reflect → root-shininess unit (``m = √n``)."""

    parts = ("reflect", "root")

    def links(self, c):
        return [(*self.vec(c), "reflect.vec", c.reflect.vec),
                ("reflect.out", c.reflect.out, "root.vec", c.root.vec),
                (*self.vec(c), "root.vec", c.root.vec)]

    def shininess_block(self, c):
        return c.root

    def top_n(self, shininess):
        return shininess * shininess

    def applied_n(self, c, n):
        """``m²``: the port takes ``m = √n`` rounded (or the constant ``m``)."""
        m = c.shininess_const or (n ** 0.5).round().clip(1, c.root.m_max)
        return (n * 0 + m * m).astype("float64")

    def spec_format(self, c):
        return c.root.fmt("t")

    def fit(self, config, n_hi, n_const):
        m = floor_sqrt(n_hi - 1) + 1  # ⌈√n_hi⌉
        low = floor_sqrt(n_const)  # √n_const rounded (never a tie for an integer), 0 for a port
        m_const = min(max(low + (n_const - low * low > low), 1), m) if n_const else 0
        return config.replace(root=config.root.with_shininess(m, m_const))

    def sweep(self, c, p):
        """``root_frac``, ``t_frac``: the fraction bits of ``root.frac`` and ``root.t``; ``k``."""
        root = c.root
        return c.replace(root=root.replace(**root.frac_changes(frac=p["root_frac"], t=p["t_frac"]), k=p["k"]))


#: The ``unit`` face of the ``fig8`` method.
FIG8 = Figure8Unit()
