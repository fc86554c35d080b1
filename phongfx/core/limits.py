"""The limits of the width settings every layer shares, in the config's own vocabulary.

The configs validate their fields against these (:mod:`phongfx.config.base`,
:mod:`phongfx.config.shape`), and the search ranges of the method registry
(:mod:`phongfx.core.methods`) must lie inside them: one place, so that a sweep can never
ask for a point the config refuses, nor the two drift apart.
"""

from numbers import Integral

__all__ = ["MAX_VEC_FRAC", "K_MAX", "LIMITS", "check_range", "check_param"]

#: Widest vector width ``f`` of :meth:`~phongfx.config.BlockConfig.with_vec_frac`: at 24 the
#: halfway datapath's exact ``4n·D·D`` (``17.2f``) no longer fits the golden model's int64.
MAX_VEC_FRAC = 23

#: Largest ``k`` of Lyon's shape and root units (the cut-off ``x >= 2^k``).
K_MAX = 10

#: Setting -> inclusive ``(lo, hi)`` it may take anywhere.
LIMITS = {"vec_frac": (1, MAX_VEC_FRAC), "k": (0, K_MAX)}


def check_range(owner, name, lo, hi):
    """Raise ValueError when the search range ``lo..hi`` of setting ``name`` leaves its limit."""
    if name in LIMITS:
        top_lo, top_hi = LIMITS[name]
        if not top_lo <= lo <= hi <= top_hi:
            raise ValueError(f"{owner} range of {name} must lie in {top_lo}..{top_hi}, not {lo}..{hi}")


def check_param(name, value, lo, hi):
    """``value`` as an ``int`` if it is an integer in ``lo..hi`` (numpy's too; a bool is not),
    else ValueError: a search parameter, which a sweep file or a numpy grid may give."""
    if isinstance(value, bool) or not isinstance(value, Integral) or not lo <= value <= hi:
        raise ValueError(f"{name} must be an integer in {lo}..{hi}, not {value!r}")
    return int(value)
