"""The sample of a scene's input domain that the compiler measures every width point on.

:class:`DomainPoints` draws ``count`` points of a :class:`phongfx.scene.domain.Domain`
(:meth:`~phongfx.scene.domain.Domain.chunks`) once per compile, seeded, in the domain's
chunks (so that one golden evaluation and its temporaries stay well under a gigabyte
whatever the count), with true Phong's specular terms of each chunk computed
once; :meth:`DomainPoints.error` is the compiler's error
(:func:`~phongfx.explore.compile.measure.shade_points`) over all of them.  Hard points
(the neighbourhood of a witness that failed, :mod:`phongfx.explore.compile.witness`) are
added with :meth:`~DomainPoints.add_hard` and measured with the rest.  Each measurement
also hill-climbs from the sample's worst points (:func:`phongfx.explore.compile.climb.climb`):
the width search is held to the worst the witness search would find, not only to the
sample's.  Asked only whether a design stays within a ``limit`` (the width search's question),
a measurement stops at the first chunk past it, after first trying the worst points of the
method's earlier measurements (its *screen*): a narrower width fails, nearly always, where the
last one was worst.  While a core is idle (the last width search runs alone) a forked twin of
the process measures every other chunk (:class:`~.workers.Twin`): the same result.

A domain point is one pixel of a span of its own, which the units fed per pixel take as
they take a frame's.  A unit fed per *span* (the spherical unit's setup is per span and
its stream covers every span pixel, :attr:`phongfx.explore.compile.units.Hooks.per_pixel`
false) cannot take a span of one pixel: it is measured instead on frames of random poses
of the domain (:func:`pose_frames`, rasterized, real spans), until they hold ``count``
visible pixels, drawn on the first such measurement.
"""

import contextlib
import dataclasses
import hashlib

import numpy as np

from phongfx.scene.geometry import FrameGeometry, frames, rotation
from phongfx.scene.mesh import Mesh
from phongfx.scene.sampling import random_rotations

from . import run as runs
from .climb import climb, state_of
from .measure import phong_terms, point_errors, shade_points, worst_per_point
from .workers import fork_imap

__all__ = ["STARTS", "CLIMB_ROUNDS", "BATCH", "SCREENS", "OWN_FORMS", "DomainPoints", "worst_index", "take", "concat", "posed_frame",
           "pose_frames"]

#: How many of the sample's worst points the local search of each measurement starts from.
STARTS = 32
#: Rounds of that local search (each ``STARTS`` × :data:`BATCH` points), at most; fewer on a
#: small sample, so that it costs at most about a twentieth of the sample's evaluation.
CLIMB_ROUNDS = 20
BATCH = 32
#: How many sets of worst points of earlier measurements a method's screen keeps.
SCREENS = 8
#: Against ``"self"``: how many float forms' terms are kept per chunk of the sample.
OWN_FORMS = 6

#: Fields of a :class:`~phongfx.scene.geometry.FrameGeometry` indexed per light (lights, P, ...).
_PER_LIGHT = ("l0", "l1", "light")
#: Fields that are not per point.
_WHOLE = ("width", "height", "rgb", "spans", "frame", "bits")


