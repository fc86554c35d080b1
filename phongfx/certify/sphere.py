"""Boxes that cover the normals of a domain: direction about the viewer and interpolated length.

With the viewer at infinity (``V`` fixed) a pixel's exact unit normal ``N̂`` is written in
polar coordinates about ``V``, ``N̂ = cos θ·V + sin θ·(cos φ·e1 + sin φ·e2)`` (``e1``,
``e2`` completing an orthonormal frame), and the interpolated, not yet normalized, normal of
Lyon's Figure 7a as ``N' = √z·N̂`` with ``z = |N'|²``.  The domain's normals
(``N̂·V >= view_cos_min``, ``|N'| >= min_normal_length``) are all inside
``θ ∈ [0, arccos(view_cos_min)]``, ``φ ∈ [0, 2π]``, ``z ∈ [min_normal_length², 1]``, which
:func:`cover` cuts into boxes; a box also carries one admissible ``n`` and its material.

Every projection a bound needs has the form ``W·N̂ = (W·V) cos θ + ρ sin θ cos(φ - ψ)``
(``ρ``, ``ψ`` the polar coordinates of ``W`` in the ``e1``, ``e2`` plane), and Phong's
``R̂·W = 2(N̂·V)(N̂·W) - V·W = (V·W) cos 2θ + ρ sin 2θ cos(φ - ψ)`` (Lyon 1993, Figure 2);
:func:`projection` evaluates them with interval arithmetic, cos and sin exact over an
interval (their extrema where the interval holds one), widened by ``1e-14`` for float64.
"""

from dataclasses import dataclass, field

import numpy as np

from .interval import least, most

__all__ = ["Boxes", "frame", "cover", "cos_range", "product", "projection"]

_SLACK = 1e-14


@dataclass
class Boxes:
    """``B`` boxes: ``theta``, ``phi``, ``z`` of shape (B, 2) (low, high), ``n`` and
    ``material`` of shape (B,); with point lights or a local viewer, optionally ``cells`` (B, 2,
    3): per box an axis-aligned box of the surface points (low and high corners,
    :mod:`.cells`), ``cell_scale`` ``(per_length, radius)``: the radians its half-diagonal turns
    their directions by at most, per unit of length, up to the domain ball's ``radius``."""

    theta: np.ndarray
    phi: np.ndarray
    z: np.ndarray
    n: np.ndarray
    material: np.ndarray
    cells: np.ndarray = None
    cell_scale: tuple = (0.0, np.inf)
    #: ``{scale: (cos, sin) ranges}`` made by :meth:`polar`, this set's own (not its halves')
    polar_ranges: dict = field(default_factory=dict, repr=False, compare=False)

    def __len__(self):
        return len(self.n)

    def polar(self, scale):
        """``(cos, sin)`` ranges (:func:`cos_range`) of ``scale·θ`` over each box: every
        :func:`projection` of these boxes shares them (one to six per box set, so kept here)."""
        if scale not in self.polar_ranges:
            theta = self.theta * scale
            self.polar_ranges[scale] = (cos_range(theta[:, 0], theta[:, 1]),
                                        cos_range(theta[:, 0] - np.pi / 2, theta[:, 1] - np.pi / 2))
        return self.polar_ranges[scale]

    def take(self, index):
        return Boxes(self.theta[index], self.phi[index], self.z[index], self.n[index], self.material[index],
                     None if self.cells is None else self.cells[index], self.cell_scale)

    def widths(self):
        """(B, 3) the extent of each box along θ, φ (as an arc at its widest) and z; (B, 4) with
        cells, the fourth the angle their half-diagonal turns a light's or the viewer's direction
        by (``cell_scale`` times it)."""
        arc = (self.phi[:, 1] - self.phi[:, 0]) * np.sin(np.minimum(self.theta[:, 1], np.pi / 2))
        sides = [self.theta[:, 1] - self.theta[:, 0], arc, self.z[:, 1] - self.z[:, 0]]
        if self.cells is not None:  # a cell's points are in the domain's ball too: no wider than it
            per_length, radius = self.cell_scale
            sides.append(per_length * np.minimum(np.linalg.norm(self.cells[:, 1] - self.cells[:, 0], axis=-1) / 2,
                                                 radius))
        return np.stack(sides, -1)

    def split(self):
        """Each box halved along its widest side (:meth:`widths`; a cell along its longest edge):
        twice as many boxes, the low halves first."""
        axis = np.argmax(self.widths(), axis=-1)
        parts = [self.theta, self.phi, self.z]
        low = [p.copy() for p in parts]
        high = [p.copy() for p in parts]
        for dim, p in enumerate(parts):
            cut = axis == dim
            mid = 0.5 * (p[cut, 0] + p[cut, 1])
            low[dim][cut, 1] = mid
            high[dim][cut, 0] = mid
        cells = None
        if self.cells is not None:
            below, above = self.cells.copy(), self.cells.copy()
            cut = np.flatnonzero(axis == 3)
            edge = np.argmax(self.cells[cut, 1] - self.cells[cut, 0], axis=-1)
            mid = 0.5 * (self.cells[cut, 0, edge] + self.cells[cut, 1, edge])
            below[cut, 1, edge] = mid
            above[cut, 0, edge] = mid
            cells = np.concatenate([below, above])
        return Boxes(*(np.concatenate([a, b]) for a, b in zip(low, high)),
                     np.concatenate([self.n, self.n]), np.concatenate([self.material, self.material]), cells,
                     self.cell_scale)

    @staticmethod
    def concat(a, b):
        """The boxes of ``a`` then those of ``b`` (both with cells or both without)."""
        cells = None if a.cells is None else np.concatenate([a.cells, b.cells])
        return Boxes(*(np.concatenate([getattr(a, f), getattr(b, f)]) for f in ("theta", "phi", "z", "n", "material")),
                     cells, a.cell_scale)


