"""A scene's domain cut into regions, each with the limits the scene really presents there.

One worst value for the whole image (:func:`phongfx.scene.domain.domain`) puts the widest span
of Lyon's image (39° on his 8-pixel spans at radius 32, Lyon 1993 Figure 9) at the centre of
every sphere, and every sphere's ``n`` with it.  A :class:`Region` holds its own limits; the
domain's regions together hold every input the scene can present, and a bound over each region
(:meth:`phongfx.scene.domain.Domain.region` is a domain every bounding method reads) bounds
the whole.

* **Lyon's spheres** (:func:`lyon_regions`): per sphere, with its own ``n``, bands of the
  angle ``θ`` between the pixel's normal ``N = unit((1-a)n0 + a·n1)`` and the viewer, each
  with the widest span whose pixels fall in it.  The image is fixed, so the limits are read
  off its spans exactly, widened by :data:`MARGIN_DEG` for the float arithmetic that made them.
  A band's span ends ``n0``, ``n1`` lie anywhere on the sphere's front hemisphere.
* **Meshes** (:mod:`phongfx.scene.patches`): patches of faces of one object and material.

A region is a set: ``(n0, n1, a, n)`` of one of its materials and admissible ``n``, with
``N·V`` in ``[view_cos_min, view_cos_max]``, ``n0·V``, ``n1·V`` in ``ends_cos``, the span
ends at most ``max_span_angle_deg`` apart and every point in ``ball``.
"""

import math
from dataclasses import dataclass, field

import numpy as np

from .lyon import Scene, pixels
from .sampling import Surface

__all__ = ["MARGIN_DEG", "BAND_MERGE_DEG", "Region", "lyon_regions", "holds", "summary"]

#: how far (degrees) a band's θ range and span angle are widened past the image's own values
MARGIN_DEG = 0.01
#: neighbouring 10° slices whose widest spans differ by less than this (degrees) share a band
BAND_MERGE_DEG = 2.0
_SLICE_DEG = 10.0


@dataclass(frozen=True)
class Region:
    """Part of a domain (module docstring): its name, its limits, where it is (``where``, for
    the manifest), and what its points are drawn from (``surface``, a
    :class:`~phongfx.scene.sampling.Surface`; ``poses``, the domain's pose fields narrowed to
    the poses under which the region faces the viewer)."""
    name: str
    materials: tuple            # as Domain.materials: per material index (name, admissible n; () none)
    view_cos_min: float         # N·V >= this for the pixel's normal N
    view_cos_max: float         # N·V <= this
    ends_cos: tuple             # (lo, hi): n0·V and n1·V within it
    max_span_angle_deg: float
    ball: tuple                 # ((cx, cy, cz), radius)
    where: dict = field(default_factory=dict, compare=False, hash=False)  # the domain stays hashable
    surface: Surface = field(default=None, compare=False, hash=False, repr=False)
    poses: tuple = ()           # ((Domain field, value), ...) for the sampler

    @property
    def min_normal_length(self):
        """``cos(angle/2)``: ``|(1-a)n0 + a·n1|`` is shortest at ``a = 1/2``."""
        return math.cos(math.radians(self.max_span_angle_deg) / 2)

    def as_dict(self):
        """JSON-able, brief: the limits a bound reads."""
        return {"name": self.name, "n": {name: list(values) for name, values in self.materials if values},
                "view_cos": [self.view_cos_min, self.view_cos_max], "ends_cos": list(self.ends_cos),
                "theta_deg": [_deg(self.view_cos_max), _deg(self.view_cos_min)],
                "max_span_angle_deg": self.max_span_angle_deg, "min_normal_length": self.min_normal_length,
                "ball": {"centre": list(self.ball[0]), "radius": self.ball[1]}, **self.where}


def _deg(cos):
    return round(math.degrees(math.acos(min(1.0, max(-1.0, cos)))), 4)


