"""Golden model of a whole shading datapath (Lyon 1993, Figures 6–8 and 5), diffuse included.

N: LIRP → approximate normalizer.  L and V: constant inputs (at infinity) or, when
local, LIRP → normalizer like N with the same ``a``.  Then one specular unit
(:class:`~phongfx.config.DatapathConfig` ``specular``) and, per light, the diffuse
term from the same normalized N.  Every intermediate format is that of the
sub-block configs.
"""

from .difference import difference
from .diffuse import diffuse
from .halfway import halfway
from .lirp import lirp
from .normalize import normalize
from .reflect import reflect
from .root import root
from .shape import shape

__all__ = ["datapath"]


def datapath(config, **ports):
    """Specular and diffuse amounts for each light.

    Parameters
    ----------
    config : DatapathConfig
    ports : Fixed
        ``n0``, ``n1`` (span-end normals; equal with ``a = 0`` for exact normals), ``a``,
        the shininess ``n`` (or ``m`` for Figure 8; none when ``config.shininess_const``
        fixes it), ``v`` or ``v0``/``v1`` (local viewer),
        and ``l<i>`` or ``l<i>_0``/``l<i>_1`` (local lights), as ``config.inputs`` lists.

    Returns
    -------
    dict
        ``spec<i>`` and ``diff<i>`` for each light.
    """
    a = ports["a"]

    def interpolated(end0, end1, normalizer):
        return normalize(normalizer, lirp(config.lirp, end0, end1, a)["n"])["n"]

    normal = interpolated(ports["n0"], ports["n1"], config.normalize)
    view = (interpolated(ports["v0"], ports["v1"], config.direction_normalize)
            if config.local_viewer else ports["v"])
    # a constant shininess (config.shininess None) lives in the unit's own config
    shininess = ports[config.shininess[0]] if config.shininess is not None else None
    if config.specular in ("fig7", "fig8"):
        r = reflect(config.reflect, normal, view)["r"]
    out = {}
    for index in range(config.lights):
        light = (interpolated(ports[f"l{index}_0"], ports[f"l{index}_1"], config.direction_normalize)
                 if config.local_light(index) else ports[f"l{index}"])
        if config.specular == "fig7":
            x2 = difference(config.difference, r, light, shininess)["x2"]
            out[f"spec{index}"] = shape(config.shape, x2)["spec"]
        elif config.specular == "fig8":
            out[f"spec{index}"] = root(config.root, r, light, shininess)["spec"]
        else:
            d = halfway(config.halfway, normal, light, view)
            scaled = shininess.shift(config.halfway_shift) if shininess is not None else None
            x2 = difference(config.difference, d["p"], d["q"], scaled)["x2"]
            out[f"spec{index}"] = shape(config.shape, x2)["spec"]
        out[f"diff{index}"] = diffuse(config.diffuse, normal, light)["diff"]
    return out
