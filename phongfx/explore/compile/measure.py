"""How the compiler measures one width point: on the scene's frames and on its input domain.

:class:`SceneEval` renders every frame once per shininess *variant*: one when every material
has a single ``n``, else three, with each range material at its ``n_lo``, its rounded
geometric mean and its ``n_hi``.  Every render goes through the golden model of the whole
shader (unit and hardware blend, :mod:`phongfx.golden.shader`), so the error is measured
at its ``r``, ``g``, ``b`` outputs (:func:`shade_points`): per pixel and channel
``|out - level(I_ref)|`` in display levels (:func:`~phongfx.scene.geometry.pixel_error`,
an integer: how far the displayed pixel is from the displayed reference), ``I_ref``
(:func:`phongfx.scene.geometry.shade`, the backside test included) from true Phong
(``"phong"``: ``(R·L)^n`` and ``N·L`` at Phong's normal (``FrameGeometry.normal``), and
the exact light and viewer of the pixel) or from the method's own float form
(``"self"``); max and mean over all visible pixels and channels of all renders, and
``max_unrounded`` against the reference before its rounding (``|out - I_ref·(2^bits -
1)|``, which the outputs' own rounding puts at 0.5 at best).

The frames are a handful of poses the scene was fitted to; a design tuned until it sits
at the requirement on them fails on the poses between (other angles, other axes).  With
a ``domain`` (:class:`phongfx.scene.domain.Domain`), the same error is measured on
:class:`~phongfx.explore.compile.points.DomainPoints` too, every input the hardware can
receive while the scene plays, and ``max`` (the search's criterion) is the larger of
``frames_max`` and ``domain_max``.  The domain is measured only where the frames meet
the requirement (elsewhere the point fails whatever the domain holds, and ``domain_max``
is None), or when asked (``complete``: an infeasible method's best point).

The width search asks only whether a point meets the requirement (:meth:`SceneEval.passes`):
a point the domain sample fails is measured only until some of its points fail (the worst
points of earlier measurements first, :meth:`~phongfx.explore.compile.points.DomainPoints.error`'s
``limit``), which is the same answer at a fraction of the cost; such a partial measurement is
not kept, so :meth:`SceneEval.error` measures the whole sample when its numbers are asked for.
"""

import math

import numpy as np

from phongfx.golden.reference import specular
from phongfx.golden.shader import shader_raw
from phongfx.scene.geometry import frames, pixel_error, shade, terminator_lit

from . import run as runs
from .analysis import analyse
from .journal import Journal, scene_key

__all__ = ["GUARD", "meets", "met_at", "SceneEval", "cosines", "diffuse", "phong_terms", "shade_points", "point_errors",
           "worst_per_point", "point_key"]


#: Levels of continuous error the width search keeps under the requirement on the domain (:func:`meets`).
GUARD = 0.1


def meets(error, required):
    """Whether a measured ``error`` (:meth:`SceneEval.error`) meets ``required`` levels: its
    ``max`` within it, and on the domain its continuous error ``domain_unrounded`` at least
    :data:`GUARD` under the ``required + 0.5`` the integer error allows.  The width search
    stops at the edge of what it measured; without the guard, a fresh witness search (more
    points, a longer local search) finds a point a hair past that edge almost every time,
    one round of hard points after another."""
    unrounded = error.get("domain_unrounded")
    return error["max"] <= required and (unrounded is None or unrounded <= required + 0.5 - GUARD)


def met_at(error):
    """The smallest whole requirement (levels) that :func:`meets` ``error``."""
    unrounded = error.get("domain_unrounded")
    return max(math.ceil(error["max"]), 0 if unrounded is None else math.ceil(unrounded - 0.5 + GUARD - 1e-12))


def cosines(g):
    """(lights, P) exact ``N·L`` at Phong's normal (the X, Y, Z products added in turn, as
    ``np.sum`` adds them, without its reduction's cost per row)."""
    products = g.normal * g.light
    return (products[..., 0] + products[..., 1]) + products[..., 2]


def diffuse(g):
    """(lights, P) exact ``max(N·L, 0)`` at Phong's normal: every method's diffuse reference."""
    return np.maximum(cosines(g), 0.0)


