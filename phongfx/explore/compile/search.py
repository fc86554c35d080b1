"""The width search of one method: the lowest widths whose error still meets the scene's requirement.

:func:`search_widths` (the steps are those of :mod:`phongfx.compiler.compile`'s
docstring): from the method's default widths, or from the widest (:func:`widest`), lower
each width by binary search (after the first pass, only when one lower passes) while a width
point ``passes`` (its error measured by
:class:`~phongfx.explore.compile.measure.SceneEval` meets the requirement, or for a
certified choice its certificate does, :mod:`.certified`), until no single width can drop; then the proof of local
minimality, one lower for every width.  :func:`search_all` searches several methods, each
in a worker process of its own when the domain sample is large (:mod:`.workers`).
"""

from phongfx.core.methods import METHODS

from . import run as runs
from .infeasible import summary
from .workers import MIN_POINTS, count, fork_map, step_aside

__all__ = ["width_params", "widest", "search_widths", "MeasuredTest", "search_all"]

_FIXED = ("n", "k", "lights")


def width_params(method, against="phong"):
    """``{name: (default, (lo, hi))}`` of the widths the search lowers; against ``"phong"``
    Lyon's datapaths add the shape function's ``k`` (its range up to
    :data:`~phongfx.config.shape.K_MAX`; against ``"self"`` it stays at the default, as it
    defines the reference)."""
    spec = METHODS[method]
    out = {k: (v, spec.ranges[k]) for k, v in spec.params.items() if k not in _FIXED}
    out.update(runs.extra(method))
    if against == "phong" and runs.is_datapath(method) and "k" in spec.params:
        out["k"] = (spec.params["k"], spec.ranges["k"])
    return out


class MeasuredTest:
    """``test(params)``: whether ``method`` at ``params`` meets the requirement as measured
    (frames and domain, :meth:`~phongfx.explore.compile.measure.SceneEval.passes`);
    ``test.failure(params)``: what the proof of minimality says of a point it failed, its error
    measured on the whole sample (``max_error``, and ``why`` when it cannot be built or
    overflows); ``test.margin(params)``: how far under the requirement a point it passed
    stayed, None here.  :func:`search_widths` asks any test these questions (``margin`` only
    where it has one)."""

    def __init__(self, scene, method):
        self.scene, self.method = scene, method

    def __call__(self, params):
        return self.scene.passes(self.method, params)

    def margin(self, params):
        """None: a measured error is a whole number of levels, which says nothing of how near
        the requirement a point that met it is."""
        return None

    def failure(self, params):
        measured = self.scene.error(self.method, params)
        return {"max_error": measured["max"], **({"why": measured["why"]} if "why" in measured else {})}


def _lowest(passes, params, name, lo):
    """Lowest value of ``name`` in ``lo..params[name]`` that ``passes``: a binary search, but one
    under the lowest value passed so far first where the test's margins say it likely fails
    (:func:`_at_edge`)."""
    good, bad = params[name], lo - 1
    while good - bad > 1:
        mid = good - 1 if _at_edge(passes, params, name, good) else (good + bad) // 2
        if passes({**params, name: mid}):
            good = mid
        else:
            bad = mid
    return good


def _at_edge(passes, params, name, good):
    """Whether ``name`` one under ``good``, lower than its start ``params[name]``, likely fails by
    the test's ``margin`` (how far under the requirement a point it passed stayed; None when it
    cannot say).  Lowering ``name`` from its start to ``good`` spent some of the start's margin;
    a bit less doubles that width's rounding step, so one lower spends about as much again: it
    is tried first when the margin left is under twice what was spent.  The result is the
    binary search's wherever every value under a failing one fails too; only the order of the
    questions changes (on Lyon's spheres, ``shape_t_frac`` passed at 13 by 0.0016 levels, and
    the binary search then failed at 8, 10, 11 and 12, 9 s of certificates)."""
    margin = getattr(passes, "margin", None)
    if margin is None or good >= params[name]:
        return False
    start, now = margin(params), margin({**params, name: good})
    if start is None or now is None:
        return False
    spent = start - now
    return spent > 0 and now < 2 * spent


def _lower_passes(passes, params, name, lo):
    """Whether ``name`` one lower (not under ``lo``) passes."""
    return params[name] > lo and passes({**params, name: params[name] - 1})


