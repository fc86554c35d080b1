"""Stimulus for the whole shader: each copy's unit stimulus, side by side, and materials.

Every copy of the unit gets its own block's stimulus (seeded per copy), cut to the
shortest (a shared input, :attr:`~phongfx.config.ShaderConfig.shared`, the first copy's), so directed extremes of each unit reach the blend; the ``material`` input,
when there is one, takes every code in turn on the directed vectors and random codes
after them.  The extreme rows are the Lyon datapaths' rows seen at the pixel: with every
term at full scale the blend saturates or gives the exact sum of its constants, and at
V = −L the backside test leaves the ambient term only (the halfway unit's spec = 1
there does not reach the pixel).
"""

from fractions import Fraction

import numpy as np

from phongfx.core.format import Format
from phongfx.core.methods import METHODS
from phongfx.core.registry import REGISTRY

from . import rng
from .extreme import Extreme, equal, round_exact

__all__ = ["stimulus", "extremes"]


def _materials(config, count, g, directed=64):
    """``material`` codes: every code cycled over the first ``directed``, random after."""
    materials = len(config.blend.ambient)
    codes = np.arange(count) % materials
    codes[directed:] = g.integers(0, materials, max(count - directed, 0))
    return codes.astype(np.int64)


def _side_by_side(config, parts):
    """One raw input dict of the shader from one raw dict per copy (cut to the shortest)."""
    count = min(len(next(iter(part.values()))) for part in parts)
    raw = {}
    for copy, part in enumerate(parts):
        for name, value in part.items():  # a shared input takes the first copy's codes
            raw.setdefault(config.port_name(copy, name), np.asarray(value)[:count])
    return raw, count


def stimulus(config, count=1000, seed=0):
    g = rng(seed)
    stimulus_of = REGISTRY[config.unit].load("stimulus")
    raw, total = _side_by_side(config, [stimulus_of(sub, count=count, seed=seed + copy)
                                        for copy, sub in enumerate(config.units)])
    if "material" in config.inputs:
        raw["material"] = _materials(config, total, g)
    return raw


def _unit_row(config, name):
    """Raw shader inputs of the unit's extreme row called ``name`` (a Lyon datapath's)."""
    if config.unit not in {method.block for method in METHODS.values() if method.is_datapath}:
        raise ValueError(f"the shader's extreme rows need a Lyon datapath unit, not {config.unit!r}")
    rows = {row.name: row for row in REGISTRY[config.unit].load("extremes")(config.unit)}
    raw, count = _side_by_side(config, [rows[name].build(sub) for sub in config.units])
    if "material" in config.inputs:
        raw["material"] = np.arange(count, dtype=np.int64) % len(config.blend.ambient)
    return raw


def _level(config, material, lit):
    """The exact code of every channel with every term at 1.0 (``lit``) or the ambient only."""
    blend = config.blend
    ambient, diffuse, specular = blend.coefficients(material)
    out = []
    for c in range(3):
        total = ambient[c] + (sum(diffuse[i][c] + specular[i][c] for i in range(blend.lights)) if lit else 0)
        out.append(round_exact(Fraction(total, 1 << blend.coef_frac), Format(blend.bits, 0), blend.rounding))
    return out


def _holds(lit):
    def holds(config, inputs, outputs):
        count = len(outputs["r"])
        material = inputs.get("material", np.zeros(count, dtype=np.int64))
        want = np.array([_level(config, int(m), lit) for m in material]).reshape(count, 3)
        return np.all([equal(outputs[name], want[:, c]) for c, name in enumerate("rgb")], axis=0)
    return holds


def extremes(block_name):
    """The shader's extreme rows: every term at 1.0 (N = V = L) and the gated V = −L."""
    return (
        Extreme(block_name, "every term at 1.0: N = V = L (R = L), n = 1 and n_max",
                "each channel the sum of its constants, rounded half up, saturated at 2^bits − 1",
                lambda c: _unit_row(c, "exactly ±1.0: N = V = L (R = L), n = 1 and n_max"), _holds(True)),
        Extreme(block_name, "V = −L (N = V), n_max",
                "the ambient term only: N·L = −1 gates diffuse and specular (also the halfway "
                "unit's spec = 1 at H = 0)",
                lambda c: _unit_row(c, "V = −L (N = V), n_max"), _holds(False)),
    )
