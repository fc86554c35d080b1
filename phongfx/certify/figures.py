"""The bounding method of Lyon's datapaths: Figures 7 and 8 and the halfway unit of Figure 5.

Intervals through the golden blocks (:mod:`.datapath`) give the rounding part, the ideal
datapath's distance from the reference (:mod:`.approximation`) the approximation part, both per
box of the domain's normals (:mod:`.sphere`), summed at the outputs (:mod:`.outputs`) and
refined by :func:`~phongfx.certify.branch.bound_boxes`.  Lights and viewer at infinity.
"""

import numpy as np

from .branch import bound_boxes
from .outputs import box_errors
from .sphere import frame

__all__ = ["LyonDatapaths", "LYON_DATAPATHS", "directional_why_not"]


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
    """Bounds ``fig7``, ``fig8`` and ``halfway`` (its ``g2proj`` and ``d3`` variants)."""

    #: what the certificate names as its method
    name = "interval"

    def why_not(self, shader, domain):
        """None when this method bounds ``shader`` on ``domain``, else one sentence why not."""
        why = directional_why_not(domain)
        if why:
            return why
        unit = shader.units[0]
        if unit.specular == "halfway" and unit.halfway.variant not in ("g2proj", "d3"):
            return f"the halfway unit's {unit.halfway.variant} variant is not bounded yet"
        return None

    def bound(self, shader, spec, domain, *, max_boxes=300_000, enough=None):
        """``(bound_levels, parts)`` over ``domain`` (:func:`~phongfx.certify.branch.bound_boxes`)."""
        basis = frame(domain.camera[1])
        lights = [np.asarray(vector, dtype=np.float64) for _, vector, _ in domain.lights]
        against = spec.requirement.against

        def errors(boxes):
            return box_errors(shader, against, boxes, basis, lights, domain.min_normal_length)

        return bound_boxes(errors, domain, max_boxes=max_boxes, enough=enough)


LYON_DATAPATHS = LyonDatapaths()
