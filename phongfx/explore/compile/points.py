"""The sample of a scene's input domain that the compiler measures every width point on.

:class:`DomainPoints` draws ``count`` points of a :class:`phongfx.scene.domain.Domain`
(:meth:`~phongfx.scene.domain.Domain.sample`) once per compile, seeded, in chunks of
:data:`CHUNK` (so that one golden evaluation and its temporaries stay well under a
gigabyte whatever the count), with true Phong's specular terms of each chunk computed
once; :meth:`DomainPoints.error` is the compiler's error
(:func:`~phongfx.explore.compile.measure.shade_points`) over all of them.  Hard points
(the neighbourhood of a witness that failed, :mod:`phongfx.explore.compile.witness`) are
added with :meth:`~DomainPoints.add_hard` and measured with the rest.

A domain point is one pixel of a span of its own, which the units fed per pixel take as
they take a frame's.  A unit fed per *span* (the spherical unit's setup is per span and
its stream covers every span pixel, :attr:`phongfx.explore.compile.units.Hooks.per_pixel`
false) cannot take a span of one pixel: it is measured instead on frames of random poses
of the domain (:func:`pose_frames`, rasterized, real spans), until they hold ``count``
visible pixels, drawn on the first such measurement.
"""

import dataclasses
import hashlib

import numpy as np

from phongfx.scene.geometry import FrameGeometry, frames, rotation
from phongfx.scene.mesh import Mesh

from . import run as runs
from .measure import phong_terms, point_errors, shade_points

__all__ = ["CHUNK", "DomainPoints", "chunk_seeds", "take", "concat", "posed_frame", "pose_frames", "random_rotations"]

#: Domain points per golden evaluation.
CHUNK = 1 << 17

#: Fields of a :class:`~phongfx.scene.geometry.FrameGeometry` indexed per light (lights, P, ...).
_PER_LIGHT = ("l0", "l1", "light")
#: Fields that are not per point.
_WHOLE = ("width", "height", "rgb", "spans", "frame", "bits")


def chunk_seeds(seed, count, chunk=CHUNK):
    """``[(size, seed)]`` of the chunks of ``count`` points drawn with ``seed``: each chunk
    its own seed (:class:`numpy.random.SeedSequence` of ``(seed, index)``)."""
    sizes = [min(chunk, count - start) for start in range(0, count, chunk)]
    return [(size, int(np.random.SeedSequence([seed, index]).generate_state(1)[0]))
            for index, size in enumerate(sizes)]


def take(g, index):
    """The domain points ``index`` of ``g`` (a :class:`FrameGeometry` of domain points, one
    pixel per span) as one of their own."""
    index = np.asarray(index)
    fields = {}
    for f in dataclasses.fields(g):
        value = getattr(g, f.name)
        if f.name in _WHOLE:
            fields[f.name] = value
        elif f.name in _PER_LIGHT:
            fields[f.name] = np.ascontiguousarray(np.asarray(value)[:, index])
        else:
            fields[f.name] = np.ascontiguousarray(np.asarray(value)[index])
    fields["span"] = np.arange(len(index))
    return FrameGeometry(**fields)


def concat(parts):
    """One :class:`FrameGeometry` of the domain points of every one of ``parts``."""
    first, fields = parts[0], {}
    for f in dataclasses.fields(first):
        values = [np.asarray(getattr(p, f.name)) for p in parts]
        if f.name in _WHOLE:
            fields[f.name] = getattr(first, f.name)
        else:
            fields[f.name] = np.concatenate(values, axis=1 if f.name in _PER_LIGHT else 0)
    fields["span"] = np.arange(len(fields["a"]))
    return FrameGeometry(**fields)


def random_rotations(domain, count, rng):
    """``count`` rotation matrices of the domain's poses: about its ``axis`` by an angle in
    its ``degrees`` (``"motion"``), up to ``wobble_degrees`` about any axis (``"still"``),
    or any rotation (``"any"``, uniform: a random unit quaternion)."""
    out = []
    for _ in range(count):
        if domain.pose == "any":
            w, x, y, z = (q := rng.normal(size=4)) / np.linalg.norm(q)
            out.append(np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                                 [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                                 [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]))
        elif domain.pose == "still":
            out.append(rotation(rng.normal(size=3), rng.uniform(0, domain.wobble_degrees)))
        else:
            out.append(rotation(domain.axis, rng.uniform(*domain.degrees)))
    return out