def _bands(theta, span):
    """``[(lo, hi, widest span)]`` over the pixels' ``theta`` and ``span`` angles (degrees):
    10° slices, neighbours merged while their widest spans stay within :data:`BAND_MERGE_DEG`."""
    slot = np.minimum((theta // _SLICE_DEG).astype(np.int64), int(180 // _SLICE_DEG) - 1)
    bands = []
    for s in np.unique(slot):
        mine = slot == s
        lo, hi, widest = float(theta[mine].min()), float(theta[mine].max()), float(span[mine].max())
        if bands and abs(widest - bands[-1][3]) < BAND_MERGE_DEG and abs(widest - bands[-1][4]) < BAND_MERGE_DEG:
            first = bands[-1]
            bands[-1] = (first[0], hi, max(first[2], widest), min(first[3], widest), max(first[4], widest))
        else:
            bands.append((lo, hi, widest, widest, widest))
    return [(lo, hi, widest) for lo, hi, widest, _, _ in bands]


def lyon_regions(params, materials, camera, claim=None):
    """The regions of Lyon's spheres (module docstring): ``params`` the ``lyon_spheres``
    object's, ``materials`` the domain's (the spheres' material has every sphere's ``n``),
    ``camera`` the unit direction toward the viewer; ``claim`` a ``[domain]``
    ``max_span_angle_deg`` that caps every band's."""
    px = pixels(Scene(params["radius"], params["shininess"], span=params["span"]))
    view = np.asarray(camera, dtype=np.float64)
    n = (1 - px.a)[:, None] * px.n0 + px.a[:, None] * px.n1
    normal = n / np.linalg.norm(n, axis=-1, keepdims=True)
    theta = np.degrees(np.arccos(np.clip(normal @ view, -1.0, 1.0)))
    span = np.degrees(np.arccos(np.clip(np.sum(px.n0 * px.n1, -1), -1.0, 1.0)))
    ends = np.minimum(px.n0 @ view, px.n1 @ view)
    used = next(m for m, (_, values) in enumerate(materials) if values)
    out = []
    for k, shininess in enumerate(params["shininess"]):
        mine = px.sphere == k
        if not np.any(mine):
            continue  # hidden behind its neighbours: it presents nothing
        own = tuple((name, (shininess,) if m == used else ()) for m, (name, _) in enumerate(materials))
        ends_lo = max(-1.0, float(ends[mine].min()) - math.radians(MARGIN_DEG))
        for lo, hi, widest in _bands(theta[mine], span[mine]):
            angle = min(180.0, widest + MARGIN_DEG)
            if claim is not None:
                angle = min(angle, claim)
            out.append(Region(
                f"sphere {k} (n = {shininess}), θ {lo:.1f}°..{hi:.1f}°", own,
                math.cos(math.radians(min(180.0, hi + MARGIN_DEG))), math.cos(math.radians(max(0.0, lo - MARGIN_DEG))),
                (ends_lo, 1.0), angle, ((float(k), 0.0, 0.0), 1.0),
                {"sphere": k, "pixels": int(np.count_nonzero(mine & (theta >= lo) & (theta <= hi)))},
                Surface(True, shininess=(shininess,), first=k)))
    return tuple(out)


def _dots(u, v):
    """Row-wise dot products: ``v`` one vector (3,) or one per row (P, 3)."""
    return u @ v if v.ndim == 1 else np.einsum("ij,ij->i", u, v)


def holds(regions, n0, n1, normal, views, material, n, positions):
    """(P,) bool: whether each point lies in some region (module docstring): ``views`` the
    viewer vectors (each one (3,) or per point (P, 3)), ``positions`` the points that must lie
    in the region's ball (each (P, 3))."""
    ok = np.zeros(len(n0), dtype=bool)
    angle = np.degrees(np.arccos(np.clip(np.einsum("ij,ij->i", n0, n1), -1.0, 1.0)))
    # each viewer's cosines taken once for every region: a region only compares them
    cosines = [(_dots(normal, v), _dots(n0, v), _dots(n1, v)) for v in views]
    distances = {}  # a ball's centre -> each position's distance from it
    for r in regions:
        mine = np.zeros(len(n0), dtype=bool)
        for m, (_, values) in enumerate(r.materials):
            if values:
                mine |= (material == m) & np.isin(n, values)
        mine &= angle <= r.max_span_angle_deg + 1e-9
        for facing, *ends in cosines:
            mine &= (facing >= r.view_cos_min - 1e-12) & (facing <= r.view_cos_max + 1e-12)
            for end in ends:
                mine &= (end >= r.ends_cos[0] - 1e-12) & (end <= r.ends_cos[1] + 1e-12)
        if r.ball[0] not in distances:  # regions of one object share its ball's centre
            centre = np.asarray(r.ball[0], dtype=np.float64)
            distances[r.ball[0]] = [np.linalg.norm(x - centre, axis=-1) for x in positions]
        for distance in distances[r.ball[0]]:
            mine &= distance <= r.ball[1] * (1 + 1e-12)
        ok |= mine
    return ok


def summary(regions):
    """A short line: how many regions and the range of their span angles and N·V limits."""
    if not regions:
        return "one region (the whole domain)"
    angles = [r.max_span_angle_deg for r in regions]
    return (f"{len(regions)} regions, span angles {min(angles):.2f}°..{max(angles):.2f}°, "
            f"N·V from {min(r.view_cos_min for r in regions):.4f}")
