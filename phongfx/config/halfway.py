"""Configuration of the halfway-vector difference unit (Lyon's Figure 5)."""

from dataclasses import dataclass

from phongfx.core.format import Format

from .base import BlockConfig, SpecularUnit, check_format
from .normalize import NormalizeConfig
from .shape import Figure7Unit

__all__ = ["HalfwayConfig", "HALFWAY_VARIANTS", "HalfwayUnit", "HALFWAY"]

#: The difference vectors of Lyon's Figure 9 rows 7–10 (:class:`HalfwayConfig`).
HALFWAY_VARIANTS = ("d1", "d2", "d3", "g2proj", "g2")


@dataclass(frozen=True)
class HalfwayConfig(BlockConfig):
    """Halfway-vector difference (Lyon Figure 5, Figure 9 rows 7–10): ``D = p - q`` with

    * ``d1``: ``p = (2V·N)N``, ``q = H``;  ``d2``: ``p = (2L·N)N``, ``q = H`` (``|D2| = |D1|``);
    * ``d3``: ``p = (H·N)N``, ``q = H`` (no normalization of H);
    * ``g2proj``: ``p = (H*·N)N``, ``q = H*``;  ``g2``: ``p = N``, ``q = H*``;
      with ``H* = g2(H·H)·H`` from the :class:`NormalizeConfig` ``normalize``.

    ``h`` is ``"sum"`` (``H = V + L``, the text) or ``"mean"`` (``H = (L + V)/2``, the
    code; default).  ``"mean"`` halves every term, so d1/d2 project ``V`` and ``L``
    rather than ``2V`` and ``2L``: ``D1 = (R - L)/2``, and ``x = (4n/2)·D·D`` is the
    appendix's, as its ``n4`` scales it.

    Formats (our reconstruction; see :mod:`phongfx.golden.halfway`): ``hvec`` holds
    ``V + L`` (``S2.10``) and ``(V + L)/2`` (``S1.11``) exactly, so ``h`` changes without
    touching a format; ``dot`` has two integer bits for ``H·N = 2`` (``"sum"``, ``V = L = N``)
    and two guard bits; ``out`` holds ``|D|`` up to 2; ``normalize.vec`` must be ``hvec``.
    ``pipeline`` raises ``normalize.pipeline`` to at least its own depth.
    """

    vec: str = "S1.10"
    variant: str = "g2proj"
    h: str = "mean"
    hvec: str = "S2.11"
    dot: str = "S2.12"
    out: str = "S2.10"
    normalize: NormalizeConfig = NormalizeConfig(vec="S2.11", out="S2.11")
    rounding: str = "round_half_up"
    pipeline: int = 0

    INPUTS = {"n": ("vec", 3), "l": ("vec", 3), "v": ("vec", 3)}
    OUTPUTS = {"p": ("out", 3), "q": ("out", 3)}
    PIPELINED = ("normalize",)
    # hvec has one bit more than the vectors, to hold (V + L)/2 exactly
    VECTOR_FIELDS = {"vec": (1, 0), "hvec": (1, 1), "dot": (1, 2), "out": (1, 0)}

    def validate(self):
        if self.variant not in HALFWAY_VARIANTS:
            raise ValueError(f"variant must be one of {', '.join(HALFWAY_VARIANTS)}, not {self.variant!r}")
        if self.h not in ("sum", "mean"):
            raise ValueError(f"h must be one of sum, mean, not {self.h!r}")
        check_format("vec", self.vec, signed=True)
        hvec = check_format("hvec", self.hvec, signed=True)
        check_format("dot", self.dot, signed=True, holds_one=True)
        check_format("out", self.out, signed=True)
        if not isinstance(self.normalize, NormalizeConfig):
            raise TypeError(f"normalize must be a NormalizeConfig, not {self.normalize!r}")
        if self.normalize.fmt("vec") != hvec:
            raise ValueError(f"normalize.vec ({self.normalize.vec}) must equal hvec ({self.hvec}): "
                             f"the normalizer takes H")

    def vec_frac_changes(self, frac):
        """Also the normalizer of H: its guard bits follow the vectors, its ports ``hvec``."""
        changes = super().vec_frac_changes(frac)
        hvec = changes["hvec"]
        changes["normalize"] = self.normalize.replace(
            **{**self.normalize.vec_frac_changes(frac), "vec": hvec, "out": hvec})
        return changes


class HalfwayUnit(SpecularUnit):
    """Figure 5: halfway difference vector → difference/x with ``n·2^halfway_shift`` → shape
    (Figure 9 rows 7–10, as the appendix code scales ``n``)."""

    parts = ("halfway", "difference", "shape")
    bisector = True

    def links(self, c):
        return [(*self.vec(c), "halfway.vec", c.halfway.vec),
                ("halfway.out", c.halfway.out, "difference.vec", c.difference.vec),
                ("difference.x2", c.difference.x2, "shape.x2", c.shape.x2)]

    def check(self, c):
        if c.difference.fmt("n").int_bits < c.halfway_shift + 1:
            raise ValueError(f"difference.n must have at least {c.halfway_shift + 1} integer "
                             f"bits to take n·2^{c.halfway_shift}, not {c.difference.n}")
        if c.difference.n_const % (1 << c.halfway_shift):
            raise ValueError(f"difference.n_const must be a multiple of {1 << c.halfway_shift} "
                             f"(it is n·2^{c.halfway_shift}), not {c.difference.n_const}")

    def shininess(self, c):
        n, shift = c.difference.fmt("n"), c.halfway_shift
        return "n", Format(n.int_bits - shift, 0), c.difference.n_max >> shift

    def shininess_const(self, c):
        return c.difference.n_const >> c.halfway_shift

    def shininess_note(self, c):
        return " (the unit scales it by 2^halfway_shift itself)"

    def fit(self, config, n_hi, n_const):
        shift = config.halfway_shift
        return super().fit(config, n_hi << shift, n_const << shift)

    sweep = Figure7Unit.sweep  # the same difference → shape widths


#: The ``unit`` face of the ``halfway`` method.
HALFWAY = HalfwayUnit()