def _posed(spec, r):
    """``spec`` with every object turned by the rotation ``r`` and one frame (no rotation of its own)."""
    objects = []
    for obj in spec.objects:
        p = obj.params
        mesh = p["mesh"]
        placed = mesh.vertices * p["scale"] + p["offset"]
        turned = Mesh(placed @ r.T, mesh.normals @ r.T, mesh.faces, mesh.polygons)
        objects.append(dataclasses.replace(obj, params={**p, "mesh": turned, "scale": 1.0, "offset": (0.0, 0.0, 0.0)}))
    return dataclasses.replace(spec, objects=tuple(objects),
                               frames=dataclasses.replace(spec.frames, count=1, degrees=0.0, camera_path=()))


def posed_frame(spec, r):
    """The frame (:class:`FrameGeometry`) of ``spec``'s objects turned by the rotation ``r``."""
    return frames(_posed(spec, r))[0]


def pose_frames(spec, domain, count, seed):
    """``[(rotation, frame)]`` of random poses of ``domain`` (:func:`random_rotations`,
    :func:`posed_frame`) until they hold ``count`` visible pixels (at most ``count`` frames,
    as a frame may show nothing)."""
    rng = np.random.default_rng([seed, 1])
    out, pixels = [], 0
    while pixels < count and len(out) < count:
        for r in random_rotations(domain, 16, rng):
            g = posed_frame(spec, r)
            out.append((r, g))
            pixels += len(g)
            if pixels >= count:
                break
    return out


class DomainPoints:
    """``count`` points of ``domain`` drawn with ``seed`` (module docstring); ``spec`` the
    scene (for the frames of random poses of the units fed per span)."""

    def __init__(self, spec, domain, count=None, seed=None):
        self.spec, self.domain = spec, domain
        self.count = domain.samples if count is None else count
        self.seed = domain.seed if seed is None else seed
        self.chunks = []
        for size, chunk_seed in chunk_seeds(self.seed, self.count):
            g = domain.sample(size, chunk_seed)
            n = np.round(g.n).astype(np.int64)
            self.chunks.append((g, n, phong_terms(g, n)))
        self.hard = []        # FrameGeometry of hard points, as added
        self._poses = None    # frames of random poses, drawn when first needed

    def key(self):
        """What the measured errors depend on beyond the frames: the domain, the count, the
        seed and every hard point (the journal's key, :func:`~phongfx.explore.compile.journal.scene_key`)."""
        h = hashlib.sha256(repr((self.domain.as_dict(), self.count, self.seed)).encode())
        for g in self.hard:
            for name in ("n0", "n1", "a", "position", "l0", "l1", "v0", "v1", "n", "material"):
                h.update(np.ascontiguousarray(getattr(g, name), dtype=np.float64).tobytes())
        return h.hexdigest()

    @property
    def hard_points(self):
        return sum(len(g) for g in self.hard)

    def add_hard(self, g):
        """Add the domain points ``g`` (a :class:`FrameGeometry`) to every later measurement."""
        n = np.round(g.n).astype(np.int64)
        self.hard.append(g)
        self.chunks.append((g, n, phong_terms(g, n)))

    def poses(self):
        """The frames of random poses the units fed per span are measured on (:func:`pose_frames`)."""
        if self._poses is None:
            found = pose_frames(self.spec, self.domain, self.count, self.seed)
            self._poses = [(g, np.round(g.n).astype(np.int64), phong_terms(g, np.round(g.n))) for _, g in found]
        return self._poses

    def error(self, method, config, params):
        """``{"max", "mean", "max_unrounded", "points", "how"}`` over the sample (or, for a
        unit fed per span, the frames of random poses) of ``method`` at ``config``."""
        per_pixel = runs.per_pixel(method)
        parts = self.chunks if per_pixel else self.poses()
        worst = worst_raw = total = 0.0
        points = 0
        for g, n, phong in parts:
            codes, reference, _, _ = shade_points(method, config, params, self.spec.requirement.against, g, n, phong)
            levels, raw = point_errors(codes, reference, g.bits)
            worst = max(worst, float(levels.max(initial=0)))
            worst_raw = max(worst_raw, float(raw.max(initial=0.0)))
            total += float(levels.sum())
            points += len(g)
        how = "domain points" if per_pixel else f"visible pixels of {len(parts)} random poses"
        return {"max": worst, "mean": total / max(3 * points, 1), "max_unrounded": worst_raw,
                "points": points, "how": how}
