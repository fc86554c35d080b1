"""The scene compiler: the cheapest datapath whose error a scene's viewer cannot see.

:func:`compile_scene` analyses the scene (:mod:`phongfx.explore.compile.analysis`), then for every
method of :data:`phongfx.explore.methods.METHODS` either records why it cannot represent the
scene (:func:`phongfx.explore.compile.run.rejection`) or searches its widths:

1. start from the method's default widths; if they miss the requirement, from every
   width at its range maximum and ``k`` at its best value there (:func:`widest`); if that
   misses too the method is infeasible, and
   :func:`~phongfx.explore.compile.infeasible.summary` reports its best measured point
   and why;
2. greedily lower each width (binary search, then verified) while the error stays within
   ``requirement.max_error_levels`` on every frame and on a seeded sample of the scene's
   input domain (:class:`~phongfx.explore.compile.measure.SceneEval`: the golden model of
   the whole shader, measured at its ``r``, ``g``, ``b`` outputs against the reference),
   on the domain with a guard (:func:`~phongfx.explore.compile.measure.meets`); passes repeat
   until no single width can drop;
3. the **proof** of local minimality: for each width, the config with that width one
   lower and its measured max error (above the requirement), or "at range minimum".

Widths are the method's :class:`~phongfx.explore.methods.MethodSpec` parameters except ``n``,
``k`` and ``lights``, plus, for Lyon's datapaths, the normalizers' ``order`` (2 = g2,
1 = g1: g1 vs g2 is measured like a width) and, against true Phong, the shape
function's ``k`` (fewer squarings is cheaper; ``2^k = n`` makes ``f_k`` Phong's power).

The choice: the feasible designs by cost; the cheapest is searched for its worst input over
the domain, ``final_samples`` fresh points and a local search from the worst
(:func:`phongfx.explore.compile.witness.search`): its **witness**.  A witness over the
requirement makes the design unfit as it is: the witness and its neighbourhood join the
domain sample as hard points (:meth:`~phongfx.explore.compile.measure.SceneEval.add_hard`),
that method's widths are searched again, and the designs re-ranked, for at most
:data:`ROUNDS` such rounds (:data:`METHOD_ROUNDS` per method; each recorded in
:attr:`Compiled.rounds`); a design whose witness still misses is not chosen.  A quick local
search from the width search's own worst points comes before each fresh sample.

Cost (to choose among methods), on the ``target`` asked for: on an FPGA LUT-eq (``LUT4 +
958·DSP``), on standard cells (``"asic"``) area in µm²; synthesized
(:func:`phongfx.explore.synth.fpga.synth`, cached) with ``synth=True``, else the tool-free
proxies :func:`phongfx.explore.synth.proxy.proxy_cost` (LUT-eq) and
:func:`phongfx.explore.synth.proxy.proxy_area` (µm², fitted to the standard-cell flow).
"""

import dataclasses
from dataclasses import dataclass, field

from phongfx.core.registry import get_block
from phongfx.explore.methods import METHODS
from phongfx.explore.progress import Candidates

from . import run as runs
from . import witness as witnesses
from .costing import COST_UNITS, TIE_MARGIN, costed, tie
from .infeasible import hint, summary
from .measure import SceneEval, meets
from .points import DomainPoints

__all__ = ["ROUNDS", "METHOD_ROUNDS", "HARD_POINTS", "Compiled", "compile_scene", "check_methods", "width_params",
           "widest",
           "search_widths", "scene_domain"]

#: At most this many rounds of hard points (a witness over the requirement) per compile,
#: and per method.
ROUNDS = 8
METHOD_ROUNDS = 3
#: Points a failed witness adds to the domain sample: itself and its neighbourhood.
HARD_POINTS = 2048

_FIXED = ("n", "k", "lights")


@dataclass
class Compiled:
    """What :func:`compile_scene` found; :mod:`phongfx.explore.compile.emit` writes it out."""

    spec: object
    analysis: object
    scene: object                       # SceneEval
    cost_model: str
    chosen: str = None                  # method name, None if nothing met the requirement
    results: dict = field(default_factory=dict)   # method -> search result dict
    rejected: dict = field(default_factory=dict)  # method -> reason
    hint: dict = None                   # nothing feasible: infeasible.hint's way forward
    tie: dict = None                    # the runner-up within TIE_MARGIN of the chosen cost
    domain: object = None               # phongfx.scene.domain.Domain the search measured on
    witness: dict = None                # the chosen design's worst input found (witness.search)
    certificate: object = None          # phongfx.certify's bound of the chosen design, when computed
    rounds: list = field(default_factory=list)  # each witness over the requirement and what it did

    @property
    def best(self):
        return self.results.get(self.chosen)


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


def _passes(scene, method, params):
    return meets(scene.error(method, params), scene.spec.requirement.max_error_levels)


def _lowest(scene, method, params, name, lo):
    """Lowest value of ``name`` in ``lo..params[name]`` that passes (binary search)."""
    good, bad = params[name], lo - 1
    while good - bad > 1:
        mid = (good + bad) // 2
        if _passes(scene, method, {**params, name: mid}):
            good = mid
        else:
            bad = mid
    return good


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


