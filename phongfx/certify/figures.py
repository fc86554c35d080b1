"""The bounding method of Lyon's datapaths: Figures 7 and 8 and the halfway unit of Figure 5.

Intervals through the golden blocks (:mod:`.datapath`) give the rounding part, the ideal
datapath's distance from the reference (:mod:`.approximation`) the approximation part, both per
box of the domain's normals (:mod:`.sphere`), summed at the outputs (:mod:`.outputs`) and
refined by :func:`~phongfx.certify.branch.bound_boxes`.  Lights and viewer at infinity, or
point lights and a local viewer seen from the domain's ball (:mod:`.cones`).
"""

import numpy as np

from .branch import bound_boxes, cases
from .cones import cone_why_not, directions
from .datapath import fig7_specular, fig8_specular, halfway_specular
from .outputs import box_errors
from .regions import limits
from .sphere import cover

__all__ = ["LyonDatapaths", "FIG7_BOUND", "FIG8_BOUND", "HALFWAY_BOUND", "directional_why_not",
           "unit_directions_why_not"]


def directional_why_not(domain):
    """Why ``domain`` is outside what a bound with lights and viewer at infinity covers (None
    when it is inside)."""
    if any(kind != "directional" for kind, _, _ in domain.lights):
        return "point lights are not bounded yet"
    if domain.camera[0] != "infinity":
        return "a local viewer is not bounded yet"
    if not any(values for _, values in domain.materials):
        return "the domain admits no shininess n"
    vectors = [vector for _, vector, _ in domain.lights] + [domain.camera[1]]
    if any(abs(float(np.linalg.norm(v)) - 1.0) > 1e-9 for v in vectors):
        return "the light and camera directions must be unit vectors, as the bound's geometry takes them"
    return None


class LyonDatapaths:
    """Bounds a specular unit of Lyon's datapath: ``fig7``, ``fig8`` and ``halfway`` (its
    ``g2proj`` and ``d3`` variants), one instance each (their methods' ``certify`` face).

    ``specular``: the unit's intervals after the normalizer
    (:func:`~phongfx.certify.datapath.fig7_specular`...); ``k_field``: the sub-config whose
    ``k`` is its shape's (``shape``; Figure 8's ``root``); ``variants``: those bounded of a unit
    whose form is taken at ``N·H`` (Figure 5's, :attr:`~phongfx.config.base.SpecularUnit.bisector`),
    which is bounded with directional lights and the viewer at infinity only; ``gappa``: Gappa
    proves its chain (:mod:`.gappa`: Figure 7's).
    """

    #: what the certificate names as its method
    name = "interval"
    #: what of a domain its bound reads: every limit (:func:`~phongfx.certify.regions.limits`)
    limits = staticmethod(limits)

    def __init__(self, specular, k_field="shape", *, variants=(), gappa=False):
        self.specular, self.k_field, self.variants, self.gappa = specular, k_field, variants, gappa

    def why_not(self, shader, domain):
        """None when this method bounds ``shader`` on ``domain``, else one sentence why not."""
        why = cone_why_not(domain) or unit_directions_why_not(domain)
        if why:
            return why
        if not any(values for _, values in domain.materials):
            return "the domain admits no shininess n"
        unit = shader.units[0]
        for index, (kind, _, _) in enumerate(domain.lights):
            if unit.local_light(index) != (kind == "point"):
                return (f"light {index} is a {kind} light but the datapath takes it "
                        f"{'interpolated' if unit.local_light(index) else 'as a constant'}")
        if unit.local_viewer != (domain.camera[0] == "point"):
            return f"the camera is {domain.camera[0]} but the datapath's local_viewer is {unit.local_viewer}"
        if unit.unit.bisector and unit.any_local:
            return ("the halfway unit with point lights or a local viewer is not bounded yet (its form "
                    "against Phong's R·L takes N·H and R·L together, which the light and viewer cones "
                    "decouple in every box of normals)")
        if unit.unit.bisector and unit.halfway.variant not in self.variants:
            return f"the halfway unit's {unit.halfway.variant} variant is not bounded yet"
        return None

    def bound(self, shader, spec, domain, *, max_boxes=300_000, enough=None, resume=None):
        """``(bound_levels, parts)`` over ``domain`` (:func:`~phongfx.certify.branch.bound_boxes`);
        point lights and a local viewer as :mod:`.cones` bounds them."""
        cones = directions(domain)
        against = spec.requirement.against
        boxes = None
        if cones.view.half:  # the boxes cover the normals about the viewer cone's axis
            boxes = cover(cones.cover_cos_min, domain.min_normal_length, cases(domain))

        def errors(boxes, floor):  # one bound for every box: the floor saves nothing
            return box_errors(shader, self, against, boxes, cones.basis, None, domain.min_normal_length, cones)

        return bound_boxes(errors, domain, max_boxes=max_boxes, enough=enough, boxes=boxes, resume=resume,
                           separable=True)


def unit_directions_why_not(domain):
    """Why the directions at infinity are outside the bound's geometry (None when inside)."""
    vectors = [vector for kind, vector, _ in domain.lights if kind == "directional"]
    if domain.camera[0] == "infinity":
        vectors.append(domain.camera[1])
    if any(abs(float(np.linalg.norm(v)) - 1.0) > 1e-9 for v in vectors):
        return "the light and camera directions must be unit vectors, as the bound's geometry takes them"
    return None


#: The ``certify`` faces of the methods ``fig7``, ``fig8`` and ``halfway``.
FIG7_BOUND = LyonDatapaths(fig7_specular, gappa=True)
FIG8_BOUND = LyonDatapaths(fig8_specular, "root")
HALFWAY_BOUND = LyonDatapaths(halfway_specular, variants=("g2proj", "d3"))
