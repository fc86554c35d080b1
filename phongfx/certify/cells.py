"""Cells of surface points: a point light's and a local viewer's cones, narrowed where a bound needs it.

A point light or a local camera at ``P`` is seen from a surface point ``x`` along ``unit(P - x)``;
from the domain's ball, within ``asin(radius/|P - centre|)`` of ``unit(P - centre)``
(:mod:`.cones`).  A box of the branch and bound (:class:`~phongfx.certify.sphere.Boxes`) may also
carry a *cell*, an axis-aligned box of surface points: the ball's points in it lie in the smaller
of the cell's circumscribed ball (its centre, half its diagonal) and the domain's ball, so that
from them ``P`` is seen within ``asin(r/|P - c|)`` of ``unit(P - c)`` (a camera path's positions
as :mod:`.cones` joins them: about the mean axis, as wide as the farthest cone reaches).

A pixel's ``L`` and ``V`` come from one surface point (the conventional unit is fed the pixel's
own vectors): a cell narrows both cones at once and keeps them together, which two independent
cones cannot (from the whole ball, ``L`` and ``V`` of different points).  The branch and bound
halves a cell along its longest edge like any side of a box (:meth:`Boxes.split
<phongfx.certify.sphere.Boxes.split>`, its width the angle its half-diagonal turns a direction
by); near the highlight only the cells whose ``L`` and ``V`` the box's normals nearly bisect stay
near the top.  A cell that does not meet the ball holds no input.
"""

import numpy as np

__all__ = ["root", "scale", "positions", "toward", "meets", "per_box"]


def root(domain, count):
    """``count`` copies of the cell holding the domain's ball, its bounding cube: (count, 2, 3)."""
    centre, radius = np.asarray(domain.ball[0], dtype=np.float64), float(domain.ball[1])
    cube = np.stack([centre - radius, centre + radius])
    return np.broadcast_to(cube, (count, 2, 3)).copy()


def positions(domain):
    """Per point light, its position (one), then the local camera's (its path's, or the one); the
    directions toward each are the cones a cell narrows."""
    lights = [((np.asarray(vector, dtype=np.float64),) if kind == "point" else ())
              for kind, vector, _ in domain.lights]
    camera = (tuple(np.asarray(p, dtype=np.float64) for p in (domain.camera_path or (domain.camera[1],)))
              if domain.camera[0] == "point" else ())
    return lights, camera


def scale(domain):
    """Radians a direction toward a point light or the local camera turns by per unit length of a
    cell's half-diagonal, at most (``1/D``, ``D`` the nearest such position's distance to the ball),
    what :meth:`~phongfx.certify.sphere.Boxes.widths` compares with the normals' sides."""
    centre, radius = np.asarray(domain.ball[0], dtype=np.float64), float(domain.ball[1])
    lights, camera = positions(domain)
    every = [p for group in lights for p in group] + list(camera)
    if not every:
        return 0.0
    return 1.0 / max(min(float(np.linalg.norm(p - centre)) for p in every) - radius, 1e-9)


def _ball(domain, cells):
    """Per cell ``(centre (B, 3), radius (B,))``: its circumscribed ball, or the domain's where that
    is no smaller."""
    centre, radius = np.asarray(domain.ball[0], dtype=np.float64), float(domain.ball[1])
    mid = 0.5 * (cells[:, 0] + cells[:, 1])
    half = 0.5 * np.linalg.norm(cells[:, 1] - cells[:, 0], axis=-1)
    whole = half >= radius
    return np.where(whole[:, None], centre, mid), np.where(whole, radius, half)


def toward(domain, cells, where):
    """``(axis (B, 3), half (B,))``: per cell the cone of directions toward the positions ``where``
    (one, or a camera path's) from its points (module docstring); ``half`` π where a position is
    within the cell's ball."""
    centre, radius = _ball(domain, cells)
    axes, halves = [], []
    for p in where:
        d = p - centre
        distance = np.linalg.norm(d, axis=-1)
        axes.append(d / np.maximum(distance, 1e-300)[:, None])
        halves.append(np.where(distance > radius, np.arcsin(np.clip(radius / np.maximum(distance, 1e-300), 0, 1)),
                               np.pi))
    mean = np.sum(axes, axis=0)
    size = np.linalg.norm(mean, axis=-1)
    axis = mean / np.maximum(size, 1e-300)[:, None]
    half = np.max([np.arccos(np.clip(np.sum(axis * a, -1), -1.0, 1.0)) + h for a, h in zip(axes, halves)], axis=0)
    half = np.where(size < 1e-9, np.pi, np.minimum(half, np.pi))
    return axis, half * (1 + 1e-12)


def meets(domain, cells):
    """(B,) whether each cell meets the domain's ball (else it holds no surface point)."""
    centre, radius = np.asarray(domain.ball[0], dtype=np.float64), float(domain.ball[1])
    nearest = np.clip(centre, cells[:, 0], cells[:, 1])
    return np.linalg.norm(nearest - centre, axis=-1) <= radius * (1 + 1e-12)


def per_box(domain, boxes):
    """``(lights, view)``: per light, and for the viewer, ``(axis (B, 3), half (B,))`` of its
    directions from each box's cell (:func:`toward`), or None where it is at infinity or the
    boxes carry no cells."""
    lights, camera = positions(domain)
    if boxes.cells is None:
        return [None] * len(lights), None
    return ([toward(domain, boxes.cells, at) if at else None for at in lights],
            toward(domain, boxes.cells, camera) if camera else None)
