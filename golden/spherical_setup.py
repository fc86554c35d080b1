"""Scanline setup of the spherical interpolation unit, Szirmay-Kalos et al. (2000) §3.2, §4.

Float first, then quantized to the unit's formats (:mod:`phongfx.golden.spherical`):

* from the span's end vectors ``u1, u2`` (e.g. N) and ``v1, v2`` (e.g. H): ``u2'`` is
  ``u2`` rotated by the inverse of the rotation taking ``v1`` to ``v2`` (the quaternion
  ``q^-1·[0, u2]·q`` of §3.2), ``cos γ = u1·u2'``, ``cos θ1 = u1·v1``, ``cos θ2 = u2·v2``,
  and ``A cos φ = cos θ1``, ``A sin φ = (cos θ2 - cos θ1 cos γ)/sin γ`` (equations 15–17):
  ``cos θ(t) = A cos(tγ - φ)``;
* ``a(n)`` solves ``1/(n+1) = (2a²(1 - cos(π/2a)) - 1)/(4a² - 1)`` (§4, the ``sin x``
  weighted integrals of equation 20) by bisection: the right side falls from
  ``1`` (``a → 1/2``) to ``0``, so ``n > 0`` has one root above ``1/2``;
* ``θ(X) = aγ·t - aφ = s·X + b`` with ``t = X/(L-1)`` over a span of ``L`` pixels
  (``s = 0`` for ``L = 1``), and ``C = I_in·k_s·A^n`` (equation 18).

``γ`` near 0 or π leaves ``sin γ`` near 0: below :data:`TINY` the span is taken as
``φ = 0``, ``A = cos θ1`` (the vectors barely turn, or the rotation is undefined).
"""

import functools
import math

import numpy as np

from .fixed import Fixed

__all__ = ["solve_a", "span_setups", "span_setup", "quantize_setup", "TINY"]

#: ``sin γ`` below which a span is treated as not turning.
TINY = 1e-9


def _rhs(a):
    return (2 * a * a * (1 - np.cos(np.pi / (2 * a))) - 1) / (4 * a * a - 1)


@functools.lru_cache(maxsize=1024)  # one n per material: a frame asks for it once per span
def solve_a(n, iterations=200):
    """``a(n)`` of §4 (Table 1) by bisection; ``n > 0``, any float."""
    if not n > 0:
        raise ValueError(f"n must be positive, not {n!r}")
    target = 1.0 / (n + 1)
    lo, hi = 0.5 + 1e-12, 2.0
    while _rhs(hi) > target:  # the right side falls like π²/16a², so the bracket closes fast
        lo, hi = hi, 2 * hi
    for _ in range(iterations):
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if _rhs(mid) > target else (lo, mid)
    return (lo + hi) / 2


def _dot(a, b):
    return np.einsum("...i,...i->...", a, b)


def _rotate_back(u2, v1, v2):
    """``u2`` turned by the inverse of the shortest rotation from ``v1`` to ``v2``
    (Rodrigues), row by row; rows where ``v1 ∥ v2`` are left as they are."""
    axis = np.cross(v1, v2)
    sin, cos = np.linalg.norm(axis, axis=-1, keepdims=True), _dot(v1, v2)[..., None]
    k = -axis / np.where(sin < TINY, 1.0, sin)
    turned = u2 * cos + np.cross(k, u2) * sin + k * _dot(k, u2)[..., None] * (1 - cos)
    return np.where(sin < TINY, u2, turned)


def span_setups(u1, u2, v1, v2, n, length, intensity=1.0):
    """Float setup of many spans: rows ``(S, 3)`` of end vectors, ``length`` ``(S,)``;
    a dict of ``(S,)`` arrays ``gamma, A, phi, s, b, C, dark`` and the scalar ``a``.

    ``dark`` marks a span whose angle ``x = tγ - φ`` stays on one side of the lobe
    ``|a·x| <= π/2`` all along (``t`` in 0..1): ``cos²(a·x)`` is 0 over the whole span,
    so its ``C`` is loaded as 0.  The host must do this, not leave it to the ROM: the
    angle register wraps at ``±π``, and ``a·x`` reaches ``a·π`` (``a(20) = 2.76``), so
    such a span would read the lit cells again after one turn.
    """
    u1, u2, v1, v2 = (np.asarray(x, dtype=np.float64) for x in (u1, u2, v1, v2))
    length = np.asarray(length)
    cos_g = np.clip(_dot(u1, _rotate_back(u2, v1, v2)), -1, 1)
    gamma, sin_g = np.arccos(cos_g), np.sqrt(np.maximum(1 - cos_g * cos_g, 0.0))
    c1, c2 = _dot(u1, v1), _dot(u2, v2)
    turns = sin_g >= TINY
    a_sin = np.where(turns, (c2 - c1 * cos_g) / np.where(turns, sin_g, 1.0), 0.0)
    big_a, phi = np.hypot(c1, a_sin), np.arctan2(a_sin, c1)
    a = solve_a(n)
    s = np.where(length > 1, a * gamma / np.maximum(length - 1, 1), 0.0)
    lobe = math.pi / (2 * a)
    start, end = -phi, gamma - phi
    dark = ((start > lobe) & (end > lobe)) | ((start < -lobe) & (end < -lobe))
    return {"gamma": gamma, "A": big_a, "phi": phi, "a": a, "s": s, "b": -a * phi,
            "C": np.where(dark, 0.0, intensity * big_a ** n), "dark": dark}


def span_setup(u1, u2, v1, v2, n, length, intensity=1.0):
    """Float setup of one span (:func:`span_setups`): ``dict(gamma, A, phi, a, s, b, C,
    dark)``, angles in radians."""
    setup = span_setups(*(np.asarray(x, dtype=np.float64)[None] for x in (u1, u2, v1, v2)), n,
                        np.array([length]), intensity)
    return {name: value if name == "a" else value[0].item() for name, value in setup.items()}


def quantize_setup(config, setup):
    """Raw ``b``, ``s`` (units of π, wrapped like the register) and ``C`` (saturated)."""
    theta = config.fmt("theta")
    raw = {name: Fixed.from_float(setup[name] / math.pi, theta, "round_half_up", "wrap").raw
           for name in ("b", "s")}
    raw["c"] = Fixed.from_float(setup["C"], config.c, "round_half_up", "saturate").raw
    return raw
