"""The scene compiler: the cheapest datapath whose error a scene's viewer cannot see.

:func:`compile_scene` analyses the scene (:mod:`phongfx.explore.compile.analysis`), then for every
method of :data:`phongfx.explore.methods.METHODS` either records why it cannot represent the
scene (:func:`phongfx.explore.compile.run.rejection`) or searches its widths:

1. start from the method's default widths; if they miss the requirement, from every
   width at its range maximum; if that misses too the method is infeasible (its
   measured error is kept);
2. greedily lower each width (binary search, then verified) while every frame, rendered
   through the golden model and shaded (:func:`phongfx.scene.geometry.shade`), stays
   within ``requirement.max_error_levels``; passes repeat until no single width can drop;
3. the **proof** of local minimality: for each width, the config with that width one
   lower and its measured max error (above the requirement), or "at range minimum".

Widths are the method's :class:`~phongfx.explore.methods.MethodSpec` parameters except ``n``,
``k`` and ``lights``, plus, for Lyon's datapaths, the normalizers' ``order`` (2 = g2,
1 = g1: g1 vs g2 is measured like a width) and, against true Phong, the shape
function's ``k`` (fewer squarings is cheaper; ``2^k = n`` makes ``f_k`` Phong's power).

Evaluation: each frame once per shininess *variant*: one when every material has a
single ``n``, else three, with each range material at its ``n_lo``, its rounded
geometric mean and its ``n_hi``.  Every render goes through the golden model of the whole
shader (unit and hardware blend, :mod:`phongfx.golden.shader`), so the error is measured
at its ``r``, ``g``, ``b`` outputs: per pixel and channel ``|out - level(I_ref)|`` in
display levels (:func:`~phongfx.scene.geometry.pixel_error`, an integer: how far the
displayed pixel is from the displayed reference), ``I_ref``
(:func:`phongfx.scene.geometry.shade`, the backside test included) from true Phong (``"phong"``: ``(R·L)^n`` and ``N·L`` at Phong's normal
(``FrameGeometry.normal``), and the exact light and viewer of the pixel) or from the
method's own float form (``"self"``); max and mean over all visible pixels and channels of
all renders, and ``max_unrounded`` against the reference before its rounding
(``|out - I_ref·(2^bits - 1)|``, which the outputs' own rounding puts at 0.5 at best).

Cost (to choose among methods), on the ``target`` asked for: on an FPGA LUT-eq (``LUT4 +
958·DSP``), on standard cells (``"asic"``) area in µm²; synthesized
(:func:`phongfx.explore.synth.synth`, cached) with ``synth=True``, else the tool-free
proxies :func:`phongfx.explore.cost_proxy.proxy_cost` (LUT-eq) and
:func:`phongfx.explore.cost_proxy.proxy_area` (µm², fitted to the standard-cell flow).
"""

from dataclasses import dataclass, field

import numpy as np

from phongfx.core.registry import get_block
from phongfx.explore.methods import METHODS
from phongfx.explore.synth import SynthError
from phongfx.golden.blend import blend
from phongfx.golden.fixed import Fixed
from phongfx.golden.reference import specular
from phongfx.golden.shader import shader_terms
from phongfx.scene.geometry import frames, pixel_error, shade, terminator_lit

from . import run as runs
from .analysis import analyse

__all__ = ["Compiled", "SceneEval", "COST_UNITS", "compile_scene", "check_methods", "width_params", "search_widths",
           "cost"]

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

    @property
    def best(self):
        return self.results.get(self.chosen)


def width_params(method, against="phong"):
    """``{name: (default, (lo, hi))}`` of the widths the search lowers; against ``"phong"``
    Lyon's datapaths add the shape function's ``k`` (up to :data:`~phongfx.explore.compile.run.K_MAX`;
    against ``"self"`` it stays at the default, as it defines the reference)."""
    spec = METHODS[method]
    out = {k: (v, spec.ranges[k]) for k, v in spec.params.items() if k not in _FIXED}
    out.update(runs.EXTRA.get(method, {}))
    if against == "phong" and method in runs.DATAPATHS:
        out["k"] = (spec.params["k"], (spec.ranges["k"][0], runs.K_MAX))
    return out


def _cosines(g):
    """(lights, P) exact ``N·L`` at Phong's normal."""
    return np.stack([np.sum(g.normal * light, -1) for light in g.light])


def _diffuse(g):
    """(lights, P) exact ``max(N·L, 0)`` at Phong's normal: every method's diffuse reference."""
    return np.maximum(_cosines(g), 0.0)


