"""A bound over a domain cut into regions: the whole domain's, or the largest of the regions'.

The regions of a domain (:mod:`phongfx.scene.regions`) hold together every input the scene can
present, so the largest of sound bounds over each region's domain
(:meth:`phongfx.scene.domain.Domain.region`) is a sound bound over the whole, and so is the
bound over the whole domain: the certificate takes the smaller.  Each region is bounded by the
same method with its own, tighter, limits (its span angle, its N·V zone, its ``n``).

The whole domain is bounded first, and the regions only when its bound misses the requirement
(``target``): a branch and bound over boxes of normals already splits the whole domain by ``n``
and direction, so the regions tighten only what their limits decide (on Lyon's spheres, where
the span angle sets ``|N'|``: a first-order normalizer, 8.0 levels against 11.5; the halfway unit
the compiler chooses, at 15/5/13 bits, 1.498 against 1.590, under the requirement's 1.5 only by
region), at two to six times the time; on the torus's patches, whose span angles are all within
5 % of the whole's, the worst patch is as bad as the whole (1.4995 against 1.4934).

The regions share the box budget: every region is first bounded on an eighth of an even share,
then, the highest first, again on four times its last budget while it is above the requirement
and not settled (a bound over more boxes is as sound, and the smaller of a region's bounds is
kept) nor falling too slowly to reach it within the whole budget at its pace per box since its
last run, as a width search's early stop does, so that the final certificate of a design the
search passed passes too; then the worst region while the budget lasts, up to :data:`SPEND`
times the budget in all (each refinement goes on from where the region's last stopped,
:class:`~.branch.Resume`, and is counted as the whole branch and bound it stands for, so the
result is that of starting over); once a region stays above the requirement the design fails
whatever the others give, and the worst region gets one more budget, for the bound reported. The
region that starts highest is most often the one that stays above: taken first, it ends a
failing width point's certificate before the others are refined.

A width search whose certificate at wider widths needed the regions asks for them first
(``regions_first``): its whole domain would miss again, and bounding it first took a third of each
of the halfway unit's certificates on Lyon's spheres; the bound is then the largest over the
regions, none being the whole's.

A region whose limits are the whole domain's as the bounding method reads them
(:func:`like_whole`: on the torus, the patch whose normals reach every N·V of the whole; for the
table units about a local viewer's cone, whose cover is the cone's whatever a region's N·V) is
bounded as the whole is, on no larger budget, so its bound is never below the whole's: when the
whole misses the requirement, so does the largest over the regions, and they are not bounded at
all (``parts["like_whole"]`` names that region).  The result is the same; a failing width
point's certificate there spent more than half its time in its regions.
"""

import math
from dataclasses import fields, replace

import numpy as np

from .branch import Resume

__all__ = ["FIRST_BOXES", "SPEND", "UNREAD", "by_region", "limits", "like_whole"]

#: the least first budget of a region, boxes
FIRST_BOXES = 1000
#: how many times ``max_boxes`` the regions may spend together
SPEND = 3
#: the fields of a :class:`~phongfx.scene.domain.Domain` no bounding method reads (the sampler's
#: own, and the regions' names)
UNREAD = ("surface", "ends_cos", "regions", "region_name")


def limits(domain, unread=()):
    """``{field: value}`` of ``domain`` a bounding method reads: every field but :data:`UNREAD`
    and ``unread`` (a method's ``limits(domain)``, which may add what it derives from them)."""
    return {f.name: getattr(domain, f.name) for f in fields(domain) if f.name not in UNREAD + tuple(unread)}


def like_whole(how, domain):
    """The indices of ``domain``'s regions of which the bounding method ``how`` reads the same
    limits as of the whole domain (``how.limits``), floats to 1e-9: the whole to its bound."""
    whole = how.limits(domain)
    return [i for i in range(len(domain.regions)) if _close(how.limits(domain.region(i)), whole)]


def _close(a, b):
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(_close(a[k], b[k]) for k in a)
    if isinstance(a, (tuple, list)) and isinstance(b, (tuple, list)):
        return len(a) == len(b) and all(_close(x, y) for x, y in zip(a, b))
    if isinstance(a, float) or isinstance(b, float):
        return (isinstance(a, (int, float)) and isinstance(b, (int, float))
                and math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-12))
    return bool(np.all(a == b)) if isinstance(a, np.ndarray) or isinstance(b, np.ndarray) else a == b


