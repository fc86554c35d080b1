"""Shared pieces of the Lyon claims (:mod:`phongfx.papers.lyon.tables`): Lyon's float formulas
(shape ``f_k``, normalizer ``g_k``, ``x`` against the angle α) and the golden
difference and shape blocks at their default formats, fed from float vectors.
"""

import numpy as np

from phongfx.core.registry import get_block
from phongfx.golden.fixed import Fixed

__all__ = ["SEED", "K", "LEVELS", "f_k", "x_of_alpha", "alpha_of_x", "g_k", "rotation", "rot_y",
           "codes", "fixed_x2", "fixed_shape"]

#: Seed of every random choice (directions, the generic orientation of test geometry).
SEED = 43

K = (0, 1, 2)
LEVELS = 255.0  # 8-bit levels of the specular amount


def f_k(x, k):
    """Lyon's ``f_k(x) = (1 - x/2^k)^(2^k)``, 0 for ``x >= 2^k``."""
    t = np.clip(1.0 - np.asarray(x, dtype=np.float64) / 2.0 ** k, 0.0, None)
    return t ** (2 ** k)


def x_of_alpha(alpha, n):
    """``x = (n/2)|D|²`` with ``|D| = 2 sin(α/2)`` (unit R and L at angle α)."""
    return n / 2.0 * (2.0 * np.sin(np.asarray(alpha) / 2.0)) ** 2


def alpha_of_x(x, n):
    """Inverse of :func:`_x_of_alpha`; NaN where ``|D|`` would pass 2 (never reached)."""
    d = np.sqrt(2.0 * np.asarray(x, dtype=np.float64) / n)
    with np.errstate(invalid="ignore"):
        return np.where(d <= 2.0, 2.0 * np.arcsin(np.minimum(d, 2.0) / 2.0), np.nan)


def g_k(z, order):
    y = 1.0 - z
    return 1.0 + y / 2.0 if order == 1 else 1.0 + (y + y * y) / 2.0


def rotation(seed=SEED):
    """A fixed generic rotation, so that test vectors are not axis-aligned codes."""
    q, r = np.linalg.qr(np.random.default_rng(seed).normal(size=(3, 3)))
    q = q * np.sign(np.diag(r))
    return q if np.linalg.det(q) > 0 else -q


def rot_y(angle):
    """Unit vectors at ``angle`` (radians, array) from +Z towards +X: rows (…, 3)."""
    angle = np.asarray(angle, dtype=np.float64)
    return np.stack([np.sin(angle), np.zeros_like(angle), np.cos(angle)], axis=-1)


def codes(values, fmt):
    """Float values to raw codes, rounded half up and saturated (stimulus, as ``make sim``)."""
    return Fixed.from_float(values, fmt, rounding="round_half_up", overflow="saturate").raw


def fixed_x2(r, l, n):
    """Raw ``2x`` codes of the golden difference block (default formats) for float R, L."""
    block = get_block("difference")
    vec = block.config.fmt("vec")
    count = len(r)
    return block.golden({"r": codes(r, vec), "l": codes(np.broadcast_to(l, (count, 3)), vec),
                         "n": np.full(count, n, dtype=np.int64)})["x2"]


def fixed_shape(x2, k):
    """Specular amount (float value of the code) of the golden shape block ``f_k``."""
    block = get_block("shape", k=k)
    return block.golden({"x2": x2})["spec"] * block.config.fmt("t").lsb