def phong_terms(g, n):
    """(lights, P) true Phong's specular terms ``(R·L)^n`` of the points ``g``."""
    return np.stack([specular("phong", g.normal, light, g.viewer, n) for light in g.light])


def shade_points(method, config, params, against, g, n, phong=None, own=None):
    """``(codes, I_ref, raw inputs, raw outputs)`` of the points ``g`` (a frame, or domain
    points) with per-point shininess ``n``: the shader's ``r``, ``g``, ``b`` codes (P, 3)
    and the float reference intensities (P, 3), whose backside test follows the shader's
    within the terminator band (:func:`~phongfx.scene.geometry.terminator_lit`).
    ``phong``: :func:`phong_terms` of ``g`` when already computed; ``own``: the method's own
    terms (:func:`~phongfx.explore.compile.run.own_specular`, against ``"self"``) when already computed."""
    raw = runs.frame_inputs(method, config, g, n)
    shaded = shader_raw(config, raw)  # chunk by chunk for a unit without state: faster, same codes
    out = {name: shaded[name] for name in "rgb"}
    codes = runs.frame_codes(method, out, g)
    lit = None
    if config.blend.diff:  # the shader's own backside test, per light, at the visible pixels
        lit = np.stack([runs.visible(method, shaded[f"diff{i}"] > 0, g) for i in range(config.blend.lights)])
    if against == "self":
        spec = runs.own_specular(method, config, params, g, n) if own is None else own
    else:
        spec = phong_terms(g, n) if phong is None else phong
    cosine = cosines(g)
    reference = shade(g, np.maximum(cosine, 0.0), spec, lit=terminator_lit(cosine, lit, g.bits))
    return codes, reference, raw, out


def point_errors(codes, reference, bits):
    """``(levels, unrounded)``, each (P, 3): :func:`~phongfx.scene.geometry.pixel_error`
    and ``|out - I_ref·(2^bits - 1)|``."""
    scale = (1 << bits) - 1
    return pixel_error(codes, reference, bits), np.abs(codes - reference * scale)


def worst_per_point(method, config, params, against, g, n, phong=None, own=None):
    """``(levels, unrounded)``, each (P,): :func:`point_errors` of :func:`shade_points`, the
    worst channel of each point (a unit fed per pixel: a frame's or domain points)."""
    codes, reference, _, _ = shade_points(method, config, params, against, g, n, phong, own)
    levels, raw = point_errors(codes, reference, g.bits)
    return levels.max(axis=-1), raw.max(axis=-1)


def point_key(method, params):
    """A width point's key in the cache, the journal, :attr:`SceneEval.failed` and the certified
    search's certificates."""
    return method, tuple(sorted(params.items()))


