"""Golden model of the diffuse amount ``max(N·L, 0)``, Lyon (1993) "Background" (Lambert).

Figure 6 has a diffuse reflection calculator beside the specular one, but Figure 7
does not detail it; the text of "Pixel Shading Hardware Datapaths" notes that the
backside test ``N·L < 0`` is usually applied to zero the diffuse component.

The formats are our reconstruction.  ``N`` and ``L`` are ``S1.10``, as every
direction vector of Figure 7.  ``N·L`` is three exact 12×12 products, ``S3.20``,
summed exactly in ``S5.20``; the backside test is its sign bit, a multiplexer to
0; one rounding brings it to ``out`` = ``1.10``: unsigned since the clamp leaves
no negative values, one integer bit so that ``N = L`` gives 1.0 exactly, the 10
fraction bits of the vectors.  Error against exact arithmetic on the same inputs:
1/2 LSB rounded, under 1 LSB truncated.

For unit inputs ``N·L <= 1``; junk codes (``|N_i|`` up to 2) reach 12, so the
quantize saturates rather than wrap a bright pixel to black.
"""

from .fixed import Fixed

__all__ = ["diffuse"]


def diffuse(config, n, l):
    """Lambert's diffuse amount for normal ``n`` and light direction ``l``.

    Parameters
    ----------
    config : DiffuseConfig
    n, l : Fixed, shape (count, 3), format ``config.vec``

    Returns
    -------
    dict
        ``{"diff": Fixed (count,) in config.out}``
    """
    dot = n.dot(l)
    lit = dot.where(dot >= 0, Fixed.const(0, dot.fmt))
    return {"diff": lit.quantize(config.out, config.rounding, "saturate", op="diffuse N·L")}