class SceneEval:
    """The scene's renders (frames × shininess variants) and their Phong references."""

    def __init__(self, spec, geometries=None):
        self.spec = spec
        self.geometries = frames(spec) if geometries is None else geometries
        if not any(len(g) for g in self.geometries):
            raise ValueError(f"{spec.name}: no object covers a pixel in any frame; nothing to compile")
        self.analysis = analyse(spec, self.geometries)
        self.bits = spec.output.bits
        #: per render of a frame, the n of each range material (empty: every n single)
        self.shininess_variants = []
        variants = self._variants()
        self.renders = [(g, n) for g in self.geometries for n in variants(g)]
        #: per render, true Phong's (lights, P) specular terms (the diffuse is the same for all)
        self.reference = [self._phong(g, n) for g, n in self.renders]
        self.cache = {}

    def _variants(self):
        """Per frame, the per-pixel n arrays of the shininess variants (module docstring)."""
        materials = list(self.spec.materials.values())
        ranged = [i for i, m in enumerate(materials) if m.n_lo is not None and m.n_lo != m.n_hi]

        names = list(self.spec.materials)
        picks = (lambda m: m.n_lo, lambda m: round(np.sqrt(m.n_lo * m.n_hi)), lambda m: m.n_hi)

        def variants(g):
            if not ranged:
                return [np.round(g.n).astype(np.int64)]
            out = []
            self.shininess_variants = [{names[i]: pick(materials[i]) for i in ranged} for pick in picks]
            for pick in picks:
                n = np.round(g.n).astype(np.int64)
                for i in ranged:
                    n[g.material == i] = pick(materials[i])
                out.append(n)
            return out
        return variants

    def _phong(self, g, n):
        return np.stack([specular("phong", g.normal, light, g.viewer, n) for light in g.light])

    def render(self, method, config, params, index):
        """``(codes, I_ref, raw inputs, raw outputs)`` of render ``index``: the shader's
        ``r``, ``g``, ``b`` codes (P, 3) and the float reference intensities (P, 3), whose
        backside test follows the shader's within the terminator band
        (:func:`~phongfx.scene.geometry.terminator_lit`)."""
        g, n = self.renders[index]
        raw = runs.frame_inputs(method, config, g, n)
        fixed = {name: Fixed(np.asarray(raw[name], dtype=np.int64), fmt)
                 for name, (fmt, _) in config.inputs.items()}
        terms = shader_terms(config, **fixed)
        out = {name: value.raw for name, value in blend(config.blend, **terms).items()}
        codes = runs.frame_codes(method, out, g)
        lit = None
        if config.blend.diff:  # the shader's own backside test, per light, at the visible pixels
            lit = np.stack([runs.visible(method, terms[f"diff{i}"].raw > 0, g)
                            for i in range(config.blend.lights)])
        if self.spec.requirement.against == "self":
            spec = runs.own_specular(method, config, params, g, n)
        else:
            spec = self.reference[index]
        diff = _diffuse(g)
        return codes, shade(g, diff, spec, lit=terminator_lit(_cosines(g), lit, self.bits)), raw, out

    def error(self, method, params):
        """``{"max", "mean", "max_unrounded"}`` error in levels of ``method`` at ``params``
        (cached; :func:`~phongfx.scene.geometry.pixel_error`); a config that cannot be built or overflows has
        ``max = inf`` and says why in ``"why"``."""
        key = (method, tuple(sorted(params.items())))
        if key not in self.cache:
            self.cache[key] = self._error(method, params)
        return self.cache[key]

    def _error(self, method, params):
        try:
            config = runs.build(method, params, self.analysis)
            renders = [self.render(method, config, params, i)[:2] for i in range(len(self.renders))]
        except (ValueError, OverflowError) as error:
            inf = float("inf")
            return {"max": inf, "mean": inf, "max_unrounded": inf, "why": str(error)}
        e = np.concatenate([pixel_error(codes, ref, self.bits).ravel() for codes, ref in renders])
        scale = (1 << self.bits) - 1
        raw = np.concatenate([np.abs(codes - ref * scale).ravel() for codes, ref in renders])
        return {"max": float(e.max(initial=0.0)), "mean": float(e.mean()) if e.size else 0.0,
                "max_unrounded": float(raw.max(initial=0.0))}


def _passes(scene, method, params):
    return scene.error(method, params)["max"] <= scene.spec.requirement.max_error_levels


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


def search_widths(scene, method, progress=None):
    """The width search of the module docstring; returns a result dict."""
    widths = width_params(method, scene.spec.requirement.against)
    default = {k: v for k, (v, _) in widths.items()}
    start = default if _passes(scene, method, default) else {k: r[1] for k, (_, r) in widths.items()}
    result = {"method": method, "default": {"params": default, **scene.error(method, default)}}
    if not _passes(scene, method, start):
        return {**result, "feasible": False, "params": start, **scene.error(method, start)}
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
                if measured["max"] <= scene.spec.requirement.max_error_levels:
                    params, changed = lower, True
                    break
                proof[name] = {"value": params[name], "lower": params[name] - 1,
                               **{k: measured[k] for k in ("max", "why") if k in measured}}
                proof[name]["max_error"] = proof[name].pop("max")
    return {**result, "feasible": True, "params": params, **scene.error(method, params), "proof": proof}


