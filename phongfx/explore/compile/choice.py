"""The choice among the searched methods: the cheapest design whose witness meets the requirement.

:func:`choose` (:mod:`phongfx.compiler.compile`'s docstring): the feasible designs by
cost; the cheapest is searched for its worst input over the domain (its witness,
:mod:`phongfx.explore.compile.witness`); one over the requirement sends its method back to the
width search with hard points (the same search again: measured, or measured and certified,
:mod:`phongfx.explore.compile.certified`).
"""

from phongfx.core.words import levels

from . import run as runs
from . import witness as witnesses
from .architecture import design_block, eligible, rank_key
from .costing import TIE_MARGIN, tie
from .search import search_widths
from .workers import Pending

__all__ = ["ROUNDS", "METHOD_ROUNDS", "HARD_POINTS", "ranked", "begin_beside_witness", "for_chosen", "choose"]

#: At most this many rounds of hard points (a witness over the requirement) per compile,
#: and per method.
ROUNDS = 8
METHOD_ROUNDS = 3
#: Points a failed witness adds to the domain sample: itself and its neighbourhood.
HARD_POINTS = 2048

def _proven(scene, result, timeout, progress):
    """Whether ``result``'s design has no counterexample to its overflow claims (proven in
    turn, ``result["overflow_proof"]``)."""
    from phongfx.sim.prove import prove

    name = result["method"]
    proof = prove(design_block(result, scene.analysis), timeout=timeout,
                  progress=progress and (lambda text: progress(f"prove {name}: {text}")))
    result["overflow_proof"] = proof.as_dict()
    return not proof.counts.get("counterexample")


def ranked(results):
    """The feasible results that meet the speed and fit the part
    (:func:`~phongfx.explore.compile.architecture.eligible`) by cost; a synthesized design
    that misses its clock after those that meet it; an uncosted one (its synthesis failed) last."""
    feasible = [r for r in results.values() if r["feasible"] and eligible(r["cost"])]
    return sorted(feasible, key=lambda r: rank_key(r["cost"]))


def begin_beside_witness(out, work, fork):
    """``(method, params, Pending)``: ``work(result)`` for the cheapest ranked design
    (:func:`ranked`), begun in a forked process (``fork``) while its witness is searched: a
    certified design's witness cannot miss, so it is most often the one chosen and its work is
    then done when asked for (:func:`for_chosen`); None when nothing is ranked."""
    first = next(iter(ranked(out.results)), None)
    if first is None:
        return None
    first = {**first, "params": dict(first["params"])}  # as it is now, whenever the work runs
    return first["method"], dict(first["params"]), Pending(work, first, fork)


def for_chosen(out, begun):
    """Whether ``begun`` (:func:`begin_beside_witness`'s, or None) is the chosen design's work."""
    return begun is not None and out.best is not None and begun[:2] == (out.chosen, out.best["params"])


def _witness(scene, name, params, domain, progress, quick):
    """``(witness, hard points)`` of ``name`` at ``params``: with ``quick``, first a local search
    from the width search's own worst domain points, of its own seed (a miss there needs no
    fresh sample), then the full search (:func:`phongfx.explore.compile.witness.explore`)."""
    spec, analysis = scene.spec, scene.analysis
    if quick and runs.per_pixel(name):
        starts = scene.points.worst(name, runs.build(name, params, analysis), params, witnesses.STARTS)
        found, hard = witnesses.explore(name, params, spec, domain, starts=starts, analysis=analysis,
                                        hard=HARD_POINTS)
        if found["error_levels"] > spec.requirement.max_error_levels:
            return found, hard
    return witnesses.explore(name, params, spec, domain, progress=progress, analysis=analysis, hard=HARD_POINTS)


def choose(out, scene, cost, prove, prove_timeout, progress, search=None):
    """The cheapest feasible design whose witness meets the requirement (module docstring)
    and, with ``prove``, without a counterexample to its overflow claims; ``search(name)``
    searches a method's widths again once hard points are added, as ``(result, why)`` (default
    :func:`~phongfx.explore.compile.search.search_widths`'s, with no why; the certified
    search's own)."""
    if search is None:
        def search(name):
            return search_widths(scene, name, progress), None
    spec, domain = out.spec, out.domain
    required = spec.requirement.max_error_levels
    queue = ranked(out.results)
    while queue:
        r = queue[0]
        name = r["method"]
        # a certified design's witness cannot miss the requirement its certificate meets: the quick
        # search, there to spare a fresh sample when it misses, would only cost its time
        found, hard = _witness(scene, name, r["params"], domain, progress, quick=not out.certified)
        r["witness"] = found
        if found["error_levels"] <= required:
            if prove and not _proven(scene, r, prove_timeout, progress):
                r["why_not_chosen"] = "a counterexample to its overflow claims"
                queue.pop(0)
                continue
            out.chosen, out.witness, out.tie = name, found, tie(queue, TIE_MARGIN)
            return
        queue.pop(0)
        step = {"method": name, "params": r["params"], "witness_levels": found["error_levels"],
                "witness_unrounded": found["unrounded"]}
        searched = [s["method"] for s in out.rounds if s["action"] == "searched again"]
        mine = searched.count(name)
        if not runs.per_pixel(name) or len(searched) >= ROUNDS or mine >= METHOD_ROUNDS:
            r["why_not_chosen"] = (f"its witness is {levels(found['error_levels'])} over the domain "
                                   f"(requirement {required:g}); "
                                   + ("a unit fed per span takes no hard points" if not runs.per_pixel(name)
                                      else f"after {mine} rounds of hard points"))
            out.rounds.append({**step, "action": "not chosen"})
            continue
        scene.add_hard(hard)
        if progress:
            progress(f"{name}: witness {levels(found['error_levels'])}; searched again with "
                     f"{scene.points.hard_points} hard points")
        again, _ = search(name)  # certifiable before: the same method still is
        again["default"]["cost"] = r["default"]["cost"]  # the same widths: the same cost
        if again["feasible"]:
            again["cost"] = cost(name, again["params"], True)
        again["superseded"] = {k: r.get(k) for k in ("params", "max", "cost", "witness")}
        out.results[name] = again
        out.rounds.append({**step, "action": "searched again", "hard_points": scene.points.hard_points,
                           "params_after": again.get("params"), "feasible_after": again["feasible"],
                           "max_after": again["max"]})
        queue = [x for x in ranked(out.results) if x is again or any(x is y for y in queue)]
