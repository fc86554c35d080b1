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
search from the width search's own worst points comes before each fresh sample (not in a
certified compile, where the witness cannot miss).

With ``certified`` (``phongfx compile``'s default) a width point must also meet the requirement
by its certificate, methods without a bounding method are rejected unsearched, and the chosen
design's full certificate is computed once (:mod:`phongfx.explore.compile.certified`).

Cost (to choose among methods), on the ``target`` asked for: on an FPGA LUT-eq (``LUT4 +
958·DSP``), on standard cells (``"asic"``) area in µm²; synthesized
(:func:`phongfx.explore.synth.fpga.synth`, cached) with ``synth=True``, else the tool-free
proxies :func:`phongfx.explore.synth.proxy.proxy_cost` (LUT-eq) and
:func:`phongfx.explore.synth.proxy.proxy_area` (µm², fitted to the standard-cell flow).
A design's cost is that of its cheapest architecture (pipeline depth, initiation interval,
shared inputs: :mod:`phongfx.explore.compile.architecture`) whose clock reaches ``clock``
and whose pixel rate meets the scene's ``requirement.mpixels_per_second`` and, on an FPGA,
that fits the part (:mod:`phongfx.explore.compile.fit`); the error does not depend on the
architecture, so the widths are searched once.  A design no architecture of which meets
the speed is not chosen; when none is, :attr:`Compiled.refused` says why and what the
fastest reaches.
"""

import dataclasses
from dataclasses import dataclass, field

from phongfx.explore.methods import METHODS

from . import run as runs
from .architecture import Speed, refusal
from .certified import begin_full_certificate, certified_search, full_certificate, refusal_lines
from .choice import HARD_POINTS, METHOD_ROUNDS, ROUNDS, begin_beside_witness, choose, for_chosen
from .costing import COST_UNITS, price_designs
from .infeasible import hint
from .measure import SceneEval, meets
from .points import DomainPoints
from .search import search_all, search_widths, widest, width_params
from .workers import MIN_POINTS, count

__all__ = ["ROUNDS", "METHOD_ROUNDS", "HARD_POINTS", "Compiled", "compile_scene", "check_methods", "width_params",
           "widest", "search_widths", "scene_domain", "meets"]

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
    certificate: object = None          # phongfx.certify's bound of the chosen design (certified search)
    certified: bool = False             # the search was certified (every width point bounded too)
    rounds: list = field(default_factory=list)  # each witness over the requirement and what it did
    speed: Speed = Speed()              # the pixel rate and clock asked
    refused: dict = None                # nothing chosen for speed or fit: refusal(...)

    @property
    def best(self):
        return self.results.get(self.chosen)


def _designs(name, result, synth):
    """``(where, design)`` per design of a searched method that is priced: the dict its cost goes
    in, and the design as :func:`~phongfx.explore.compile.costing.price_designs` takes it.  Its
    default widths always (the manifest's "saved against the defaults"), the searched ones when
    they meet the requirement; an infeasible method's defaults by the proxy only and at the
    default architecture, since neither its synthesis (minutes) nor its architecture can change
    the choice."""
    feasible = result["feasible"]
    return [(where, (name, where["params"], synth and feasible, not feasible))
            for where in ((result["default"], result) if feasible else (result["default"],))]


def check_methods(methods):
    """``methods`` as a list (all of :data:`~phongfx.explore.methods.METHODS` for None), each checked."""
    names = list(METHODS) if methods is None else list(methods)
    for name in names:
        if name not in METHODS:
            raise ValueError(f"method must be one of {', '.join(METHODS)}, not {name!r}")
    return names


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


def compile_scene(spec, *, methods=None, synth=False, target="ecp5", device=None, freq=150, seed=1,
                  progress=None, geometries=None, journal=None, prove=False, prove_timeout=600,
                  samples=None, final_samples=None, certifier=None, certified=False, clock=None,
                  scheduler=None, workers=None, prepare=None):
    """Compile ``spec`` (a :class:`~phongfx.scene.file.SceneSpec`): see the module docstring.

    :param methods: keys of :data:`~phongfx.explore.methods.METHODS` to consider (default
        all).
    :param bool synth: cost by synthesis instead of the proxy.
    :param target: what the cost is measured on: ``"ecp5"`` (LUT-eq), ``"ice40"`` or
        ``"asic"`` (µm²); with ``device`` (the part, or the library on ``"asic"``, default
        ``osu018``), ``freq`` (the clock given to the tools, MHz) and ``seed`` (nextpnr's
        placement seed).
    :param clock: the clock (MHz) the core will run at: the chosen architecture must reach it,
        its pixel rate is ``clock / interval``, and synthesis is given it instead of ``freq``;
        None: each design at its own Fmax.  The pixel rate asked is the scene's
        ``requirement.mpixels_per_second`` (:func:`phongfx.scene.file.with_throughput`).
    :param scheduler: where ``synth`` runs its candidates in parallel (a Dask scheduler
        address; None: a local cluster of ``workers`` processes).  ``workers`` also bounds
        the processes that search the methods' widths and the witness side by side
        (:mod:`~phongfx.explore.compile.workers`; None: every core, 1: this process alone).
    :param progress: called with a short description of each step; each synthesis as
        "candidate i of N (label): stage, T s".
    :param journal: a folder where every measured width point is kept, so that a rerun of
        the same scene (and code) skips them (:mod:`phongfx.explore.compile.journal`).
    :param prove: prove the chosen design's ``overflow="error"`` claims
        (:mod:`phongfx.sim.prove`, ``prove_timeout`` seconds per claim); a design with a
        counterexample is not chosen and the next cheapest is proven instead.
    :param samples: domain points per measured width point, instead of the scene's
        (``[domain] samples``); ``final_samples``: those of the witness search.
    :param certifier: ``certifier(method, params, spec, domain, early=False, analysis=None[, max_boxes])``
        gives a :class:`~phongfx.certify.certificate.Certificate` (:func:`phongfx.certify.certify`,
        which sits above this wing and is passed in; ``max_boxes=0`` asks whether the method is
        bounded at all, :func:`~phongfx.explore.compile.certified.certified_search`); without ``certified`` the chosen
        design's is kept in :attr:`Compiled.certificate`, changing nothing.
    :param certified: the certified search (:mod:`~phongfx.explore.compile.certified`; needs
        ``certifier``): each method certifiable on the scene is searched once with its
        certificate as a second test, the others are rejected with the certificate's why; the
        chosen design's full certificate is :attr:`Compiled.certificate`.  When no method has
        a certified design, nothing is chosen and :attr:`Compiled.refused` says why per method
        (``"why": "certificate"``).
    :param prepare: ``prepare(result, analysis)``, work the caller will need for the chosen
        design (``result`` a search result), begun for the likeliest choice in a forked process
        beside its witness search and waited for when that design is chosen (the command builds
        its RTL check's simulator: :func:`~phongfx.explore.compile.emit.prepare_check`).
    :returns: a :class:`Compiled`.
    """
    names = check_methods(methods)
    if target not in COST_UNITS:
        raise ValueError(f"target must be one of {', '.join(COST_UNITS)}, not {target!r}")
    if certified and certifier is None:
        raise ValueError("certified=True needs a certifier (phongfx.certify.certify)")
    speed = Speed(spec.requirement.mpixels_per_second, clock)  # checked before the minutes of search
    scene = SceneEval(spec, geometries, journal=journal)
    domain = scene_domain(spec, scene.geometries, samples, final_samples)
    if progress:
        progress(f"drawing {domain.samples:,} domain points")
    scene.measure_domain(DomainPoints(spec, domain))
    freq = clock or freq
    out = Compiled(spec, scene.analysis, scene, f"{target}-synth" if synth else f"{target}-proxy", domain=domain,
                   speed=speed, certified=certified)

    options = {"target": target, "device": device, "freq": freq, "seed": seed, "scheduler": scheduler,
               "workers": workers, "progress": progress}

    def search(name):
        found = ((search_widths(scene, name, progress), None) if not certified else
                 certified_search(scene, name, domain, certifier, progress))
        if found[0] is not None and not synth:
            # priced by the proxies where it was searched (their per-user cache keeps them), while
            # another method's search may still run: the pricing of every design below reads them back
            price_designs([d for _, d in _designs(name, found[0], False)], scene.analysis, speed,
                          **{**options, "progress": None, "workers": 1})
        return found

    searched = []
    for name in names:
        reason = runs.rejection(name, spec, scene.analysis, scene.geometries)
        if reason:
            out.rejected[name] = reason
        else:
            searched.append(name)
    for name, (result, why) in search_all(scene, searched, progress, workers, search).items():
        if why:
            out.rejected[name] = f"not certifiable: {why}"
        if result is not None:
            out.results[name] = result
    out.rejected = {name: out.rejected[name] for name in names if name in out.rejected}  # in the order asked
    priced = [pair for name, r in out.results.items() for pair in _designs(name, r, synth)]
    if progress:
        progress(f"pricing {len(priced)} designs' architectures")
    for (where, _), found in zip(priced, price_designs([d for _, d in priced], scene.analysis, speed, **options)):
        where["cost"] = found

    def cost(name, params, by_synth):
        return price_designs([(name, params, by_synth and synth)], scene.analysis, speed, **options)[0]

    # the chosen design's full certificate and ``prepare``, begun beside its witness on a sample
    # worth forking for
    fork = scene.points.count >= MIN_POINTS and count(workers) > 1
    pending = begin_full_certificate(out, certifier, fork) if certified and certifier is not None else None
    prepared = (begin_beside_witness(out, lambda result: prepare(result, scene.analysis), fork)
                if prepare is not None else None)
    try:
        choose(out, scene, cost, prove, prove_timeout, progress, search)
        if certified and out.rounds:  # a witness over the requirement on a design its certificate bounds
            step = out.rounds[0]
            raise AssertionError(f"internal error: {step['method']} at {step['params']} has a witness of "
                                 f"{step['witness_levels']} levels over the requirement its certificate "
                                 f"meets: the bound is not sound")
        if certifier is not None and out.chosen is not None:
            if progress:
                progress(f"certifying {out.chosen}")
            out.certificate = (full_certificate(out, certifier, pending) if certified else
                               certifier(out.chosen, out.best["params"], spec, domain, analysis=scene.analysis))
        if for_chosen(out, prepared):
            prepared[2].result()
    finally:  # not taken (another design chosen, or none), or interrupted
        for begun in (pending, prepared):
            if begun is not None:
                begun[2].cancel()
    out.refused = refusal(out)
    if certified and out.chosen is None and out.refused is None:
        out.refused = {"why": "certificate", "text": refusal_lines(out)}
    out.hint = None if out.refused else hint(out)
    return out
