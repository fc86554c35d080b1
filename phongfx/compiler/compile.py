"""The scene compiler: the cheapest datapath whose error a scene's viewer cannot see.

:func:`compile_scene` takes a :class:`~phongfx.compiler.request.CompileRequest`, analyses the scene (:mod:`phongfx.explore.compile.analysis`), then for every
method of :data:`phongfx.core.methods.METHODS` either records why it cannot represent the
scene (:func:`phongfx.explore.compile.run.rejection`) or searches its widths:

1. start from the method's default widths; if they miss the requirement, from every
   width at its range maximum and ``k`` at its best value there (:func:`~phongfx.explore.compile.search.widest`); if that
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

Widths are the method's :class:`~phongfx.core.methods.Method` parameters except ``n``,
``k`` and ``lights``, plus, for Lyon's datapaths, the normalizers' ``order`` (2 = g2,
1 = g1: g1 vs g2 is measured like a width) and, against true Phong, the shape
function's ``k`` (fewer squarings is cheaper; ``2^k = n`` makes ``f_k`` Phong's power).

The choice: the feasible designs by cost; the cheapest is searched for its worst input over
the domain, ``final_samples`` fresh points and a local search from the worst
(:func:`phongfx.explore.compile.witness.search`): its **witness**.  A witness over the
requirement makes the design unfit as it is: the witness and its neighbourhood join the
domain sample as hard points (:meth:`~phongfx.explore.compile.measure.SceneEval.add_hard`),
that method's widths are searched again, and the designs re-ranked, for at most
:data:`~phongfx.explore.compile.choice.ROUNDS` such rounds
(:data:`~phongfx.explore.compile.choice.METHOD_ROUNDS` per method; each recorded in
:attr:`Compiled.rounds`); a design whose witness still misses is not chosen.  A quick local
search from the width search's own worst points comes before each fresh sample (not in a
certified compile, where the witness cannot miss).

With ``certify="search"`` (``phongfx compile``'s default) a width point must also meet the
requirement by its certificate (:func:`phongfx.certify.certify`, kept in the request's
``certificates`` folder when given: :func:`phongfx.certify.remembered.remembering`), methods
without a bounding method are rejected unsearched, and the chosen design ships with the
certificate its search passed it by (:mod:`phongfx.explore.compile.certified`).  This layer sits above
:mod:`phongfx.certify`, which bounds a design through the compile room's fitting of a method to
a scene (:mod:`phongfx.explore.compile.run`, :mod:`~phongfx.explore.compile.analysis`).

Cost (to choose among methods), on the request's ``target``: on an FPGA LUT-eq (``LUT4 +
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

from phongfx.certify import certify
from phongfx.certify.certificate import Certificate
from phongfx.certify.remembered import remembering
from phongfx.explore.compile import run as runs
from phongfx.explore.compile.architecture import Speed, refusal
from phongfx.explore.compile.certified import certified_search, refusal_lines
from phongfx.explore.compile.choice import begin_beside_witness, choose, for_chosen
from phongfx.explore.compile.costing import price_designs
from phongfx.explore.compile.infeasible import hint
from phongfx.explore.compile.measure import SceneEval
from phongfx.explore.compile.points import DomainPoints
from phongfx.explore.compile.search import search_all, search_widths
from phongfx.explore.compile.workers import MIN_POINTS, count

from .request import check_samples

__all__ = ["Compiled", "compile_scene", "certifier_of", "scene_domain"]


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
    prepared: object = None             # what request.prepare made for the chosen design (its return)
    pending: object = None              # request.prepare still running beside for it (take_prepared)
    rounds: list = field(default_factory=list)  # each witness over the requirement and what it did
    speed: Speed = Speed()              # the pixel rate and clock asked
    refused: dict = None                # nothing chosen for speed or fit: refusal(...)

    @property
    def best(self):
        return self.results.get(self.chosen)

    def take_prepared(self):
        """:attr:`prepared`, waited for first when ``request.prepare`` still runs beside (begun
        with the witness search, it may outlast it: its caller does what needs no prepared output
        first, as emit draws its pictures); None without one."""
        if self.pending is not None:
            pending, self.pending = self.pending, None
            try:
                self.prepared = pending.result()
            finally:  # interrupted while waiting: the work too
                pending.cancel()
        return self.prepared

    def close(self):
        """End ``request.prepare`` if it still runs beside, not taken (nothing written, or emit
        failed first)."""
        if self.pending is not None:
            self.pending.cancel()
            self.pending = None


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


def scene_domain(spec, geometries, samples=None, final_samples=None):
    """The :class:`~phongfx.scene.domain.Domain` of ``spec`` with its ``samples`` and
    ``final_samples`` replaced when given (positive integers, checked)."""
    from phongfx.scene.domain import domain

    for name, value in (("samples", samples), ("final_samples", final_samples)):
        check_samples(name, value)
    found = domain(spec, geometries)
    changes = {k: v for k, v in (("samples", samples), ("final_samples", final_samples)) if v is not None}
    return dataclasses.replace(found, **changes) if changes else found


def certifier_of(request):
    """What bounds a design for ``request``: None when it certifies nothing, else
    :func:`phongfx.certify.certify`, its certificates kept in ``request.certificates`` when given
    (:func:`~phongfx.certify.remembered.remembering`).  Called as ``certifier(method, params,
    spec, domain, early=False, analysis=None[, max_boxes])``; ``max_boxes=0`` asks whether the
    method is bounded at all (:func:`~phongfx.explore.compile.certified.certified_search`)."""
    if request.certify == "none":
        return None
    return certify if request.certificates is None else remembering(request.certificates)


def compile_scene(request):
    """Compile ``request.spec`` as ``request`` (a :class:`~phongfx.compiler.request.CompileRequest`)
    asks: see the module docstring.  Returns a :class:`Compiled`."""
    spec, progress, synth, workers = request.spec, request.progress, request.synth, request.workers
    names = request.names
    certified = request.certify == "search"
    certifier = certifier_of(request)
    speed = request.speed
    scene = SceneEval(spec, request.geometries, journal=request.journal)
    domain = scene_domain(spec, scene.geometries, request.samples, request.final_samples)
    if progress:
        progress(f"drawing {domain.samples:,} domain points")
    scene.measure_domain(DomainPoints(spec, domain))
    target = request.target
    out = Compiled(spec, scene.analysis, scene, f"{target}-synth" if synth else f"{target}-proxy", domain=domain,
                   speed=speed, certified=certified)

    options = {"target": target, "device": request.device, "freq": request.clock or request.freq,
               "seed": request.seed, "scheduler": request.scheduler, "workers": workers, "progress": progress}

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

    # the chosen design's ``prepare``, begun beside its witness on a sample worth forking for
    fork = scene.points.count >= MIN_POINTS and count(workers) > 1
    prepared = (begin_beside_witness(out, lambda result: request.prepare(result, scene.analysis), fork)
                if request.prepare is not None else None)
    try:
        choose(out, scene, cost, request.prove, request.prove_timeout, progress, search)
        if certified and out.rounds:  # a witness over the requirement on a design its certificate bounds
            step = out.rounds[0]
            raise AssertionError(f"internal error: {step['method']} at {step['params']} has a witness of "
                                 f"{step['witness_levels']} levels over the requirement its certificate "
                                 f"meets: the bound is not sound")
        if certified and out.chosen is not None:  # the certificate its search passed it by
            out.certificate = Certificate.from_dict(out.best["certificate"])
        elif certifier is not None and out.chosen is not None:
            if progress:
                progress(f"certifying {out.chosen}")
            out.certificate = certifier(out.chosen, out.best["params"], spec, domain, analysis=scene.analysis)
        if for_chosen(out, prepared):  # its caller takes it when it needs it (Compiled.take_prepared)
            out.pending, prepared = prepared[2], None
    finally:  # not taken (another design chosen, or none), or interrupted
        if prepared is not None:
            prepared[2].cancel()
    out.refused = refusal(out)
    if certified and out.chosen is None and out.refused is None:
        out.refused = {"why": "certificate", "text": refusal_lines(out)}
    out.hint = None if out.refused else hint(out)
    return out
