"""Golden model of the colour blend, the last step of a shader: per channel the ambient term
plus, over the lights, diffuse and specular amounts weighted by the material's coefficients.

Phong (1975) and Lyon (1993, "Background") shade a pixel as ``ambient + Σ_lights
intensity·(kd·diffuse + ks·specular)`` per colour channel; the units before this one give
each light's ``diffuse`` (``max(N·L, 0)``) and ``specular`` amounts, and here they are
weighted by constants the scene compiler computes (``ka·colour``, ``kd·colour·light RGB``,
``ks·colour·light RGB``, :class:`~phongfx.config.BlendConfig`).  The constants carry the
display scale ``2^bits − 1`` folded in (:meth:`~phongfx.config.BlendConfig.raw_code`), so the
exact sum is already in output levels and one rounding to an integer, saturating at
``2^bits − 1``, gives the code: no multiply by 255 and no second rounding.

With :attr:`~phongfx.config.BlendConfig.gate` the specular amount of light ``i`` counts only
where ``diff_i > 0``: the backside test.  Lyon (1993, "Pixel Shading Hardware Datapaths")
notes that ``N·L < 0`` is usually made to zero the diffuse component, which the diffuse
unit's clamp does (``diff_i = 0`` there); a light behind the surface must give no highlight
either, and ``diff_i`` is the one bit of it the blend sees (the conventional unit applies
the same test to its specular output).

Exact arithmetic throughout: each product is a ``Fixed`` times the coefficient code of the
pixel's material (a table look-up, as a coefficient ROM addressed by ``material`` would be),
summed exactly; the hardware (:class:`phongfx.hdl.blend.Blend`) builds the same exact value
by shifts and adds in narrower formats, so the one quantize gives the same code.
"""

import numpy as np

from phongfx.config.blend import CHANNELS

from .fixed import Fixed, check_range

__all__ = ["blend"]


def blend(config, **ports):
    """The blended colour codes of each pixel.

    Parameters
    ----------
    config : BlendConfig
    ports : Fixed, shape (count,)
        ``diff{i}`` (``config.diff``; none when it is ``""``) and ``spec{i}``
        (``config.spec``) for each light ``i``, and ``material`` (its code,
        ``0..materials − 1``) when ``config.materials > 1``.

    Returns
    -------
    dict
        ``{"r", "g", "b": Fixed (count,) in config.out_format}``

    Raises
    ------
    ValueError
        A ``material`` code outside ``0..materials − 1``.
    """
    # each table checked once against the coefficient format, then looked up per pixel (a
    # coefficient ROM addressed by ``material``); with one material, its constants as they are
    coef = config.coef_format
    tables = [config.coefficients(m) for m in range(config.materials)]
    ambient = Fixed(np.array([a for a, _, _ in tables], dtype=np.int64), coef)     # (materials, 3)
    diffuse = Fixed(np.array([d for _, d, _ in tables], dtype=np.int64), coef)     # (materials, lights, 3)
    specular = Fixed(np.array([s for _, _, s in tables], dtype=np.int64), coef)
    if config.materials > 1:
        index = check_range("material", ports["material"], 0, config.materials - 1).raw
    else:
        index = 0

    spec = []
    for i in range(config.lights):
        s = ports[f"spec{i}"]
        if config.gate:
            d = ports[f"diff{i}"]
            s = s.where(d >= d.fmt.lsb, Fixed.const(0, s.fmt))
        spec.append(s)

    out = {}
    for c, name in enumerate(CHANNELS):
        acc = ambient[index, c]
        for i in range(config.lights):
            if config.diff:
                acc = acc + ports[f"diff{i}"] * diffuse[index, i, c]
            acc = acc + spec[i] * specular[index, i, c]
        out[name] = acc.quantize(f"{config.bits}.0", config.rounding, "saturate", op=f"blend {name}")
    return out
