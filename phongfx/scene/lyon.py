"""Lyon's test scene (1993, appendix ``specular.m``): shiny unit spheres in a row.

Spheres of radius ``radius`` pixels, one per shininess ``n``, each offset one radius
to the right of the previous one and hidden behind it where they overlap (the
appendix code takes the first sphere found); viewer at (0, 0, 1), lights at
infinity along [1, 1, -1] and [1, -1, 1].  Pixel ``(i, j)`` samples the point
``((0.5 + i)/radius, (0.5 + j)/radius)`` as in the appendix, with ``j`` up.

Two ways to feed the datapath:

* exact per-pixel normals (``span=0``, as Lyon did): ``N0 = N1 =`` the normal, ``a = 0``;
* span-interpolated normals (``span=S``): each sphere's run of pixels on a scanline is
  cut into spans of ``S`` pixels; exact unit normals at the span ends, ``a`` the
  pixel's position in its span, so the LIRP and the normalizer do real work.
"""

from dataclasses import dataclass

import numpy as np

__all__ = ["Scene", "Pixels", "pixels"]


@dataclass(frozen=True)
class Scene:
    radius: int = 64
    shininess: tuple = (1, 4, 16, 64, 256)
    lights: tuple = ((1.0, 1.0, -1.0), (1.0, -1.0, 1.0))
    viewer: tuple = (0.0, 0.0, 1.0)
    span: int = 0

    def __post_init__(self):
        if not isinstance(self.radius, int) or not 4 <= self.radius <= 4096:
            raise ValueError(f"radius must be an integer in 4..4096, not {self.radius!r}")
        if not isinstance(self.span, int) or not 0 <= self.span <= 2048:
            raise ValueError(f"span must be an integer in 0..2048 (0: exact normals), not {self.span!r}")
        if not self.shininess or any(not isinstance(n, int) or n < 1 for n in self.shininess):
            raise ValueError(f"shininess must be positive integers, not {self.shininess!r}")

    @property
    def width(self):
        return self.radius * (len(self.shininess) + 1) + 1

    @property
    def height(self):
        return 2 * self.radius + 1

    def unit_lights(self):
        lights = np.array(self.lights, dtype=np.float64)
        return lights / np.linalg.norm(lights, axis=-1, keepdims=True)

    def unit_viewer(self):
        v = np.array(self.viewer, dtype=np.float64)
        return v / np.linalg.norm(v)


@dataclass
class Pixels:
    """The scene's covered pixels, in scanline order."""

    row: np.ndarray      # image row (0 at the top)
    col: np.ndarray      # image column
    sphere: np.ndarray   # index into scene.shininess
    n: np.ndarray        # shininess per pixel
    normal: np.ndarray   # exact unit normal at the pixel (float, (P, 3))
    n0: np.ndarray       # span-start normal (float, (P, 3))
    n1: np.ndarray       # span-end normal
    a: np.ndarray        # position in the span, 0..1

    def __len__(self):
        return len(self.row)


def _normal(x, y):
    return np.stack([x, y, np.sqrt(np.maximum(1 - x * x - y * y, 0))], axis=-1)


def pixels(scene):
    """Covered pixels of ``scene`` with their normals (exact or span end) and shininess."""
    m = scene.radius
    i = np.arange(-m, m * len(scene.shininess) + 1)
    j = np.arange(m, -m - 1, -1)  # top row first, y up
    xx, yy = np.meshgrid((0.5 + i) / m, (0.5 + j) / m)
    sphere = np.full(xx.shape, -1)
    for index in range(len(scene.shininess)):
        x = xx - index
        inside = (sphere < 0) & (1 - x * x - yy * yy >= 0)
        sphere[inside] = index
    row, col = np.nonzero(sphere >= 0)
    s = sphere[row, col]
    x, y = xx[row, col] - s, yy[row, col]
    normal = _normal(x, y)
    if scene.span == 0:
        a = np.zeros(len(row))
        return Pixels(row, col, s, np.array(scene.shininess)[s], normal, normal, normal, a)

    # the run of each sphere on each row is contiguous; cut it into spans
    key = row * len(scene.shininess) + s
    starts = np.r_[0, np.nonzero(np.diff(key) | (np.diff(col) != 1))[0] + 1]
    run_start = np.repeat(col[starts], np.diff(np.r_[starts, len(col)]))
    run_end = np.repeat(col[np.r_[starts[1:], len(col)] - 1], np.diff(np.r_[starts, len(col)]))
    p0 = run_start + (col - run_start) // scene.span * scene.span
    p1 = np.minimum(p0 + scene.span, run_end)
    length = p1 - p0
    a = np.where(length > 0, (col - p0) / np.maximum(length, 1), 0.0)
    xs0, xs1 = (0.5 + p0 - m) / m - s, (0.5 + p1 - m) / m - s
    return Pixels(row, col, s, np.array(scene.shininess)[s], normal,
                  _normal(xs0, y), _normal(xs1, y), a)