def worst_index(levels, unrounded, count):
    """``np.lexsort((unrounded, levels))[-count:]`` (the ``count`` worst points by integer
    error, ties by the continuous one, then by index, in that order) without sorting every
    point: the points that can be among them are found by two partitions, and only they
    are sorted (in index order, so that the stable sort breaks ties as on all of them)."""
    levels, unrounded = np.asarray(levels), np.asarray(unrounded)
    size = len(levels)
    if size <= 4 * count or not np.isfinite(unrounded).all():
        return np.lexsort((unrounded, levels))[-count:]
    cut = np.partition(levels, size - count)[size - count]  # the count-th largest level
    above = np.flatnonzero(levels > cut)
    tied = np.flatnonzero(levels == cut)
    need = count - len(above)
    if len(tied) > need:  # of the tied, those at least the need-th largest continuous error
        values = unrounded[tied]
        tied = tied[values >= np.partition(values, len(values) - need)[len(values) - need]]
    chosen = np.union1d(above, tied)
    return chosen[np.lexsort((unrounded[chosen], levels[chosen]))[-count:]]


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
    """``[(rotation, frame)]`` of random poses of ``domain``
    (:func:`phongfx.scene.sampling.random_rotations`, :func:`posed_frame`) until they hold
    ``count`` visible pixels (at most ``count`` frames, as a frame may show nothing)."""
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
        for g in domain.chunks(self.count, self.seed):
            n = np.round(g.n).astype(np.int64)
            self.chunks.append((g, n, phong_terms(g, n)))
        self.hard = []        # FrameGeometry of hard points, as added
        self._poses = None    # frames of random poses, drawn when first needed
        self._screens = {}    # per method, the worst points of its latest measurements (module docstring)
        self._own = {}        # (chunk index, run.own_key) -> the method's own terms of the chunk ("self")

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

    def error(self, method, config, params, limit=None):
        """``{"max", "mean", "max_unrounded", "points", "climbed", "how"}`` of ``method`` at
        ``config`` over the sample (or, for a unit fed per span, the frames of random poses),
        and for a unit fed per pixel over a local search from the sample's :data:`STARTS`
        worst points (:func:`phongfx.explore.compile.climb.climb`, up to :data:`CLIMB_ROUNDS`
        rounds: a few percent of the sample's cost, and it finds the corners of the bad
        regions that a sample only brushes).

        ``limit``: ``(levels, unrounded)``; None as soon as some sample point's error is past
        either (module docstring), else the same dict as without it."""
        per_pixel = runs.per_pixel(method)
        parts = self.chunks if per_pixel else self.poses()
        against = self.spec.requirement.against
        if limit is not None and per_pixel and self.screened_out(method, config, params, limit):
            return None
        worst = worst_raw = total = 0.0
        points, kept = 0, []
        # closed at the first part past the limit: the twin's part in hand is not waited for
        with contextlib.closing(self._chunks(method, config, params, parts)) as measured:
            for chunk_worst, chunk_raw, chunk_total, count, chunk_kept in measured:
                worst = max(worst, chunk_worst)
                worst_raw = max(worst_raw, chunk_raw)
                total += chunk_total
                points += count
                if per_pixel:
                    kept.append(chunk_kept)
                if limit is not None and (worst > limit[0] or worst_raw > limit[1]):
                    if per_pixel:
                        self._screen(method, kept[-1])
                    return None
        out = {"max": worst, "mean": total / max(3 * points, 1), "max_unrounded": worst_raw, "points": points,
               "climbed": 0, "how": "domain points" if per_pixel else f"visible pixels of {len(parts)} random poses"}
        if not per_pixel:
            return out
        pool = concat(kept)
        self._screen(method, pool)

        def evaluate(g):
            return worst_per_point(method, config, params, against, g, np.round(g.n).astype(np.int64))

        e, u = evaluate(pool)
        top = np.lexsort((u, e))[-STARTS:]
        rounds = int(np.clip(points // (20 * STARTS * BATCH), 1, CLIMB_ROUNDS))
        best, _, climbed = climb(evaluate, state_of(take(pool, top), self.domain), self.domain, pool.rgb,
                                 pool.bits, np.random.default_rng([self.seed, 4]), rounds=rounds, batch=BATCH)
        out.update(climbed=climbed, how="domain points and a local search from the worst")
        if best[2] is not None:
            out.update(max=max(worst, float(best[0])), max_unrounded=max(worst_raw, best[1]))
        return out

    def _chunks(self, method, config, params, parts):
        """Per part of ``parts`` (the sample's chunks, or the random poses' frames), in order as
        the caller takes them, its ``(max levels, max unrounded, sum of levels, points, worst
        points)`` (the worst points only for a unit fed per pixel).  While a core is idle
        (:func:`~.workers.spare_core`: the last width search runs alone) a
        :class:`~.workers.Twin` of this process measures every other part
        (:func:`~.workers.fork_imap` inside a worker): the same parts, the same order."""
        per_pixel = runs.per_pixel(method)

        def measure(index):
            g, n, phong = parts[index]
            own = self._own_terms(index, method, config, params) if per_pixel else None
            codes, reference, _, _ = shade_points(method, config, params, self.spec.requirement.against, g, n,
                                                  phong, own)
            levels, raw = point_errors(codes, reference, g.bits)
            return (float(levels.max(initial=0)), float(raw.max(initial=0.0)), float(levels.sum()), len(g),
                    take(g, worst_index(levels.max(axis=-1), raw.max(axis=-1), STARTS)) if per_pixel else None)

        # one worker: this process, and a twin only where a core is spare
        return fork_imap(measure, range(len(parts)), 1)

    def _own_terms(self, index, method, config, params):
        """Against ``"self"``, the method's own terms of chunk ``index``, computed once per
        :func:`~phongfx.explore.compile.run.own_key` (at most :data:`OWN_FORMS` kept per
        chunk); None otherwise (:func:`shade_points` computes what it needs)."""
        if self.spec.requirement.against != "self":
            return None
        g, n, _ = self.chunks[index]
        key = runs.own_key(method, config, params, n)
        if key is None:
            return None
        memo = self._own.setdefault(index, {})
        if key not in memo:
            if len(memo) >= OWN_FORMS:
                memo.pop(next(iter(memo)))
            memo[key] = runs.own_specular(method, config, params, g, n)
        return memo[key]

    def _screen(self, method, g):
        """Keep the domain points ``g`` (worst of a measurement) in ``method``'s screen."""
        self._screens[method] = [*self._screens.get(method, ())[1 - SCREENS:], g]

    def screened_out(self, method, config, params, limit):
        """Whether a point of ``method``'s screen or a hard point is past ``limit`` (each a
        point of the sample: then so is the sample); a unit fed per pixel.  A screen that cannot be measured (an
        overflow) decides nothing: the sample's measurement says what it says."""
        parts = [(g, np.round(g.n).astype(np.int64), None) for g in self._screens.get(method, ())]
        parts += self.chunks[len(self.chunks) - len(self.hard):]
        against = self.spec.requirement.against
        try:
            for g, n, phong in parts:
                codes, reference, _, _ = shade_points(method, config, params, against, g, n, phong)
                levels, raw = point_errors(codes, reference, g.bits)
                if levels.max(initial=0) > limit[0] or raw.max(initial=0.0) > limit[1]:
                    return True
        except (ValueError, OverflowError):
            return False
        return False

    def worst(self, method, config, params, count):
        """The ``count`` worst points of the sample (hard points included) of ``method`` at
        ``config`` (a unit fed per pixel), by integer error, ties by the continuous one."""
        kept = []
        for index, (g, n, phong) in enumerate(self.chunks):
            own = self._own_terms(index, method, config, params)
            e, u = worst_per_point(method, config, params, self.spec.requirement.against, g, n, phong, own)
            kept.append(take(g, worst_index(e, u, count)))
        return concat(kept)
