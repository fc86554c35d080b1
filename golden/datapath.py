"""Golden model of a whole shading datapath (Lyon 1993, Figures 6–8 and 5), diffuse included.

N: LIRP → approximate normalizer.  L and V: constant inputs (at infinity) or, when
local, LIRP → normalizer like N with the same ``a``.  Then one specular unit
(:class:`~phongfx.config.DatapathConfig` ``specular``: the ``golden`` face of its method in
:data:`phongfx.core.methods.METHODS`, e.g. :func:`fig7` below) and, per light, the diffuse
term from the same normalized N.  Every intermediate format is that of the
sub-block configs.
"""

from phongfx.core.methods import get_method

from .difference import difference
from .diffuse import diffuse
from .halfway import halfway
from .lirp import lirp
from .normalize import normalize
from .reflect import reflect
from .root import root
from .shape import shape

__all__ = ["datapath", "fig7", "fig8", "halfway_unit"]


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
    lights = [interpolated(ports[f"l{index}_0"], ports[f"l{index}_1"], config.direction_normalize)
              if config.local_light(index) else ports[f"l{index}"] for index in range(config.lights)]
    unit = get_method(config.specular).load("golden")
    out = {}
    for index, (light, spec) in enumerate(zip(lights, unit(config, normal, view, lights, shininess))):
        out[f"spec{index}"] = spec
        out[f"diff{index}"] = diffuse(config.diffuse, normal, light)["diff"]
    return out


def fig7(config, normal, view, lights, shininess):
    """Figure 7b–d per light: R once, then difference/x (``n``) → shape; the ``spec`` of each light."""
    r = reflect(config.reflect, normal, view)["r"]
    return [shape(config.shape, difference(config.difference, r, light, shininess)["x2"])["spec"]
            for light in lights]


def fig8(config, normal, view, lights, shininess):
    """Figure 8 per light: R once, then the root-shininess unit (``m = √n``)."""
    r = reflect(config.reflect, normal, view)["r"]
    return [root(config.root, r, light, shininess)["spec"] for light in lights]


def halfway_unit(config, normal, view, lights, shininess):
    """Figure 5 per light: the halfway difference vector, then difference/x with the
    shininess scaled by ``2^halfway_shift`` → shape."""
    scaled = shininess.shift(config.halfway_shift) if shininess is not None else None
    out = []
    for light in lights:
        d = halfway(config.halfway, normal, light, view)
        out.append(shape(config.shape, difference(config.difference, d["p"], d["q"], scaled)["x2"])["spec"])
    return out
