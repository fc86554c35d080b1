"""A design's worst input over the scene's domain: the **witness**, and how to replay it.

:func:`search` measures a design (``method`` at ``params``) on ``samples`` fresh points of
the domain (:meth:`phongfx.scene.domain.Domain.chunks`, default ``final_samples``, with a
seed of its own, never the width search's), in chunks, keeping the :data:`STARTS` worst of
each; :func:`phongfx.explore.compile.highlight.scan` looks at the highlights' peaks of the
worst of those; from the :data:`STARTS` worst of both,
:func:`phongfx.explore.compile.climb.climb` hill-climbs the continuous error.  The witness
is the worst integer error found, ties broken by the continuous one, as a JSON-able dict::

    {"error_levels": int, "unrounded": float, "point": {the float inputs}, "codes": {port: raw},
     "outputs": {"r", "g", "b"}, "reference_levels": [r, g, b], "found_by": ..., "replay": ...}

``codes`` are what the core is fed (its input ports' raw integers), ``outputs`` what it
gives, ``reference_levels`` the displayed reference; :func:`replay` re-evaluates the point
through the golden model and says whether it gives the same.

A unit fed per span (the spherical unit) cannot take one point alone: its witness is the
worst visible pixel of frames of random poses (:func:`phongfx.explore.compile.points.pose_frames`),
without a local search; its ``point`` holds the pose and the pixel.
"""

import time

import numpy as np

from phongfx.golden.blend import blend
from phongfx.golden.fixed import Fixed
from phongfx.golden.shader import shader_terms
from phongfx.scene.geometry import FrameGeometry, frames, levels
from phongfx.scene.sampling import CHUNK

from . import run as runs
from .analysis import analyse
from .climb import climb, neighbourhood, points, state_of
from .highlight import scan
from .measure import point_errors, shade_points, worst_per_point
from .points import concat, pose_frames, posed_frame, take, worst_index
from .workers import MIN_POINTS, count, fork_imap

__all__ = ["STARTS", "SCAN_SHARE", "ROUNDS", "CLIMBS", "REPLAY", "SEED_OFFSET", "search", "explore",
           "climb_rounds", "replay", "geometry"]

#: How many of the worst sampled points the local search starts from.  Many starts on a
#: smaller fresh sample find more than few on a larger one: on the four example scenes' chosen
#: designs, 128 starts from 2,000,000 points found witnesses within 2 % of, or above, 32 starts
#: from 10,000,000 (local-mesh 0.776 against 0.742) in a third of the time.
STARTS = 128
#: The highlight scan (:mod:`.highlight`) draws this fraction of the fresh sample's count of
#: normals about the peaks of the sample's worst positions: on the example scenes' chosen
#: designs 250,000 of them beside 2,000,000 fresh points raised the witness from 0.776 to 0.820
#: levels (local mesh), 1.343 to 1.405 (torus), 1.397 to 1.399 (two lights), Lyon's the same,
#: for 0.3–1.5 s more (4.1–4.4 s without).
SCAN_SHARE = 8
#: Rounds of the local search, at most.
ROUNDS = 40
#: How many of the climbs (the worst where they ended) give hard points beside the witness.
CLIMBS = 7
#: How a compiled design's witness is replayed.
REPLAY = "phongfx certify DIR --replay"
#: The witness search's seed, when not given: the domain's, offset so that its points are
#: never the width search's.
SEED_OFFSET = 1_000_003


def _analysis(spec, analysis):
    return analyse(spec, frames(spec)) if analysis is None else analysis


def search(method, params, spec, domain, *, samples=None, seed=None, progress=None, analysis=None,
           rounds=None, workers=None):
    """The witness dict of ``method`` at ``params`` over ``domain`` (module docstring).

    :param samples: fresh domain points (default ``domain.final_samples``).
    :param seed: their seed (default the domain's plus :data:`SEED_OFFSET`).
    :param progress: called with a line per chunk (points done, points per second).
    :param analysis: the scene's :class:`~phongfx.explore.compile.analysis.Analysis`
        (computed from its frames when None).
    :param rounds: rounds of the local search (default :func:`climb_rounds`).
    :param workers: processes measuring the fresh points (:mod:`~phongfx.explore.compile.workers`;
        None: every core).
    """
    return explore(method, params, spec, domain, samples=samples, seed=seed, progress=progress,
                   analysis=analysis, rounds=rounds, workers=workers)[0]


