"""Golden model of Lyon's Figure 7 datapath (1993, Figures 6 and 7a–d), diffuse included.

LIRP → approximate normalizer → reflect → (per light) difference/x → shape, and
(per light) diffuse from the same normalized ``N``.  Lights and viewer are at
infinity, so ``L`` and ``V`` are constant inputs, not interpolated.  Every
intermediate format is that of the sub-block configs in :class:`Fig7Config`.
"""

from .difference import difference
from .diffuse import diffuse
from .lirp import lirp
from .normalize import normalize
from .reflect import reflect
from .shape import shape

__all__ = ["fig7"]


def fig7(config, n0, n1, a, n, v, **lights):
    """Specular and diffuse amounts for each light.

    Parameters
    ----------
    config : Fig7Config
    n0, n1 : Fixed (count, 3)
        Span-end normals (equal, with ``a = 0``, for exact per-pixel normals).
    a : Fixed (count,)
        Interpolation factor.
    n : Fixed (count,)
        Shininess, integer 1..n_max.
    v : Fixed (count, 3)
        Viewer direction.
    l0, l1, ... : Fixed (count, 3)
        Light directions, ``config.lights`` of them.

    Returns
    -------
    dict
        ``spec<i>`` (format ``shape.t``) and ``diff<i>`` (format ``diffuse.out``).
    """
    normal = normalize(config.normalize, lirp(config.lirp, n0, n1, a)["n"])["n"]
    r = reflect(config.reflect, normal, v)["r"]
    out = {}
    for index in range(config.lights):
        l = lights[f"l{index}"]
        x2 = difference(config.difference, r, l, n)["x2"]
        out[f"spec{index}"] = shape(config.shape, x2)["spec"]
        out[f"diff{index}"] = diffuse(config.diffuse, normal, l)["diff"]
    return out
