"""The certified search, ``phongfx compile``'s default: every width point must meet the
requirement by a sound bound.

A method is certifiable on a scene when its unit has a bounding method that covers the
scene's domain: the certifier (:func:`phongfx.certify.certify`, passed in by the compiler,
:mod:`phongfx.compiler`, since certify sits above this room) answers for the method's default widths, asked for no
refinement (``max_boxes=0``: the coverage, not the bound, is the question), with a bound, or
without one only because some quantize may overflow at those widths (``parts["faults"]``: other
widths may not).  Any other certificate without a bound says why no width can help (no bounding
method for the unit, lights or viewer it does not cover): the method is rejected with that
sentence and not searched at all, so a new bounding method needs no change here.

A certifiable method is searched once (:func:`~phongfx.explore.compile.search.search_widths`)
with two tests per width point: a cheap measured one first (its frames and the domain
sample's screen, :meth:`~phongfx.explore.compile.measure.SceneEval.fails_screen`), then its
certificate, refined only until it meets (``early``); a width one lower than the result
fails by one of the two (:meth:`CertifiedTest.failure`).  The whole domain sample is not
measured at each point: a certificate that meets the requirement bounds every point of it,
and on the two-light scene the whole sample passed 19 of the 25 width points of Figure 7's
search, 10 of which the certificate then failed: it decided little and cost as much as the
certificates (21 s beside 22 s on one core).  The search's start and its result are measured
whole.

The chosen design ships with the certificate its search passed it by (its result's ``"certificate"``):
sound, refined until its bound met the requirement (``early``, :data:`REFINED`), so just under
it.  Refining it to the end (``phongfx certify DIR``) tightens it by little on the example
scenes (Lyon's spheres: 1.498 to 1.495 levels) and cost the longest compile a sixth of its time
(18 of 113 s on 2 cores, the last thing it waited for), so the compile does not.
"""

__all__ = ["REFINED", "CertifiedTest", "uncertifiable", "certified_search", "refusal_lines"]

from phongfx.core.words import levels

from .measure import point_key
from .search import search_widths, width_params


#: How far the shipped certificate was refined (its search's, module docstring).
REFINED = "until it met the requirement (early); phongfx certify DIR refines it to the end"


def uncertifiable(certificate):
    """Why no width of a method can be certified, from its certificate at some widths; None
    when it has a bound there, or lacks one only for an overflow that other widths may avoid."""
    if certificate.bound_levels is None and not certificate.parts.get("faults"):
        return certificate.why or "no bound"
    return None


class CertifiedTest:
    """``test(params)``: whether ``method`` at ``params`` passes the cheap measured test and meets
    the requirement by its certificate (module docstring); each width point's certificate is asked once
    (:attr:`certificates`: key -> ``(params, certificate)``)."""

    def __init__(self, scene, method, domain, certifier):
        self.scene, self.method, self.domain, self.certifier = scene, method, domain, certifier
        self.certificates = {}
        #: a certificate this search passed needed the domain's regions (its whole missed the requirement)
        self.regions_needed = False

    def certificate(self, params):
        """The early certificate of ``params`` (cached).  Once one that passed needed the domain's
        regions, the next bound the regions without the whole domain first (``regions_first``):
        the search only lowers widths from a point that passed, and lower widths than one whose
        whole domain missed miss there too (on Lyon's spheres a third of each certificate's time).
        A failing point's regions say nothing of wider widths (on the two-light scene, whose whole
        domain certifies its passing points, the regions first cost 12 s more)."""
        key = point_key(self.method, params)
        if key not in self.certificates:
            more = {"regions_first": True} if self.regions_needed else {}
            found = self.certifier(self.method, dict(params), self.scene.spec, self.domain, early=True,
                                   analysis=self.scene.analysis, **more)
            self.certificates[key] = (dict(params), found)
            self.regions_needed = self.regions_needed or (found.certified and "regions" in (found.parts or {}))
        return self.certificates[key][1]

    def __call__(self, params):
        return not self.scene.fails_screen(self.method, params) and self.certificate(params).certified

    def margin(self, params):
        """How far under the requirement's limit the bound of a point this test passed stayed
        (levels), None for a point it has not certified: the search's hint of where the
        widths' edge is (:func:`~phongfx.explore.compile.search.search_widths`)."""
        found = self.certificates.get(point_key(self.method, params))
        if found is None or not found[1].certified:
            return None
        return self.scene.spec.requirement.bound_limit - found[1].bound_levels

    def failure(self, params):
        """What the proof of minimality says of a point this test failed: measured past the
        requirement (frames or screen), or its certificate's bound (``bound_levels``, None
        without one) and why it misses; no measurement of the whole sample is made for it."""
        if self.scene.fails_screen(self.method, params):
            return {"why": "measured past the requirement (on its frames or the worst points measured before)"}
        certificate = self.certificate(params)
        return {"bound_levels": certificate.bound_levels,
                "why": f"its certificate misses the requirement: {certificate.why or 'no bound'}"}


def certified_search(scene, method, domain, certifier, progress=None):
    """``(result, None)``: ``method``'s certified width search (a
    :func:`~phongfx.explore.compile.search.search_widths` result, a feasible one with its
    ``"certificate"``: the early bound at its widths), or ``(None, why)`` when the method is
    not certifiable on the scene (:func:`uncertifiable`)."""
    default = {k: v for k, (v, _) in width_params(method, scene.spec.requirement.against).items()}
    probe = certifier(method, default, scene.spec, domain, early=True, analysis=scene.analysis, max_boxes=0)
    why = uncertifiable(probe)
    if why:
        return None, why
    if progress:
        progress(f"{method}: a certified design")
    test = CertifiedTest(scene, method, domain, certifier)
    result = search_widths(scene, method, progress, passes=test)
    if result["feasible"]:
        result["certificate"] = {**test.certificate(result["params"]).as_dict(), "refined": REFINED}
    else:
        tried = [(p, c) for p, c in test.certificates.values() if c.bound_levels is not None]
        best = min(tried, key=lambda pc: pc[1].bound_levels, default=None)
        result.setdefault("why", []).append(
            "no width point is certified within the requirement"
            + (f"; the lowest bound found is {best[1].bound_levels:.3f} levels at {best[0]}" if best else ""))
    return result, None


def refusal_lines(out):
    """Why a certified compile chose nothing for its error: one line per method, and the way
    to a measured choice (``--sampled``)."""
    spec = out.spec
    required = spec.requirement.max_error_levels
    text = [f"no design of {spec.name} is certified within {levels(required)} against "
            f"{spec.requirement.against}:"]
    for name, reason in out.rejected.items():
        text.append(f"  {name}: {reason}")
    for name, r in out.results.items():
        if r["feasible"]:
            text.append(f"  {name}: certified at {r['params']}, but " + (r.get("why_not_chosen") or "not chosen"))
        else:
            text.append(f"  {name}: {(r.get('why') or ['infeasible'])[-1]}")
    path = spec.path or f"{spec.name}.toml"
    text.append(f"--sampled chooses by the measured error alone (certified: false): "
                f"phongfx compile {path} -o DIR --sampled")
    return text