def by_region(how, shader, spec, domain, *, max_boxes, enough=None, target=None, regions_first=False):
    """``(bound_levels, parts)`` of the bounding method ``how`` over ``domain`` (module
    docstring): the whole domain's bound, and when it is not below ``target`` and the domain
    has regions, the largest over the regions if smaller.  Then ``parts["regions"]`` gives per
    region its name, bound and where its worst box is, ``parts["region"]`` the worst region's
    name and ``parts["whole_bound"]`` the whole domain's bound.  With ``enough`` (a width search,
    which asks only whether the bound is below it) a region is refined only until it is below,
    and the first region that stays above ends the search (``parts["unbounded_regions"]``
    names the others not yet below; the bound is then the whole domain's).  With no
    ``max_boxes`` only the whole domain is bounded.

    ``regions_first`` (with ``enough``: a width search whose certificate at wider widths needed
    its regions, where the whole domain, bounded first, would miss again): the regions without
    the whole, unless one of them is like it; the bound is then the largest over the regions
    (each region's bound holds over it, and they cover the domain), ``parts["whole_bound"]``
    None."""
    regions = getattr(domain, "regions", ())
    if (regions_first and regions and enough is not None and target is not None and max_boxes
            and not like_whole(how, domain)):
        bound, parts = np.inf, {"boxes": 0}
    else:
        bound, parts = how.bound(shader, spec, replace(domain, regions=()) if regions else domain,
                                 max_boxes=max_boxes, enough=enough)
        # no budget (whether the domain can be bounded at all): the regions could only refine it
        if not regions or target is None or not max_boxes or bound < target or not np.isfinite(bound):
            return bound, parts
        same = like_whole(how, domain)
        if same:  # the regions cannot beat the whole (module docstring)
            return bound, dict(parts, like_whole=regions[same[0]].name)
    found, failed, spent = _regions(how, shader, spec, domain, max_boxes, enough, target)
    names = [r.name for r in domain.regions]
    worst = int(np.argmax([b for b, *_ in found])) if failed is None else failed
    listed = [{"name": name, "bound_levels": float(b), "where": p.get("where")} for name, (b, p, *_) in
              zip(names, found)]
    extra = {"regions": listed, "region": names[worst], "whole_bound": float(bound) if np.isfinite(bound) else None,
             "boxes": int(parts.get("boxes", 0) + spent)}
    if failed is not None:
        extra["unbounded_regions"] = [name for i, (name, f) in enumerate(zip(names, found))
                                      if i != failed and not f[0] < enough]
        extra["region_bound"] = float(found[failed][0])  # the region that stayed above, alone
    if failed is None and found[worst][0] < bound:
        bound, parts = found[worst][:2]
    elif not np.isfinite(bound):  # no whole bound (regions_first): the regions' largest
        bound, parts = found[int(np.argmax([b for b, *_ in found]))][:2]
    return bound, dict(parts, **extra)


def _regions(how, shader, spec, domain, max_boxes, enough, target):
    """``(found, failed, boxes)``: per region ``(bound, parts, budget, final, boxes)`` (module
    docstring), the region at which a width search (``enough``) stopped, None when it did not,
    and the boxes spent.  Each region is refined until it is below ``enough`` or ``target``,
    as a width search would, so that the final certificate of a design the search passed passes
    too; then, without ``enough``, the worst region again while the budget lasts (once a region
    stays above ``target``, one more budget for the worst)."""
    count = len(domain.regions)
    found, spent = [], [0]
    resumes = [Resume() for _ in range(count)]
    below = enough if enough is not None else target

    def run(index, budget, stop):
        bound, parts = how.bound(shader, spec, domain.region(index), max_boxes=budget, enough=stop,
                                 resume=resumes[index])
        bound = bound if np.isfinite(bound) else np.inf
        boxes = parts.get("boxes", budget)
        spent[0] += boxes
        # settled before the budget (not merely below ``stop``, nor given up on this budget's
        # pace: a larger one may reach it), or given all of it
        final = budget >= max_boxes or (boxes < budget and not (stop is not None and bound < stop)
                                        and not parts.get("abandoned"))
        if index < len(found):
            before, _, _, _, used = found[index]
            if stop is not None and not bound < stop and boxes > used:
                # falling at its pace per box since the last run, it would still not be below
                # ``stop`` at the whole budget: a larger one is not worth its time either
                pace = (before - bound) / (boxes - used)
                final = final or bound - pace * (max_boxes - boxes) >= stop
            if not bound < before:
                bound, parts = found[index][:2]
            found[index] = (bound, parts, budget, final, boxes)
        else:
            found.append((bound, parts, budget, final, boxes))

    def refine(index, stop):
        run(index, min(4 * found[index][2], max_boxes), stop)

    first = max(max_boxes // (8 * count), FIRST_BOXES)
    limit = SPEND * max_boxes
    for index in range(count):
        run(index, first, below)
    # the worst on its first share first: a region that stays above ends a width search's
    # certificate, and it is most often the one that starts highest
    for index in sorted(range(count), key=lambda i: -found[i][0]):
        while not found[index][0] < below and not found[index][3] and spent[0] < limit:
            refine(index, below)
        if not found[index][0] < below:
            if enough is not None:
                return found, index, spent[0]
            # the design fails whatever the others give: one more budget to tighten the worst,
            # for the bound the certificate reports
            limit = spent[0] + max_boxes
            break
    while enough is None and spent[0] < limit:
        worst = int(np.argmax([b for b, *_ in found]))
        if found[worst][3]:
            break
        refine(worst, None)
    return found, None, spent[0]
