"""Stimulus for the colour blend: no light, full scale, the light behind the surface (diff = 0
with spec at its top), the smallest lit diff, exactly 1.0, one light at a time, every one at
each material code; then seeded random amounts in the unit range and over the whole formats."""

import numpy as np

from phongfx.config.blend import CHANNELS

from . import concat, random_codes, rng
from .extreme import Extreme, equal

__all__ = ["stimulus", "directed", "exact", "extremes"]


def _ports(config, diff, spec, materials=None):
    """Raw inputs from ``diff`` and ``spec`` codes of shape (rows, lights): every row at each
    material code in turn (``materials`` None), or at the codes ``materials`` (rows,)."""
    diff, spec = (np.asarray(x, dtype=np.int64).reshape(-1, config.lights) for x in (diff, spec))
    if materials is None and config.materials > 1:
        count = config.materials
        materials = np.repeat(np.arange(count, dtype=np.int64), len(spec))
        diff, spec = np.tile(diff, (count, 1)), np.tile(spec, (count, 1))
    ports = {}
    for i in range(config.lights):
        if config.diff:
            ports[f"diff{i}"] = diff[:, i]
        ports[f"spec{i}"] = spec[:, i]
    if config.materials > 1:
        ports["material"] = np.asarray(materials, dtype=np.int64)
    return ports


def _tops(config):
    """(diff top, diff 1.0, spec top, spec 1.0 or its top): the codes the rows are made of."""
    spec = config.fmt("spec")
    diff = config.fmt("diff") if config.diff else spec  # no diff port: its codes are unused
    return diff.max_raw, diff.one, spec.max_raw, min(spec.one, spec.max_raw)


def directed(config):
    """Raw inputs of the directed rows, each light alike, at every material code: all zeros;
    all top codes; diff = 0 with spec at its top (gated off); diff = 1 LSB with spec at its
    top (the smallest lit amount); diff = spec = 1.0; diff at its top with spec = 0; and
    each light alone lit (diff = spec = 1.0) with the others behind the surface (diff = 0,
    spec at its top)."""
    lights = config.lights
    diff_top, diff_one, spec_top, spec_one = _tops(config)
    pairs = [(0, 0), (diff_top, spec_top), (0, spec_top), (1, spec_top), (diff_one, spec_one), (diff_top, 0)]
    diff = [[d] * lights for d, _ in pairs]
    spec = [[s] * lights for _, s in pairs]
    for lit in range(lights) if lights > 1 else ():
        diff.append([diff_one if i == lit else 0 for i in range(lights)])
        spec.append([spec_one if i == lit else spec_top for i in range(lights)])
    return _ports(config, diff, spec)


def stimulus(config, count=1000, seed=0):
    g = rng(seed)
    spec_fmt = config.fmt("spec")
    diff_fmt = config.fmt("diff") if config.diff else spec_fmt
    shape = (count // 2, config.lights)
    parts = [directed(config)]
    for unit in (True, False):  # amounts a shader gives (0..1.0), then any code of the formats
        diff = random_codes(diff_fmt, shape, g, hi=min(diff_fmt.one, diff_fmt.max_raw) if unit else None)
        spec = random_codes(spec_fmt, shape, g, hi=min(spec_fmt.one, spec_fmt.max_raw) if unit else None)
        diff = np.where(g.random(shape) < 0.25, 0, diff)  # lights behind the surface: the gate
        materials = g.integers(0, config.materials, size=shape[0], dtype=np.int64)
        parts.append(_ports(config, diff, spec, materials))
    return concat(*parts)


def _round(value, frac, rounding):
    """Python int ``value`` (``frac`` fraction bits) rounded to an integer."""
    if frac == 0:
        return value
    kept, rest, half = value >> frac, value & ((1 << frac) - 1), 1 << (frac - 1)
    if rounding == "round_half_up":
        return kept + (rest >= half)
    if rounding == "round_half_even":
        return kept + (rest > half or (rest == half and kept & 1))
    return kept


def exact(config, inputs):
    """The blend's outputs ``{channel: int64 array}`` in Python integers from the formula of
    :class:`~phongfx.config.BlendConfig` (its coefficient codes), row by row: the check of
    the extreme rows, independent of the golden model's arithmetic."""
    spec_frac = config.fmt("spec").frac_bits
    diff_frac = config.fmt("diff").frac_bits if config.diff else 0
    frac = config.coef_frac + max(spec_frac, diff_frac)
    tables = [config.coefficients(m) for m in range(config.materials)]
    count = len(inputs["spec0"])
    out = {name: np.zeros(count, dtype=np.int64) for name in CHANNELS}
    for row in range(count):
        a, d, s = tables[int(inputs["material"][row]) if config.materials > 1 else 0]
        for c, name in enumerate(CHANNELS):
            acc = a[c] << (frac - config.coef_frac)
            for i in range(config.lights):
                lit = int(inputs[f"diff{i}"][row]) if config.diff else 0
                amount = int(inputs[f"spec{i}"][row]) if lit > 0 or not config.gate else 0
                acc += d[i][c] * lit << (frac - config.coef_frac - diff_frac)
                acc += s[i][c] * amount << (frac - config.coef_frac - spec_frac)
            out[name][row] = min(_round(acc, frac, config.rounding), config.levels)
    return out


def _exactly(c, i, o):
    want = exact(c, i)
    return np.all([equal(o[name], want[name]) for name in CHANNELS], axis=0)


def extremes(block_name):
    """The blend's extreme rows (Phong 1975, Lyon 1993 "Background": ambient + Σ_lights
    intensity·(kd·diffuse + ks·specular)), each at every material code, checked against
    :func:`exact`."""
    def rows(diff, spec):
        def build(c):
            tops = dict(zip(("diff_top", "diff_one", "spec_top", "spec_one"), _tops(c)))
            return _ports(c, [[tops.get(diff, diff)] * c.lights], [[tops.get(spec, spec)] * c.lights])
        return build
    return (
        Extreme(block_name, "all-zeros codes (no light), each material", "ambient only: round(A) per channel",
                rows(0, 0), _exactly),
        Extreme(block_name, "all-ones codes (diff, spec at their tops), each material",
                "the exact sum rounded, saturating at 2^bits − 1", rows("diff_top", "spec_top"), _exactly),
        Extreme(block_name, "light behind the surface (diff = 0, spec at its top), each material",
                "specular gated off (with gate, the default): ambient only", rows(0, "spec_top"), _exactly),
        Extreme(block_name, "exactly 1.0 (diff = spec = 1.0), each material",
                "A + Σ (D + S), rounded and clamped", rows("diff_one", "spec_one"), _exactly),
    )
