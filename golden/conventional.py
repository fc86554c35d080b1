"""Golden model of the conventional Phong unit: normalize, reflect, ``(R·V)^n``.

Phong (1975), as Lyon (1993, "Background") restates it: the specular term is
``(R·L)^n``, or equally ``(R_L·V)^n`` with ``R_L`` the light reflected off the surface; a
direct design normalizes ``N`` (and a local ``L`` or ``V``), forms the cosine and raises it
to ``n`` with "typically 16 bits of precision".  This is that design, on the arithmetic of
the Blinn–Phong baseline (:mod:`phongfx.golden.blinn`, whose functions it calls; bit growth
and error bounds of each step are stated there).  At the defaults of
:class:`~phongfx.config.ConventionalConfig` (``F = 15`` fraction bits of ``vec``):

* **local vectors** (``local_light`` / ``local_viewer``): ``X·X`` exact in ``q``
  [``4.30``], :func:`~phongfx.golden.blinn.even_shift`,
  :func:`~phongfx.golden.blinn.reciprocal_sqrt` and the scaling of
  :func:`~phongfx.golden.blinn.cosine` applied to each component: ``X̂ = X·2^(j-h)·y1``
  rounded to ``vec`` (saturated, clamped to 1); ``X = 0`` gives ``X̂ = 0``.  Otherwise the
  input is used as it is (taken as unit);
* **normal**: ``q = N·N``, the same even shift and ``y1 ~ 1/sqrt(m)``;
* **cosines**: ``N·L``, ``N·V`` exact in ``S5.30``, scaled by ``2^(j-h)`` and ``y1`` to
  ``cos`` [``S1.17``] (signed, clamped to 1): ``c_L = N̂·L``, ``c_V = N̂·V``, each within
  about ``2^-15.3`` (Blinn's bound with ``cos``'s half LSB of ``2^-18``);
* **reflection**: ``R·V = 2·c_L·c_V - L·V``, with ``c_L·c_V`` exact in ``S3.34``, the
  doubling a shift (``S4.33``) and ``L·V`` exact in ``S5.30``: the difference is exact in
  ``S6.33`` and rounded once, to ``t`` [``1.15``] (saturated: a negative ``R·V`` gives 0),
  then clamped to 1.  This is Phong's ``R·V`` with ``R = 2(N̂·L)N̂ - L`` by exact algebra, not an
  approximation: ``R·V = 2(N̂·L)(N̂·V) - L·V`` for any ``N̂``, ``L``, ``V``.  It is chosen
  over an explicit ``R`` because it needs no vector ``N̂`` (three multipliers), no ``R``
  (three more) and no last dot product ``R·V`` (three): ``L·V`` is computed beside ``N·N``
  at the first stage and only one ``c_L × c_V`` multiplier follows the cosines, so the
  reflection costs one stage after the cosines instead of three.  Error: ``2(|c_V| +
  |c_L|)`` times a cosine's, plus ``t``'s half LSB, about ``2^-13.1`` in all;
* **power**: ``t^n`` by Blinn's :func:`~phongfx.golden.blinn.power` (log2 and exp2 tables,
  linear interpolation, ``x = n·log2 t`` exact).  ``n`` is a port taking any integer
  ``1..n_max``, not a power of two, so repeated squaring does not serve;
  ``2^(n·log2 t)`` costs one multiplier for any ``n``.  ``t = 0`` gives 0;
* **backside**: ``specular`` is 0 wherever ``N·L <= 0`` (exact: ``N̂`` is a positive multiple
  of ``N``; with a local light it is ``N·L̂``), the light behind the surface, even where
  ``R·V > 0`` (``L = V = -N`` gives ``R·V = 1``).  ``diffuse`` is ``c_L`` rounded to ``out``
  (saturated: 0 for a negative cosine), so it is 0 there too.

Measured against float Phong ``max(R·V, 0)^n`` (0 where ``N̂·L <= 0``) on the same input
codes (the tests: seeded highlights with ``R`` within ``4/sqrt(n)`` of ``V``), max error in
8-bit levels (20000 pixels per ``n``): n = 1: 0.011; 16: 0.17; 64: 0.76; 500: 7.9; 8000:
67 — the 16-bit cosine magnified ``n`` times, as for Blinn, but about twice Blinn's
(0.40 at 64, 46 at 8000) since ``R·V`` takes two cosines.

On a scene (the torus of :mod:`phongfx.explore.evaluate`, n = 16, against float Phong at
the renormalized interpolated normal): 0.12 levels at the defaults.  The cheapest widths
within one level, by the tool-free cost proxy, are 11-bit vectors (``vec = S1.11``), a
128-word seed table (``rsqrt_addr = 7``) and 16-word log and exp tables (``log_addr =
exp_addr = 4``): 0.92 levels; one bit fewer in any of the three misses (10-bit vectors:
1.9).
"""

from .blinn import clamp_one, cosine, inverse_length, power
from .fixed import Fixed, check_range

__all__ = ["conventional", "unit_length", "reflection"]


def unit_length(config, vector):
    """``X/|X|`` in ``config.vec`` for an un-normalized ``vector`` (count, 3): each component
    scaled like a dot product by :func:`~phongfx.golden.blinn.cosine`; 0 for ``X = 0``."""
    j, y1 = inverse_length(config, vector, "conventional |X|²")
    return cosine(config, vector, j[:, None], Fixed(y1.raw[:, None], y1.fmt), config.fmt("vec"))


def reflection(config, c_light, c_view, light_view):
    """``clamp(2·c_L·c_V - L·V, 0, 1)`` in ``config.t``: Phong's ``R·V`` for
    ``R = 2(N̂·L)N̂ - L``, exact until one rounding."""
    return clamp_one(((c_light * c_view).shift(1) - light_view).quantize(
        config.t, config.rounding, "saturate", op="conventional R·V"))


def conventional(config, normal, light, view, n):
    """Diffuse ``clamp(N̂·L, 0, 1)`` and specular ``clamp(R·V, 0, 1)^n`` (0 where ``N̂·L <= 0``).

    Parameters
    ----------
    config : ConventionalConfig
    normal, light, view : Fixed, shape (count, 3), format ``config.vec``
        Un-normalized ``N``; ``L`` and ``V`` unit, or un-normalized where
        ``config.local_light`` / ``config.local_viewer`` (any codes give defined outputs).
    n : Fixed, shape (count,), format ``config.n``, integers 1..``config.n_max``

    Returns
    -------
    dict
        ``{"diffuse": Fixed (count,), "specular": Fixed (count,)}`` in ``config.out``
    """
    check_range("n", n, 1, config.n_max)
    light = unit_length(config, light) if config.local_light else light
    view = unit_length(config, view) if config.local_viewer else view
    j, y1 = inverse_length(config, normal, "conventional q")
    d_light = normal.dot(light)
    c_light, c_view = (cosine(config, d, j, y1, config.fmt("cos")) for d in (d_light, normal.dot(view)))
    diffuse = c_light.quantize(config.out, config.rounding, "saturate", op="conventional diffuse")
    # the backside test on the exact N·L, not on the rounded cosine: a c_L rounded to 0 is
    # still a light in front, and R·V = -L·V there is what Phong's formula gives.  t = 0
    # gives t^n = 0, so zeroing t is zeroing the specular
    t = reflection(config, c_light, c_view, light.dot(view))
    t = t.where(d_light.raw > 0, Fixed.const(0, config.t))
    return {"diffuse": diffuse, "specular": power(config, t, n)}

