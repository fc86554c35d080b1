"""Golden model of a whole shader: the shading unit's copies, then the blend to r, g, b.

Each copy of the unit (:class:`~phongfx.config.ShaderConfig` ``units``) runs its own golden
model on its own inputs and the shared ones; every light's diffuse and specular terms, in the order
:attr:`~phongfx.config.ShaderConfig.terms` gives, go to :func:`~phongfx.golden.blend.blend`
with the pixel's material.  Nothing is narrowed between them: the blend takes the
unit's output formats as they are.
"""

import numpy as np

from phongfx.core.registry import REGISTRY

from .blend import blend
from .chunks import chunked, stateless
from .fixed import Fixed

__all__ = ["shader", "shader_terms", "shader_raw"]


def shader(config, **ports):
    """The pixel's ``r``, ``g``, ``b`` codes.

    Parameters
    ----------
    config : ShaderConfig
    ports : Fixed
        Every input of ``config.inputs``: the unit's (prefixed ``c<j>_`` per copy when there
        are several, except the shared ones) and ``material`` when the blend has several
        materials.

    Returns
    -------
    dict
        ``{"r", "g", "b"}``: Fixed in ``blend.bits``.0.
    """
    return blend(config.blend, **shader_terms(config, **ports))


def shader_terms(config, **ports):
    """The blend's inputs :func:`shader` computes: every light's ``diff<i>`` (when the unit
    has a diffuse output) and ``spec<i>``, and ``material``; a caller that also needs the
    terms (the scene compiler's backside test) blends them itself.

    Each cycle ``t`` of :attr:`~phongfx.config.ShaderConfig.interval` runs the physical
    copies on what :meth:`~phongfx.config.ShaderConfig.feeds` gives them (the shared inputs
    fanned out to every copy, light ``t·per_cycle + j`` to copy ``j``), as the hardware does;
    the terms are blended once, so any interval gives interval 1's codes."""
    unit = REGISTRY[config.unit].load("golden")
    per = config.per_cycle
    slots = config.physical_terms
    terms = {}
    for group in range(config.interval):
        outputs = [unit(sub, **{name: ports[port] for name, port in feed.items()})
                   for sub, feed in zip(config.physical_units, config.feeds(group))]
        for slot, (copy, diff, lane, spec) in enumerate(slots):
            light = group * per + slot
            if light >= config.lights:
                continue
            if diff is not None:
                value = outputs[copy][diff]
                terms[f"diff{light}"] = value if lane is None else Fixed(value.raw[:, lane], value.fmt)
            terms[f"spec{light}"] = outputs[copy][spec]
    if "material" in ports:
        terms["material"] = ports["material"]
    return terms


def shader_raw(config, raw):
    """:func:`shader` on raw input codes ``raw`` (``{port: int array}``): raw ``r``, ``g``,
    ``b`` codes and, when the blend has them, each light's ``diff<i>`` term (the scene
    compiler's backside test); a chunk of pixels at a time when the unit keeps no state
    (:mod:`~phongfx.golden.chunks`: the same codes, faster)."""
    def shade(part):
        terms = shader_terms(config, **{name: Fixed(part[name], fmt) for name, (fmt, _) in config.inputs.items()})
        out = {name: value.raw for name, value in blend(config.blend, **terms).items()}
        if config.blend.diff:
            out.update((f"diff{i}", terms[f"diff{i}"].raw) for i in range(config.blend.lights))
        return out

    raw = {name: np.asarray(raw[name], dtype=np.int64) for name in config.inputs}
    return chunked(shade, raw) if stateless(raw) else shade(raw)
