"""A sound bound on a compiled design's error over a scene's domain.

:func:`certify` asks the unit's bounding method (:mod:`.bounding`) whether it covers the design
on the domain and, when it does, for its bound ``B`` on ``|out - (2^bits - 1)·I_ref|`` in display
levels; the certificate meets the requirement when ``floor(B + 1/2)`` does
(:func:`~phongfx.certify.certificate.meets`).  A unit without a bounding method, or a domain
its method does not cover, gets a certificate without a bound that says why.
"""

import time

import numpy as np

from phongfx.explore.compile import run as runs
from phongfx.explore.compile.analysis import analyse
from phongfx.scene.geometry import frames

from .certificate import Certificate, meets
from .bounding import bounding
from .regions import by_region

__all__ = ["certify", "shader_config"]


def shader_config(method, params, spec, analysis=None):
    """The compiler's ShaderConfig of ``method`` at ``params`` for the scene ``spec``."""
    if analysis is None:
        analysis = analyse(spec, frames(spec))
    return runs.build(method, params, analysis)


def certify(method, params, spec, domain, *, shader=None, analysis=None, max_boxes=300_000, early=False,
            regions_first=False):
    """A :class:`~phongfx.certify.certificate.Certificate` for ``method`` at ``params`` (the
    compiler's, :func:`shader_config`) on the scene ``spec`` over ``domain``
    (:class:`phongfx.scene.domain.Domain`); ``shader``: the ShaderConfig when already built;
    ``max_boxes``: the branch and bound's budget (:func:`~phongfx.certify.branch.bound_boxes`);
    ``early``: stop refining as soon as the bound meets the requirement (for a width search,
    which asks only that); ``regions_first``: with ``early``, a domain's regions without its
    whole (:func:`~phongfx.certify.regions.by_region`)."""
    start = time.perf_counter()
    how = bounding(method)

    def done(certified, bound, parts=None, why=""):
        return Certificate(certified, bound, how.name if how else "interval", parts or {}, why,
                           time.perf_counter() - start)

    if how is None:
        return done(False, None, why=f"no bounding method for the {method} unit yet")
    if shader is None:
        shader = shader_config(method, params, spec, analysis)
    why = how.why_not(shader, domain)
    if why:
        return done(False, None, why=why)
    need = spec.requirement.max_error_levels
    target = spec.requirement.bound_limit
    bound, parts = by_region(how, shader, spec, domain, max_boxes=max_boxes, enough=target if early else None,
                             target=target, regions_first=regions_first)
    if not np.isfinite(bound):
        faults = ", ".join(parts.get("faults", [])) or "a quantize"
        return done(False, None, parts, f"{faults} may overflow or wrap somewhere in the domain")
    ok = meets(bound, need)
    why = "" if ok else (f"the bound {bound:.3f} levels rounds to {int(np.floor(bound + 0.5))}, over the "
                         f"required {need:g}")
    if not ok and "region" in parts:
        why += f"; by region, largest in {parts['region']}"
        if "region_bound" in parts and parts["region_bound"] < bound:
            why += f" at {parts['region_bound']:.3f} levels there"
        if parts.get("unbounded_regions"):
            why += f" (which stays over it: {len(parts['unbounded_regions'])} regions not bounded)"
    if not ok and "backside" in parts:
        why += (f"; at its largest the hardware's backside test may differ from the reference's: its "
                f"N·L error bound {parts['backside']:.4f} is wider than the terminator band "
                f"1/{(1 << spec.output.bits) - 1}")
    return done(ok, bound, parts, why)