def climb_rounds(samples):
    """Rounds of the local search after ``samples`` fresh points: :data:`ROUNDS` from a
    million points up (each round costs ``STARTS`` × 32 points), fewer for a small sample
    (a quick compile, a test), at least 2."""
    return int(np.clip(samples // (8 * STARTS * 32), 2, ROUNDS))


def explore(method, params, spec, domain, *, samples=None, seed=None, progress=None, analysis=None,
            rounds=None, starts=None, hard=0, workers=None):
    """:func:`search`, and with ``hard`` > 0 the hard points of what it found: ``(witness,
    hard points or None)``.  ``starts``: domain points (a
    :class:`~phongfx.scene.geometry.FrameGeometry`) to climb from instead of a fresh sample's
    worst (the width search's own worst, a quick check before a fresh sample).  ``workers``:
    processes measuring the fresh sample (:mod:`~phongfx.explore.compile.workers`; None: every core).

    The hard points are the worst point found and where the :data:`CLIMBS` worst climbs
    ended, each with its neighbourhood (:func:`phongfx.explore.compile.climb.neighbourhood`),
    ``hard`` points in all: what the width search must get right next.
    """
    samples = domain.final_samples if samples is None else samples
    if isinstance(samples, bool) or not isinstance(samples, (int, np.integer)) or samples < 1:
        raise ValueError(f"samples must be a positive integer, not {samples!r}")
    seed = domain.seed + SEED_OFFSET if seed is None else seed
    rounds = climb_rounds(samples) if rounds is None else rounds
    analysis = _analysis(spec, analysis)
    config = runs.build(method, params, analysis)
    against, start, bits = spec.requirement.against, time.perf_counter(), spec.output.bits
    if not runs.per_pixel(method):
        return _pose_search(method, config, params, spec, domain, samples, seed, start), None

    def evaluate(g):
        return worst_per_point(method, config, params, against, g, np.round(g.n).astype(np.int64))

    if starts is None:
        kept, done = [], 0
        for worst in _worst_of_chunks(domain, samples, seed, evaluate, workers):
            kept.append(worst.points)
            done += worst.count
            if progress:
                rate = done / max(time.perf_counter() - start, 1e-9)
                progress(f"witness {method}: {done:,} of {samples:,} domain points, {rate:,.0f} points/s")
        starts, source = concat(kept), f"{samples:,} fresh domain points, seed {seed}"
        sampled_count = len(starts)
        peaks, scanned = scan(evaluate, starts, domain, starts.rgb, bits, seed, STARTS, samples // SCAN_SHARE)
        if peaks is not None:
            starts = concat([starts, peaks])
            source += f", a highlight scan of {scanned:,}"
    else:
        source = f"the {len(starts):,} worst points of the width search's domain sample"
        sampled_count, scanned = len(starts), 0
    e, u = evaluate(starts)
    top = np.lexsort((u, e))[-STARTS:]
    first = np.lexsort((u[:sampled_count], e[:sampled_count]))[-1]
    sampled = (int(e[first]), float(u[first]))
    start_best = (int(e[top[-1]]), float(u[top[-1]]))
    best, ends, evaluated = climb(evaluate, state_of(take(starts, top), domain), domain, starts.rgb, bits,
                                  np.random.default_rng([seed, 2]), rounds=rounds)
    if progress:
        progress(f"witness {method}: local search, {evaluated:,} points")
    if best[2] is not None and best[:2] > start_best:
        g, found_by = points(best[2], domain, starts.rgb, bits), "local search"
    else:
        g, found_by = take(starts, top[-1:]), "sample" if top[-1] < sampled_count else "highlight scan"
    out = _witness(method, config, params, against, g, 0)
    out.update(found_by=f"{found_by} ({source}; hill-climbing from the {len(top)} worst, {evaluated:,} points)",
               sampled={"error_levels": sampled[0], "unrounded": sampled[1]},
               samples=samples, seed=seed, scan_points=scanned, local_points=evaluated,
               seconds=time.perf_counter() - start)
    if not hard:
        return out, None
    worst = np.argsort(ends[1])[-CLIMBS:]
    centres = [state_of(g, domain)] + [ends[2].rows([i]) for i in worst]
    rng = np.random.default_rng([seed, 3])
    each = max(hard // len(centres), 1)
    return out, concat([neighbourhood(c, domain, starts.rgb, bits, each, rng) for c in centres])


class _Worst:
    """The :data:`STARTS` worst points of a chunk (``points``) and how many it held (``count``)."""

    def __init__(self, points, count):
        self.points, self.count = points, count


def _worst_of_chunks(domain, samples, seed, evaluate, workers):
    """Per chunk of ``samples`` fresh points (:meth:`~phongfx.scene.domain.Domain.chunks`),
    in order, its :data:`STARTS` worst by ``evaluate``: from :data:`~.workers.MIN_POINTS`
    points on, the chunks drawn and measured by forked workers (each chunk from its own
    generator, :meth:`~phongfx.scene.domain.Domain.chunk`: the same points)."""
    def worst(g):
        e, u = evaluate(g)
        return _Worst(take(g, worst_index(e, u, STARTS)), len(g))

    if samples < MIN_POINTS or count(workers) == 1:
        return (worst(g) for g in domain.chunks(samples, seed))
    return fork_imap(lambda index: worst(domain.chunk(samples, seed, index)), range(-(-samples // CHUNK)), workers)


def _witness(method, config, params, against, g, index, point=None):
    """The witness dict of point ``index`` of ``g`` (module docstring)."""
    codes, reference, raw, out = shade_points(method, config, params, against, g,
                                              np.round(g.n).astype(np.int64))
    e, u = point_errors(codes, reference, g.bits)
    feed = index if runs.per_pixel(method) else _stream_index(g, index)
    return {"error_levels": int(e[index].max()), "unrounded": float(u[index].max()),
            "point": point or _point(g, index),
            "codes": {port: np.asarray(value)[feed].tolist() for port, value in raw.items()},
            "outputs": {name: int(np.asarray(out[name])[feed]) for name in "rgb"},
            "reference_levels": levels(reference[index], g.bits).tolist(), "replay": REPLAY}


def _stream_index(g, index):
    """The stream position of visible pixel ``index`` of a frame fed per span pixel."""
    return int(np.flatnonzero(g.spans.visible)[index])


def _point(g, index):
    """The float inputs of point ``index`` of ``g``."""
    def vec(x):
        return [float(v) for v in np.asarray(x)[index]]
    return {"n0": vec(g.n0), "n1": vec(g.n1), "a": float(g.a[index]), "n": float(g.n[index]),
            "material": int(g.material[index]), "position": vec(g.position),
            "l0": [vec(v) for v in g.l0], "l1": [vec(v) for v in g.l1], "light": [vec(v) for v in g.light],
            "v0": vec(g.v0), "v1": vec(g.v1), "viewer": vec(g.viewer)}


def _pose_search(method, config, params, spec, domain, samples, seed, start):
    """The witness of a unit fed per span: the worst visible pixel of random poses."""
    worst = None
    found = pose_frames(spec, domain, samples, seed)
    for index, (_, g) in enumerate(found):
        e, u = worst_per_point(method, config, params, spec.requirement.against, g, np.round(g.n).astype(np.int64))
        if len(e):
            pixel = int(np.lexsort((u, e))[-1])
            if worst is None or (e[pixel], u[pixel]) > worst[:2]:
                worst = (e[pixel], u[pixel], index, pixel)
    if worst is None:
        raise ValueError(f"{spec.name}: no random pose of the domain shows a pixel")
    (rotation, g), pixel = found[worst[2]], worst[3]
    out = _witness(method, config, params, spec.requirement.against, g, pixel,
                   {**_point(g, pixel), "pose": rotation.tolist(), "row": int(g.row[pixel]), "col": int(g.col[pixel])})
    out.update(found_by=f"random poses ({sum(len(f) for _, f in found):,} visible pixels of {len(found)} poses, "
                        f"seed {seed}); no local search: the unit is fed per span",
               samples=samples, seed=seed, local_points=0, seconds=time.perf_counter() - start)
    return out


def geometry(witness, spec):
    """The witness point as a :class:`~phongfx.scene.geometry.FrameGeometry` of one point."""
    p = witness["point"]
    m = list(spec.materials.values())[p["material"]]

    def one(x):
        return np.asarray([x], dtype=np.float64)
    a = np.asarray([p["a"]], dtype=np.float64)
    n0, n1 = one(p["n0"]), one(p["n1"])
    normal = (1 - a[:, None]) * n0 + a[:, None] * n1
    zero = np.zeros(1, dtype=np.int64)
    return FrameGeometry(0, 0, zero, zero, np.arange(1), a, n0, n1, normal / np.linalg.norm(normal),
                         one(p["position"]),
                         *(np.asarray(p[k], dtype=np.float64)[:, None] for k in ("l0", "l1", "light")),
                         one(p["v0"]), one(p["v1"]), one(p["viewer"]),
                         np.array([light.rgb for light in spec.lights], dtype=np.float64).reshape(-1, 3),
                         np.asarray([p["n"]], dtype=np.float64), one(m.kd), one(m.ks), one(m.ka), one(m.colour),
                         np.asarray([p["material"]], dtype=np.int64), None, -1, spec.output.bits)


def replay(witness, method, params, spec, *, analysis=None):
    """Re-evaluate ``witness`` (:func:`search`'s dict) of ``method`` at ``params`` through the
    golden model: from its float inputs (encoded afresh) and from its recorded ``codes``.

    :returns: ``{"error_levels", "unrounded", "codes", "outputs", "reference_levels",
        "codes_match", "outputs_match", "matches"}``: ``codes_match``, the inputs encode to the
        recorded codes; ``outputs_match``, the recorded codes give the recorded outputs;
        ``matches``, both and the same error.
    """
    config = runs.build(method, params, _analysis(spec, analysis))
    against = spec.requirement.against
    if "pose" in witness["point"]:
        return _replay_pose(witness, method, config, params, spec)
    g = geometry(witness, spec)
    fresh = _witness(method, config, params, against, g, 0, witness["point"])
    fixed = {name: Fixed(np.asarray(witness["codes"][name], dtype=np.int64).reshape((1,) + np.shape(
        witness["codes"][name])), fmt) for name, (fmt, _) in config.inputs.items()}
    given = {name: int(value.raw[0]) for name, value in blend(config.blend, **shader_terms(config, **fixed)).items()
             if name in "rgb"}
    return _verdict(witness, fresh, given)


def _replay_pose(witness, method, config, params, spec):
    p = witness["point"]
    g = posed_frame(spec, np.asarray(p["pose"], dtype=np.float64))
    pixel = int(np.flatnonzero((g.row == p["row"]) & (g.col == p["col"]))[0])
    fresh = _witness(method, config, params, spec.requirement.against, g, pixel, p)
    return _verdict(witness, fresh, fresh["outputs"])


def _verdict(witness, fresh, given):
    codes_match = fresh["codes"] == witness["codes"]
    outputs_match = given == witness["outputs"] and fresh["outputs"] == witness["outputs"]
    return {**{k: fresh[k] for k in ("error_levels", "unrounded", "codes", "outputs", "reference_levels")},
            "codes_match": codes_match, "outputs_match": outputs_match,
            "matches": codes_match and outputs_match and fresh["error_levels"] == witness["error_levels"]}