def widest(scene, method, widths):
    """The fallback start: every width at its range maximum, and the shape function's ``k``
    (when searched) at the value of its range with the lowest error there, since ``f_k`` is
    Phong's power only where ``2^k = n`` (a larger k is not closer).  Returns the params
    and ``{k: error}`` of the scan (empty without ``k``)."""
    top = {k: r[1] for k, (_, r) in widths.items()}
    if "k" not in widths:
        return top, {}
    lo, hi = widths["k"][1]
    scan = {k: scene.error(method, {**top, "k": k}) for k in range(lo, hi + 1)}
    return {**top, "k": min(scan, key=lambda k: (scan[k]["max"], scan[k]["mean"], k))}, scan


def search_widths(scene, method, progress=None, passes=None):
    """The width search of the module docstring; returns a result dict (an infeasible
    method's is :func:`~phongfx.explore.compile.infeasible.summary`).  ``passes(params)``:
    whether a width point is good enough, and ``passes.failure(params)`` what the proof of
    minimality says of one that is not (default: :class:`MeasuredTest`, its measured error;
    :func:`~phongfx.compiler.compile.compile_scene`'s ``certify="search"`` asks for a certificate,
    :class:`~phongfx.explore.compile.certified.CertifiedTest`)."""
    if passes is None:
        passes = MeasuredTest(scene, method)
    widths = width_params(method, scene.spec.requirement.against)
    default = {k: v for k, (v, _) in widths.items()}
    # measured whole first: the result quotes the defaults' numbers, which passes() alone may not measure
    result = {"method": method, "default": {"params": default, **scene.measured(method, default)}}
    start, scan = (default, {}) if passes(default) else widest(scene, method, widths)
    if not passes(start):
        step_aside()  # infeasible: its summary and price are not likely to be what the compile waits for
        return {**result, **summary(scene, method, start, scan)}
    params, changed, first = dict(start), True, True
    while changed:
        changed = False
        for name, (_, (lo, _hi)) in widths.items():
            # after the first pass the widths sit near their lowest: one lower first, which
            # fails where a binary search from ``lo`` would fail twice or more on the way
            value = _lowest(passes, params, name, lo) if first or _lower_passes(passes, params, name, lo) \
                else params[name]
            if value < params[name]:
                params[name], changed = value, True
            if progress:
                progress(f"{method} {name}={params[name]}")
        first = False
        if not changed:  # the proof pass: one lower must fail for every width
            proof = {}
            for name, (_, (lo, _hi)) in widths.items():
                if params[name] <= lo:
                    proof[name] = {"value": params[name], "lower": None, "why": "at range minimum"}
                    continue
                lower = {**params, name: params[name] - 1}
                if passes(lower):
                    params, changed = lower, True
                    break
                proof[name] = {"value": params[name], "lower": params[name] - 1, **passes.failure(lower)}
    return {**result, "feasible": True, "params": params, **scene.measured(method, params), "proof": proof}


def search_all(scene, methods, progress=None, workers=None, search=None):
    """``{method: (result, why)}`` for each of ``methods``, in order, where ``search(method)``
    gives ``(result, why)`` (default: ``(search_widths(scene, method, progress), None)``; the
    certified search gives ``(None, why)`` for a method it cannot certify).  On a domain
    sample of :data:`~.workers.MIN_POINTS` points or more, the methods are searched by forked
    workers (:func:`~.workers.fork_map`, ``workers``; by default one per method, at least one
    more than the cores),
    whose measured points join ``scene``'s
    cache and journal as if measured here: the same results."""
    if search is None:
        def search(method):
            return search_widths(scene, method, progress), None

    def one(method):
        before, failed, journal = set(scene.cache), set(scene.failed), scene.journal
        scene.journal = None  # journalled by the caller of the worker, with what it returns
        try:
            result = search(method)
        finally:
            scene.journal = journal
        return result, {k: v for k, v in scene.cache.items() if k not in before}, scene.failed - failed

    out = {}
    if scene.points is None or scene.points.count < MIN_POINTS or count(workers) == 1:
        for method in methods:
            out[method] = search(method)
            if progress:
                progress(f"{method} searched")
        return out
    # a worker per method, and at least one more than the cores: the searches are of unequal
    # length and which is long is not known before, so all run at once and the cores share them
    # until the long ones run alone (with a worker per core, the last left alone idled a core for
    # its whole tail: two-lights 15 of 58 s; with one more than the cores, three methods queued
    # behind each other while the long one waited: two-lights 82 s, Lyon's spheres 92 s, against
    # 77 s and 84 s with a worker each, 1.4 GB at most for six)
    spare = max(count(workers) + 1, len(methods)) if workers is None else workers
    for method, (result, measured, failed) in zip(methods, fork_map(one, methods, spare)):
        scene.merge(measured, failed)
        out[method] = result
        if progress:
            progress(f"{method} searched")
    return out