def frame(view):
    """``(V, e1, e2)``: the unit viewer direction (``view`` itself when it is unit to 1e-12, so
    that the hardware's code of it is the host's) and two unit vectors completing the frame."""
    v = np.asarray(view, dtype=np.float64)
    if abs(np.linalg.norm(v) - 1.0) > 1e-12:
        v = v / np.linalg.norm(v)
    helper = np.eye(3)[int(np.argmin(np.abs(v)))]
    e1 = np.cross(v, helper)
    e1 /= np.linalg.norm(e1)
    return v, e1, np.cross(v, e1)


def cover(view_cos_min, min_normal_length, cases, theta_cuts=12, phi_cuts=24, z_cuts=1, view_cos_max=1.0):
    """The boxes of the module docstring for every ``(n, material)`` of ``cases``; a region's
    normals with ``N̂·V <= view_cos_max`` start at ``θ = arccos(view_cos_max)``."""
    top = float(np.arccos(np.clip(view_cos_min, -1.0, 1.0)))
    z_lo = min(1.0, float(min_normal_length)) ** 2
    t = np.linspace(min(top, float(np.arccos(np.clip(view_cos_max, -1.0, 1.0)))), top, theta_cuts + 1)
    p = np.linspace(0.0, 2 * np.pi, phi_cuts + 1)
    zz = np.linspace(z_lo, 1.0, z_cuts + 1)
    grid = np.stack(np.meshgrid(np.arange(theta_cuts), np.arange(phi_cuts), np.arange(z_cuts), indexing="ij"),
                    -1).reshape(-1, 3)
    one = len(grid)
    theta = np.stack([t[grid[:, 0]], t[grid[:, 0] + 1]], -1)
    phi = np.stack([p[grid[:, 1]], p[grid[:, 1] + 1]], -1)
    z = np.stack([zz[grid[:, 2]], zz[grid[:, 2] + 1]], -1)
    count = len(cases)
    return Boxes(np.tile(theta, (count, 1)), np.tile(phi, (count, 1)), np.tile(z, (count, 1)),
                 np.repeat([n for n, _ in cases], one).astype(np.int64),
                 np.repeat([m for _, m in cases], one).astype(np.int64))


def cos_range(lo, hi):
    """Exact ``(min, max)`` of ``cos`` over ``[lo, hi]`` (arrays), widened for float64."""
    a, b = np.cos(lo), np.cos(hi)
    low, high = np.minimum(a, b), np.maximum(a, b)
    two_pi = 2 * np.pi
    has_max = np.floor(hi / two_pi) >= np.ceil(lo / two_pi)
    has_min = np.floor((hi - np.pi) / two_pi) >= np.ceil((lo - np.pi) / two_pi)
    return np.where(has_min, -1.0, low - _SLACK), np.where(has_max, 1.0, high + _SLACK)


def product(a, b):
    """Interval product of ``a = (lo, hi)`` and ``b``."""
    corners = (a[0] * b[0], a[0] * b[1], a[1] * b[0], a[1] * b[1])
    return least(corners) - _SLACK, most(corners) + _SLACK


def projection(boxes, basis, w, reflected=False):
    """``(lo, hi)`` of ``W·N̂`` over each box, or of ``R̂·W`` with ``reflected`` (``R̂`` the
    viewer reflected about ``N̂``); ``basis`` is :func:`frame`'s ``(V, e1, e2)``."""
    v, e1, e2 = basis
    w = np.asarray(w, dtype=np.float64)
    along, rho, psi = float(w @ v), float(np.hypot(w @ e1, w @ e2)), float(np.arctan2(w @ e2, w @ e1))
    c, s = boxes.polar(2.0 if reflected else 1.0)
    turn = cos_range(boxes.phi[:, 0] - psi, boxes.phi[:, 1] - psi)
    first = product((along, along), c)
    second = product(product((rho, rho), s), turn)
    return first[0] + second[0], first[1] + second[1]
