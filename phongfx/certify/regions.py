"""A bound over a domain cut into regions: the largest of the bounds over each region.

The regions of a domain (:mod:`phongfx.scene.regions`) hold together every input the scene can
present, so the largest of sound bounds over each region's domain
(:meth:`phongfx.scene.domain.Domain.region`) is a sound bound over the whole; each region is
bounded by the same method with its own, tighter, limits (its span angle, its N·V zone, its
``n``).  A domain without regions is bounded whole.
"""

import numpy as np

__all__ = ["by_region"]


def by_region(how, shader, spec, domain, *, max_boxes, enough=None):
    """``(bound_levels, parts)`` of the bounding method ``how`` over ``domain``: with regions,
    the largest over them, ``parts`` the worst region's with ``parts["region"]`` its name and
    ``parts["regions"]`` per region its name, bound and where its worst box is.  With
    ``enough`` (a width search, which asks only whether the bound is below it) each region is
    refined only below it, and the first region left above it ends the search: the design
    fails whatever the others give, and ``parts["unbounded_regions"]`` names the regions not
    bounded, whose bound (the largest so far) is then no bound over the whole domain."""
    if not getattr(domain, "regions", ()):
        return how.bound(shader, spec, domain, max_boxes=max_boxes, enough=enough)
    count = len(domain.regions)
    # each region has its own budget; the whole never spends much more than one domain's
    budget = max(max_boxes // count, 1000)
    found = []
    for index, region in enumerate(domain.regions):
        bound, parts = how.bound(shader, spec, domain.region(index), max_boxes=budget, enough=enough)
        found.append((bound, region.name, parts))
        if enough is not None and not bound < enough:
            break
    worst = int(np.argmax([b if np.isfinite(b) else np.inf for b, _, _ in found]))
    bound, name, parts = found[worst]
    parts = dict(parts, region=name,
                 regions=[{"name": n, "bound_levels": float(b), "where": p.get("where")} for b, n, p in found])
    if len(found) < count:
        parts["unbounded_regions"] = [r.name for r in domain.regions[len(found):]]
    faults = sorted({f for _, _, p in found for f in p.get("faults", [])})
    if faults:
        parts["faults"] = faults
    return bound, parts