def search_widths(scene, method, progress=None):
    """The width search of the module docstring; returns a result dict (an infeasible
    method's is :func:`~phongfx.explore.compile.infeasible.summary`)."""
    widths = width_params(method, scene.spec.requirement.against)
    default = {k: v for k, (v, _) in widths.items()}
    start, scan = (default, {}) if _passes(scene, method, default) else widest(scene, method, widths)
    result = {"method": method, "default": {"params": default, **scene.measured(method, default)}}
    if not _passes(scene, method, start):
        return {**result, **summary(scene, method, start, scan)}
    params, changed = dict(start), True
    while changed:
        changed = False
        for name, (_, (lo, _hi)) in widths.items():
            value = _lowest(scene, method, params, name, lo)
            if value < params[name]:
                params[name], changed = value, True
            if progress:
                progress(f"{method} {name}={params[name]}")
        if not changed:  # the proof pass: one lower must fail for every width
            proof = {}
            for name, (_, (lo, _hi)) in widths.items():
                if params[name] <= lo:
                    proof[name] = {"value": params[name], "lower": None, "why": "at range minimum"}
                    continue
                lower = {**params, name: params[name] - 1}
                measured = scene.error(method, lower)
                if meets(measured, scene.spec.requirement.max_error_levels):
                    params, changed = lower, True
                    break
                proof[name] = {"value": params[name], "lower": params[name] - 1,
                               **{k: measured[k] for k in ("max", "why") if k in measured}}
                proof[name]["max_error"] = proof[name].pop("max")
    return {**result, "feasible": True, "params": params, **scene.measured(method, params), "proof": proof}


def check_methods(methods):
    """``methods`` as a list (all of :data:`~phongfx.explore.methods.METHODS` for None), each checked."""
    names = list(METHODS) if methods is None else list(methods)
    for name in names:
        if name not in METHODS:
            raise ValueError(f"method must be one of {', '.join(METHODS)}, not {name!r}")
    return names


def _proven(scene, result, timeout, progress):
    """Whether ``result``'s design has no counterexample to its overflow claims (proven in
    turn, ``result["overflow_proof"]``)."""
    from phongfx.sim.prove import prove

    name = result["method"]
    block = get_block(runs.block_name(name), config=runs.build(name, result["params"], scene.analysis))
    proof = prove(block, timeout=timeout, progress=progress and (lambda text: progress(f"prove {name}: {text}")))
    result["overflow_proof"] = proof.as_dict()
    return not proof.counts.get("counterexample")


def scene_domain(spec, geometries, samples=None, final_samples=None):
    """The :class:`~phongfx.scene.domain.Domain` of ``spec`` with its ``samples`` and
    ``final_samples`` replaced when given (positive integers, checked)."""
    from phongfx.scene.domain import domain

    for name, value in (("samples", samples), ("final_samples", final_samples)):
        if value is not None and (isinstance(value, bool) or not isinstance(value, int) or value < 1):
            raise ValueError(f"{name} must be a positive integer, not {value!r}")
    found = domain(spec, geometries)
    changes = {k: v for k, v in (("samples", samples), ("final_samples", final_samples)) if v is not None}
    return dataclasses.replace(found, **changes) if changes else found


def _ranked(results):
    """The feasible results by cost; an uncosted design (its synthesis failed) last."""
    feasible = [r for r in results.values() if r["feasible"]]
    return sorted(feasible, key=lambda r: (r["cost"]["cost"] is None, r["cost"]["cost"] or 0))


def _witness(scene, name, params, domain, progress):
    """``(witness, hard points)`` of ``name`` at ``params``: first a local search from the
    width search's own worst domain points, of its own seed (a miss there needs no fresh
    sample), then the full search (:func:`phongfx.explore.compile.witness.explore`)."""
    spec, analysis = scene.spec, scene.analysis
    if runs.per_pixel(name):
        starts = scene.points.worst(name, runs.build(name, params, analysis), params, witnesses.STARTS)
        quick, hard = witnesses.explore(name, params, spec, domain, starts=starts, analysis=analysis,
                                        hard=HARD_POINTS)
        if quick["error_levels"] > spec.requirement.max_error_levels:
            return quick, hard
    return witnesses.explore(name, params, spec, domain, progress=progress, analysis=analysis, hard=HARD_POINTS)


