"""Which bounding method bounds each unit the compiler can choose.

A bounding method is an object with

* ``name``: what the certificate names as its method (``"interval"``...);
* ``why_not(shader, domain)``: None when it bounds the design ``shader`` (the compiler's
  ShaderConfig) over ``domain`` (:class:`phongfx.scene.domain.Domain`), else one sentence;
* ``bound(shader, spec, domain, *, max_boxes, enough, resume)``: ``(bound_levels, parts)``, a sound
  upper bound on ``|out - (2^bits - 1)·I_ref|`` over the domain in display levels (inf when some
  quantize may overflow, ``parts["faults"]`` naming them), refined until it falls below
  ``enough`` when that is given, going on from ``resume`` (:class:`phongfx.certify.branch.Resume`)
  when given (:func:`phongfx.certify.branch.bound_boxes`);
* ``limits(domain)``: what of the domain its bound reads (:func:`phongfx.certify.regions.limits`,
  or less): regions it reads as the whole domain are not bounded apart
  (:func:`~phongfx.certify.regions.like_whole`).

A method's bounding method is its ``certify`` face in the method registry
(:data:`phongfx.core.methods.METHODS`): adding one is its object and that one line.  None is
named for ``euler`` and ``gouraud`` (Hast, Barrera & Bengtsson: the diffuse ``N·L`` alone,
no place in a shader and never compiled) nor for ``schlick`` (its compile hooks build no input
stream): no compiled design is one of them (docs/certificate.rst).
"""

from phongfx.core.methods import get_method

__all__ = ["bounding"]


def bounding(method):
    """The bounding method of ``method`` (None when it has none yet)."""
    method = get_method(method)
    return method.load("certify") if method.has("certify") else None
