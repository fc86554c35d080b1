"""Configuration of the halfway-vector difference unit (Lyon's Figure 5)."""

from dataclasses import dataclass

from .base import BlockConfig, check_format
from .normalize import NormalizeConfig

__all__ = ["HalfwayConfig", "HALFWAY_VARIANTS"]

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
