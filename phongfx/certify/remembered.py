"""Certificates kept in the per-user cache, so that a rerun of a compile bounds nothing twice.

A certified compile (:mod:`phongfx.explore.compile.certified`) asks for a certificate at every
width point its cheap measured test passes, and each takes seconds of branch and bound; the
measured points are kept by the compile's journal (:mod:`phongfx.explore.compile.journal`), and
:func:`remembering` does the same for the certificates: one JSON file per certificate in
``<folder>/<key>.json``, the key covering everything the bound depends on: the package source
(:func:`~phongfx.explore.compile.journal.source_digest`), the design (its whole shader config),
the domain (not its sample), the scene's requirement and output, and how the bound was refined
(``early``, ``max_boxes``, ``regions_first``).  The blend's coefficients enter by their values, not their
width (:func:`~phongfx.certify.outputs.fewest_coefficient_bits`): a width search lowering
``coef`` where the codes only lose trailing zeros bounds the same outputs once.  A probe that
refines nothing (``max_boxes=0``) is not kept: it costs less than reading it back; nor is one the
branch and bound's hang guard cut (``parts["timed_out"]``), which another run would refine further.
"""

import dataclasses
import hashlib
import json
import os

from phongfx.core.files import atomic_write
from phongfx.explore.compile.journal import source_digest

from .bound import certify, shader_config
from .certificate import Certificate
from .outputs import fewest_coefficient_bits

__all__ = ["certificate_key", "remembering"]


def certificate_key(method, shader, spec, domain, early, max_boxes, regions_first=False):
    """The cache key of a certificate (module docstring); the domain's sample sizes and seed,
    which only the measurement reads, are left out."""
    domain = dataclasses.replace(domain, samples=1, final_samples=1, seed=0)
    shader = dataclasses.replace(shader, blend=fewest_coefficient_bits(shader.blend))
    text = repr((source_digest(), method, shader, domain, spec.requirement, spec.output, bool(early), max_boxes)
                + ((True,) if regions_first else ()))
    return hashlib.sha256(text.encode()).hexdigest()[:24]


def remembering(folder):
    """A certifier with :func:`~phongfx.certify.bound.certify`'s signature whose certificates
    are kept in ``folder`` and read back from it."""

    def certifier(method, params, spec, domain, *, analysis=None, max_boxes=300_000, early=False,
                  regions_first=False):
        if not max_boxes:
            return certify(method, params, spec, domain, analysis=analysis, max_boxes=max_boxes, early=early)
        shader = shader_config(method, params, spec, analysis)
        key = certificate_key(method, shader, spec, domain, early, max_boxes, regions_first)
        path = os.path.join(folder, f"{key}.json")
        try:
            with open(path, encoding="utf-8") as file:
                return Certificate.from_dict(json.load(file))
        except (OSError, ValueError, TypeError, KeyError):
            pass  # not kept yet, or torn: bound it again
        found = certify(method, params, spec, domain, shader=shader, max_boxes=max_boxes, early=early,
                        regions_first=regions_first)
        if (found.parts or {}).get("timed_out"):
            return found  # cut by the clock, not the budget: this machine's, not the key's, bound
        try:
            text = json.dumps(found.as_dict(), default=float)
        except TypeError:
            return found  # parts JSON cannot hold: bounded again next time
        atomic_write(path, lambda p: open(p, "w", encoding="utf-8").write(text))
        return found

    return certifier