def _choose(out, scene, cost, prove, prove_timeout, progress):
    """The cheapest feasible design whose witness meets the requirement (module docstring)
    and, with ``prove``, without a counterexample to its overflow claims."""
    spec, domain = out.spec, out.domain
    required = spec.requirement.max_error_levels
    ranked = _ranked(out.results)
    while ranked:
        r = ranked[0]
        name = r["method"]
        found, hard = _witness(scene, name, r["params"], domain, progress)
        r["witness"] = found
        if found["error_levels"] <= required:
            if prove and not _proven(scene, r, prove_timeout, progress):
                r["why_not_chosen"] = "a counterexample to its overflow claims"
                ranked.pop(0)
                continue
            out.chosen, out.witness, out.tie = name, found, tie(ranked, TIE_MARGIN)
            return
        ranked.pop(0)
        step = {"method": name, "params": r["params"], "witness_levels": found["error_levels"],
                "witness_unrounded": found["unrounded"]}
        searched = [s["method"] for s in out.rounds if s["action"] == "searched again"]
        mine = searched.count(name)
        if not runs.per_pixel(name) or len(searched) >= ROUNDS or mine >= METHOD_ROUNDS:
            r["why_not_chosen"] = (f"its witness is {found['error_levels']} levels over the domain "
                                   f"(requirement {required:g}); "
                                   + ("a unit fed per span takes no hard points" if not runs.per_pixel(name)
                                      else f"after {mine} rounds of hard points"))
            out.rounds.append({**step, "action": "not chosen"})
            continue
        scene.add_hard(hard)
        if progress:
            progress(f"{name}: witness {found['error_levels']} levels; searched again with "
                     f"{scene.points.hard_points} hard points")
        again = search_widths(scene, name, progress)
        again["default"]["cost"] = r["default"]["cost"]  # the same widths: the same cost
        if again["feasible"]:
            again["cost"] = cost(name, again["params"], True)
        again["superseded"] = {k: r.get(k) for k in ("params", "max", "cost", "witness")}
        out.results[name] = again
        out.rounds.append({**step, "action": "searched again", "hard_points": scene.points.hard_points,
                           "params_after": again.get("params"), "feasible_after": again["feasible"],
                           "max_after": again["max"]})
        ranked = [x for x in _ranked(out.results) if x is again or any(x is y for y in ranked)]


def compile_scene(spec, *, methods=None, synth=False, target="ecp5", device=None, freq=150, seed=1,
                  progress=None, geometries=None, journal=None, prove=False, prove_timeout=600,
                  samples=None, final_samples=None):
    """Compile ``spec`` (a :class:`~phongfx.scene.file.SceneSpec`): see the module docstring.

    :param methods: keys of :data:`~phongfx.explore.methods.METHODS` to consider (default
        all).
    :param bool synth: cost by synthesis instead of the proxy.
    :param target: what the cost is measured on: ``"ecp5"`` (LUT-eq), ``"ice40"`` or
        ``"asic"`` (µm²); with ``device`` (the part, or the library on ``"asic"``, default
        ``osu018``), ``freq`` (the clock given to the tools, MHz) and ``seed`` (nextpnr's
        placement seed).
    :param progress: called with a short description of each step; each synthesis as
        "synthesizing candidate i of N (method, widths) T s" and its flow's stages.
    :param journal: a folder where every measured width point is kept, so that a rerun of
        the same scene (and code) skips them (:mod:`phongfx.explore.compile.journal`).
    :param prove: prove the chosen design's ``overflow="error"`` claims
        (:mod:`phongfx.sim.prove`, ``prove_timeout`` seconds per claim); a design with a
        counterexample is not chosen and the next cheapest is proven instead.
    :param samples: domain points per measured width point, instead of the scene's
        (``[domain] samples``); ``final_samples``: those of the witness search.
    :returns: a :class:`Compiled`.
    """
    names = check_methods(methods)
    if target not in COST_UNITS:
        raise ValueError(f"target must be one of {', '.join(COST_UNITS)}, not {target!r}")
    scene = SceneEval(spec, geometries, journal=journal)
    domain = scene_domain(spec, scene.geometries, samples, final_samples)
    if progress:
        progress(f"drawing {domain.samples:,} domain points")
    scene.measure_domain(DomainPoints(spec, domain))
    out = Compiled(spec, scene.analysis, scene, f"{target}-synth" if synth else f"{target}-proxy", domain=domain)
    for name in names:
        reason = runs.rejection(name, spec, scene.analysis, scene.geometries)
        if reason:
            out.rejected[name] = reason
            continue
        out.results[name] = search_widths(scene, name, progress)
        if progress:
            progress(f"{name} searched")
    # the default widths are costed always (the manifest's "saved against the defaults"),
    # the searched ones only when they meet the requirement; an infeasible method's
    # defaults by the proxy only, since its synthesis (minutes) cannot change the choice
    designs = [(name, where, synth and r["feasible"]) for name, r in out.results.items()
               for where in ((r["default"], r) if r["feasible"] else (r["default"],))]
    steps = Candidates(sum(by_synth for *_, by_synth in designs), progress or (lambda text: None))

    def cost(name, params, by_synth, stage=None):
        return costed(name, runs.build(name, params, scene.analysis), by_synth and synth,
                      target=target, device=device, freq=freq, seed=seed, progress=stage)

    for name, where, by_synth in designs:
        where["cost"] = cost(name, where["params"], by_synth, steps.next(name, where["params"]) if by_synth else None)
    _choose(out, scene, cost, prove, prove_timeout, progress)
    out.hint = hint(out)
    return out