class SceneEval:
    """The scene's renders (frames × shininess variants) and their Phong references; with
    ``domain``, :class:`~phongfx.explore.compile.points.DomainPoints` of it (module docstring)."""

    def __init__(self, spec, geometries=None, journal=None):
        self.spec = spec
        self.geometries = frames(spec) if geometries is None else geometries
        if not any(len(g) for g in self.geometries):
            raise ValueError(f"{spec.name}: no object covers a pixel in any frame; nothing to compile")
        self.analysis = analyse(spec, self.geometries)
        self.bits = spec.output.bits
        #: per render of a frame, the n of each range material (empty: every n single)
        self.shininess_variants = []
        variants = self._variants()
        self.renders = [(g, n) for g in self.geometries for n in variants(g)]
        #: per render, the index of its shininess variant (0 when every n is single)
        self.variant_of = [i for g in self.geometries for i, _ in enumerate(variants(g))]
        #: per render, true Phong's (lights, P) specular terms (the diffuse is the same for all)
        self.reference = [phong_terms(g, n) for g, n in self.renders]
        #: the domain sample (:class:`~phongfx.explore.compile.points.DomainPoints`), or None
        self.points = None
        #: ``journal``: a folder where measured points are kept for a rerun (:mod:`.journal`)
        self.folder, self.journal, self.cache, self.resumed = journal, None, {}, 0
        #: keys of the points :meth:`passes` found failing on part of the domain sample (not in the cache)
        self.failed = set()
        self._open_journal()

    def measure_domain(self, points):
        """Measure every width point on the domain sample ``points`` too (a
        :class:`~phongfx.explore.compile.points.DomainPoints`): a journal of its own."""
        self.points = points
        self._open_journal()

    def _open_journal(self):
        """(Re)key the journal: the frames, and the domain sample with its hard points."""
        if self.folder is not None:
            extra = None if self.points is None else self.points.key()
            self.journal = Journal(self.folder, scene_key(self.spec, self.geometries, extra))
            loaded = self.journal.load()
        else:
            loaded = {}
        self.cache = {key: error for key, error in loaded.items() if not error.get("partial")}
        self.failed = {key for key, error in loaded.items() if error.get("partial")}
        self.resumed = len(loaded)

    @property
    def points_measured(self):
        """How many width points were measured, whole or (:meth:`passes`) until they failed."""
        return len(self.failed.union(self.cache))

    def add_hard(self, geometry):
        """Add hard points (a :class:`~phongfx.scene.geometry.FrameGeometry` of domain
        points) to the domain sample: every point is measured afresh from here on."""
        self.points.add_hard(geometry)
        self._open_journal()

    def _variants(self):
        """Per frame, the per-pixel n arrays of the shininess variants (module docstring)."""
        materials = list(self.spec.materials.values())
        ranged = [i for i, m in enumerate(materials) if m.n_lo is not None and m.n_lo != m.n_hi]

        names = list(self.spec.materials)
        picks = (lambda m: m.n_lo, lambda m: round(np.sqrt(m.n_lo * m.n_hi)), lambda m: m.n_hi)

        def variants(g):
            if not ranged:
                return [np.round(g.n).astype(np.int64)]
            out = []
            self.shininess_variants = [{names[i]: pick(materials[i]) for i in ranged} for pick in picks]
            for pick in picks:
                n = np.round(g.n).astype(np.int64)
                for i in ranged:
                    n[g.material == i] = pick(materials[i])
                out.append(n)
            return out
        return variants

    def render(self, method, config, params, index):
        """``(codes, I_ref, raw inputs, raw outputs)`` of render ``index`` (:func:`shade_points`)."""
        g, n = self.renders[index]
        return shade_points(method, config, params, self.spec.requirement.against, g, n, self.reference[index])

    def error(self, method, params, complete=False):
        """``{"max", "mean", "max_unrounded", "frames_max", "domain_max", "domain_unrounded",
        "domain_points", "domain_climbed"}`` error in levels of ``method`` at ``params``
        (cached; module docstring); a config that cannot be built or overflows has ``max =
        inf`` and says why in ``"why"``.  ``complete``: measure the domain even where the
        frames miss (an infeasible method's best point, which a hint quotes)."""
        key = point_key(method, params)
        cached = self.cache.get(key)
        if cached is None or (complete and self.points is not None and cached.get("domain_max") is None
                              and math.isfinite(cached["max"])):
            self.cache[key] = self._error(method, params, complete)
            self.failed.discard(key)  # measured whole now
            if self.journal is not None:
                self.journal.add(key, self.cache[key])
        return self.cache[key]

    def passes(self, method, params):
        """Whether ``method`` at ``params`` :func:`meets` the requirement: the answer of
        ``meets(self.error(method, params), ...)``, with a point that fails on the domain
        measured only until it does (module docstring)."""
        required = self.spec.requirement.max_error_levels
        key = point_key(method, params)
        if key in self.cache:
            return meets(self.cache[key], required)
        if key in self.failed:
            return False
        found = self._error(method, params, limit=(required, required + 0.5 - GUARD))
        if found is None:
            self._failed(key)
            return False
        self.cache[key] = found
        if self.journal is not None:
            self.journal.add(key, found)
        return meets(found, required)

    def merge(self, measured, failed):
        """Take width points measured elsewhere (another process's :attr:`cache` entries
        ``measured`` and :attr:`failed` keys ``failed``) as if measured here, journalled."""
        for key, error in measured.items():
            self.cache[key] = error
            if self.journal is not None:
                self.journal.add(key, error)
        for key in sorted(set(failed) - set(self.cache) - self.failed):
            self.failed.add(key)
            if self.journal is not None:
                self.journal.add(key, {"partial": True})

    def _frames(self, method, params):
        """``(config, error on the frames)`` of ``method`` at ``params``; ``(None, error)``
        with ``max = inf`` and ``"why"`` for a config that cannot be built or overflows."""
        inf = math.inf
        try:
            config = runs.build(method, params, self.analysis)
            renders = [self.render(method, config, params, i)[:2] for i in range(len(self.renders))]
        except (ValueError, OverflowError) as error:
            return None, {"max": inf, "mean": inf, "max_unrounded": inf, "why": str(error)}
        each = [point_errors(codes, ref, self.bits) for codes, ref in renders]
        e = np.concatenate([levels.ravel() for levels, _ in each])
        out = {"max": float(e.max(initial=0.0)), "mean": float(e.mean()) if e.size else 0.0,
               "max_unrounded": float(max(raw.max(initial=0.0) for _, raw in each)),
               "per_render": [float(levels.max(initial=0.0)) for levels, _ in each]}
        out["frames_max"] = out["max"]
        return config, out

    def fails_screen(self, method, params):
        """Whether ``method`` at ``params`` is past the requirement on the frames or on the
        domain sample's screen (:meth:`~phongfx.explore.compile.points.DomainPoints.screened_out`:
        the worst points of the method's earlier measurements, and the hard points): an
        integer error over it, or a continuous one of at least ``required + 1/2``, which no
        certificate of the requirement allows.  The certified search asks this before a
        certificate, in place of measuring the whole sample, which a sound certificate
        answers; a point found past it fails :meth:`passes` too, and is kept as failed."""
        required = self.spec.requirement.max_error_levels
        key = point_key(method, params)
        if key in self.cache:
            return self.cache[key]["max"] > required
        if key in self.failed:
            return True
        config, out = self._frames(method, params)
        past = out["max"] > required
        if not past and self.points is not None and runs.per_pixel(method):
            past = self.points.screened_out(method, config, params, (required, required + 0.5))
        if past:
            self._failed(key)
        return past

    def _failed(self, key):
        """Keep ``key`` as failing on part of the domain, journalled as such: a rerun knows it
        fails without measuring it."""
        self.failed.add(key)
        if self.journal is not None:
            self.journal.add(key, {"partial": True})

    def _error(self, method, params, complete=False, limit=None):
        """:meth:`error` measured; with ``limit``, None as soon as part of the domain sample
        is past it (:meth:`~phongfx.explore.compile.points.DomainPoints.error`)."""
        config, out = self._frames(method, params)
        if config is None or self.points is None:
            return out
        out.update(domain_max=None, domain_points=0)
        if out["max"] > self.spec.requirement.max_error_levels and not complete:
            return out  # fails on the frames: the domain cannot make it pass
        try:
            measured = self.points.error(method, config, params, limit)
        except (ValueError, OverflowError) as error:
            return {**out, "max": math.inf, "domain_max": math.inf, "why": f"on the domain: {error}"}
        if measured is None:
            return None
        out.update(domain_max=measured["max"], domain_mean=measured["mean"], domain_points=measured["points"],
                   domain_climbed=measured["climbed"], domain_unrounded=measured["max_unrounded"],
                   max=max(out["max"], measured["max"]),
                   max_unrounded=max(out["max_unrounded"], measured["max_unrounded"]))
        return out

    def measured(self, method, params, complete=False):
        """:meth:`error` without its per-render list: what a result and the manifest keep."""
        return {k: v for k, v in self.error(method, params, complete).items() if k != "per_render"}

    def form_error(self, method, params):
        """Max over every render of ``|I_form - I_ref|·(2^bits - 1)``: how far the method's
        own float form (at ``params``' ``k``) is from true Phong, before any rounding."""
        config = runs.build(method, params, self.analysis)
        scale, worst = (1 << self.bits) - 1, 0.0
        for (g, n), ref in zip(self.renders, self.reference):
            lit = terminator_lit(cosines(g), None, self.bits)
            own = runs.own_specular(method, config, params, g, n)
            diff = diffuse(g)
            worst = max(worst, float(np.max(np.abs(shade(g, diff, own, lit) - shade(g, diff, ref, lit)),
                                            initial=0.0)) * scale)
        return worst