#: Per target: the key of the compared cost and its unit.
COST_UNITS = {"ecp5": ("lut_eq", "LUT-eq"), "ice40": ("lut_eq", "LUT-eq"), "asic": ("area_um2", "µm²")}


def cost(method, config, synth=False, copies=1, *, target="ecp5", device=None, freq=150, seed=1):
    """Cost of ``copies`` of ``method``'s block at ``config`` on ``target``: synthesis
    (``synth``) or the tool-free proxy.  ``cost`` is the compared number for every copy
    (LUT-eq on an FPGA, µm² on standard cells), also under its own key (``lut_eq`` or
    ``area_um2``); the other keys are per copy, and ``target``, ``device``, ``freq``,
    ``seed`` and ``model`` say what produced it."""
    from phongfx.explore.asic import DEFAULT_LIBRARY

    block = get_block(runs.block_name(method), config=config)
    key, unit_name = COST_UNITS[target]
    if target == "asic":
        device = device or DEFAULT_LIBRARY
    where = {"target": target, "device": device, "freq": freq if synth else None,
             "seed": seed if synth and target != "asic" else None,
             "model": f"{target}-synth" if synth else f"{target}-proxy", "unit": unit_name}
    if not synth:
        from phongfx.explore.cost_proxy import proxy_estimate
        unit = proxy_estimate(block, target, device)
    else:
        from phongfx.explore.synth import synth as run_synth
        result = run_synth(block.name, config=config, target=target, device=device, freq=freq, seed=seed)
        if target == "asic":
            keys = ("area_um2", "cell_count", "ff", "fmax_mhz", "latency", "critical_path")
            unit = {k: result[k] for k in keys}
        else:
            keys = ("lut4", "ff", "carry", "dsp", "bram_bits", "fmax_mhz", "latency")
            unit = {"lut_eq": result["lut4"] + 958 * result["dsp"], **{k: result[k] for k in keys}}
    total = copies * unit[key]
    return {**unit, key: total, "cost": total, "copies": copies, **where}


def check_methods(methods):
    """``methods`` as a list (all of :data:`~phongfx.explore.methods.METHODS` for None), each checked."""
    names = list(METHODS) if methods is None else list(methods)
    for name in names:
        if name not in METHODS:
            raise ValueError(f"method must be one of {', '.join(METHODS)}, not {name!r}")
    return names


def compile_scene(spec, *, methods=None, synth=False, target="ecp5", device=None, freq=150, progress=None,
                  geometries=None):
    """Compile ``spec`` (a :class:`~phongfx.scene.file.SceneSpec`): see the module docstring.

    Parameters
    ----------
    methods : sequence of str, optional
        Keys of :data:`~phongfx.explore.methods.METHODS` to consider (default all).
    synth : bool
        Cost by synthesis instead of the proxy.
    target, device, freq : str, str, float
        What the cost is measured on: ``"ecp5"`` (LUT-eq), ``"ice40"`` or ``"asic"``
        (µm²; ``device`` the library, default ``osu018``), and the clock given to the tools.
    progress : callable, optional
        Called with a short description of each step.

    Returns
    -------
    Compiled
    """
    names = check_methods(methods)
    scene = SceneEval(spec, geometries)
    if target not in COST_UNITS:
        raise ValueError(f"target must be one of {', '.join(COST_UNITS)}, not {target!r}")
    out = Compiled(spec, scene.analysis, scene, f"{target}-synth" if synth else f"{target}-proxy")
    for name in names:
        reason = runs.rejection(name, spec, scene.analysis, scene.geometries)
        if reason:
            out.rejected[name] = reason
            continue
        result = search_widths(scene, name, progress)
        # the default widths are costed always (the manifest's "saved against the defaults"),
        # the searched ones only when they meet the requirement
        for where in (result["default"], result) if result["feasible"] else (result["default"],):
            try:
                # the shader holds every copy of the unit and the blend: one design to cost
                where["cost"] = cost(name, runs.build(name, where["params"], scene.analysis), synth,
                                     1, target=target, device=device,
                                     freq=freq)
            except (ValueError, SynthError) as error:  # a tool failure costs that design only
                where["cost"] = {"cost": None, "why": str(error).splitlines()[0]}
        out.results[name] = result
        if progress:
            progress(f"{name} done")
    feasible = [r for r in out.results.values() if r["feasible"]]
    if feasible:  # an uncosted design (its synthesis failed) is chosen only if nothing else meets it
        out.chosen = min(feasible, key=lambda r: (r["cost"]["cost"] is None,
                                                  r["cost"]["cost"] or 0))["method"]
    return out
