"""The scene compiler: the cheapest datapath whose error a scene's viewer cannot see.

:func:`compile_scene` analyses the scene (:mod:`phongfx.explore.compile.analysis`), then for every
method of :data:`phongfx.explore.methods.METHODS` either records why it cannot represent the
scene (:func:`phongfx.explore.compile.run.rejection`) or searches its widths:

1. start from the method's default widths; if they miss the requirement, from every
   width at its range maximum and ``k`` at its best value there (:func:`widest`); if that
   misses too the method is infeasible, and
   :func:`~phongfx.explore.compile.infeasible.summary` reports its best measured point
   and why;
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
(:func:`phongfx.explore.synth.fpga.synth`, cached) with ``synth=True``, else the tool-free
proxies :func:`phongfx.explore.synth.proxy.proxy_cost` (LUT-eq) and
:func:`phongfx.explore.synth.proxy.proxy_area` (µm², fitted to the standard-cell flow).
"""

from dataclasses import dataclass, field

import numpy as np

from phongfx.core.registry import get_block
from phongfx.explore.methods import METHODS
from phongfx.explore.progress import Candidates
from phongfx.golden.blend import blend
from phongfx.golden.fixed import Fixed
from phongfx.golden.reference import specular
from phongfx.golden.shader import shader_terms
from phongfx.scene.geometry import frames, pixel_error, shade, terminator_lit

from . import run as runs
from .analysis import analyse
from .costing import COST_UNITS, TIE_MARGIN, costed, tie
from .infeasible import hint, summary
from .journal import Journal, scene_key

__all__ = ["Compiled", "SceneEval", "compile_scene", "check_methods", "width_params", "widest",
           "search_widths"]

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
    hint: dict = None                   # nothing feasible: infeasible.hint's way forward
    tie: dict = None                    # the runner-up within TIE_MARGIN of the chosen cost

    @property
    def best(self):
        return self.results.get(self.chosen)


def width_params(method, against="phong"):
    """``{name: (default, (lo, hi))}`` of the widths the search lowers; against ``"phong"``
    Lyon's datapaths add the shape function's ``k`` (its range up to
    :data:`~phongfx.config.shape.K_MAX`; against ``"self"`` it stays at the default, as it
    defines the reference)."""
    spec = METHODS[method]
    out = {k: (v, spec.ranges[k]) for k, v in spec.params.items() if k not in _FIXED}
    out.update(runs.extra(method))
    if against == "phong" and runs.is_datapath(method) and "k" in spec.params:
        out["k"] = (spec.params["k"], spec.ranges["k"])
    return out


def _cosines(g):
    """(lights, P) exact ``N·L`` at Phong's normal."""
    return np.stack([np.sum(g.normal * light, -1) for light in g.light])


def _diffuse(g):
    """(lights, P) exact ``max(N·L, 0)`` at Phong's normal: every method's diffuse reference."""
    return np.maximum(_cosines(g), 0.0)


class SceneEval:
    """The scene's renders (frames × shininess variants) and their Phong references."""

    def __init__(self, spec, geometries=None, journal=None):
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
        #: per render, the index of its shininess variant (0 when every n is single)
        self.variant_of = [i for g in self.geometries for i, _ in enumerate(variants(g))]
        #: per render, true Phong's (lights, P) specular terms (the diffuse is the same for all)
        self.reference = [self._phong(g, n) for g, n in self.renders]
        #: ``journal``: a folder where measured points are kept for a rerun (:mod:`.journal`)
        self.journal = None if journal is None else Journal(journal, scene_key(spec, self.geometries))
        self.cache = {} if self.journal is None else self.journal.load()
        self.resumed = len(self.cache)

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
            if self.journal is not None:
                self.journal.add(key, self.cache[key])
        return self.cache[key]

    def _error(self, method, params):
        try:
            config = runs.build(method, params, self.analysis)
            renders = [self.render(method, config, params, i)[:2] for i in range(len(self.renders))]
        except (ValueError, OverflowError) as error:
            inf = float("inf")
            return {"max": inf, "mean": inf, "max_unrounded": inf, "why": str(error)}
        each = [pixel_error(codes, ref, self.bits).ravel() for codes, ref in renders]
        e = np.concatenate(each)
        scale = (1 << self.bits) - 1
        raw = np.concatenate([np.abs(codes - ref * scale).ravel() for codes, ref in renders])
        return {"max": float(e.max(initial=0.0)), "mean": float(e.mean()) if e.size else 0.0,
                "max_unrounded": float(raw.max(initial=0.0)),
                "per_render": [float(r.max(initial=0.0)) for r in each]}

    def measured(self, method, params):
        """:meth:`error` without its per-render list: what a result and the manifest keep."""
        return {k: v for k, v in self.error(method, params).items() if k != "per_render"}

    def form_error(self, method, params):
        """Max over every render of ``|I_form - I_ref|·(2^bits - 1)``: how far the method's
        own float form (at ``params``' ``k``) is from true Phong, before any rounding."""
        config = runs.build(method, params, self.analysis)
        scale, worst = (1 << self.bits) - 1, 0.0
        for (g, n), ref in zip(self.renders, self.reference):
            lit = terminator_lit(_cosines(g), None, self.bits)
            own = runs.own_specular(method, config, params, g, n)
            diff = _diffuse(g)
            worst = max(worst, float(np.max(np.abs(shade(g, diff, own, lit) - shade(g, diff, ref, lit)),
                                            initial=0.0)) * scale)
        return worst


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


def widest(scene, method, widths):
    """The fallback start: every width at its range maximum, and the shape function's ``k``
    (when searched) at the value of its range with the lowest error there, since ``f_k`` is
    Phong's power only where ``2^k = n`` (a larger k is not closer).  Returns the params
    and ``{k: error}`` of the scan (empty without ``k``)."""
    top = {k: r[1] for k, (_, r) in widths.items()}
    if "k" not in widths:
        return top, {}
    lo, hi = widths["k"][1]
    scan = {k: scene.error(method, {**top, "k": k}) for k in range(lo, hi + 1)}
    return {**top, "k": min(scan, key=lambda k: (scan[k]["max"], scan[k]["mean"], k))}, scan


def search_widths(scene, method, progress=None):
    """The width search of the module docstring; returns a result dict (an infeasible
    method's is :func:`~phongfx.explore.compile.infeasible.summary`)."""
    widths = width_params(method, scene.spec.requirement.against)
    default = {k: v for k, (v, _) in widths.items()}
    start, scan = (default, {}) if _passes(scene, method, default) else widest(scene, method, widths)
    result = {"method": method, "default": {"params": default, **scene.measured(method, default)}}
    if not _passes(scene, method, start):
        return {**result, **summary(scene, method, start, scan)}
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
    return {**result, "feasible": True, "params": params, **scene.measured(method, params), "proof": proof}


def check_methods(methods):
    """``methods`` as a list (all of :data:`~phongfx.explore.methods.METHODS` for None), each checked."""
    names = list(METHODS) if methods is None else list(methods)
    for name in names:
        if name not in METHODS:
            raise ValueError(f"method must be one of {', '.join(METHODS)}, not {name!r}")
    return names


def _proven(scene, ranked, timeout, progress):
    """``ranked`` from the first design without a counterexample to its overflow claims
    on: each proven in turn (``result["overflow_proof"]``) until one has none."""
    from phongfx.sim.prove import prove

    for index, result in enumerate(ranked):
        name = result["method"]
        block = get_block(runs.block_name(name), config=runs.build(name, result["params"], scene.analysis))
        proof = prove(block, timeout=timeout, progress=progress and (lambda text: progress(f"prove {name}: {text}")))
        result["overflow_proof"] = proof.as_dict()
        if not proof.counts.get("counterexample"):
            return ranked[index:]
    return []


def compile_scene(spec, *, methods=None, synth=False, target="ecp5", device=None, freq=150, seed=1,
                  progress=None, geometries=None, journal=None, prove=False, prove_timeout=600):
    """Compile ``spec`` (a :class:`~phongfx.scene.file.SceneSpec`): see the module docstring.

    :param methods: keys of :data:`~phongfx.explore.methods.METHODS` to consider (default
        all).
    :param bool synth: cost by synthesis instead of the proxy.
    :param target: what the cost is measured on: ``"ecp5"`` (LUT-eq), ``"ice40"`` or
        ``"asic"`` (µm²); with ``device`` (the part, or the library on ``"asic"``, default
        ``osu018``), ``freq`` (the clock given to the tools, MHz) and ``seed`` (nextpnr's
        placement seed).
    :param progress: called with a short description of each step; each synthesis as
        "synthesizing candidate i of N (method, widths) T s" and its flow's stages.
    :param journal: a folder where every measured width point is kept, so that a rerun of
        the same scene (and code) skips them (:mod:`phongfx.explore.compile.journal`).
    :param prove: prove the chosen design's ``overflow="error"`` claims
        (:mod:`phongfx.sim.prove`, ``prove_timeout`` seconds per claim); a design with a
        counterexample is not chosen and the next cheapest is proven instead.
    :returns: a :class:`Compiled`.
    """
    names = check_methods(methods)
    if target not in COST_UNITS:
        raise ValueError(f"target must be one of {', '.join(COST_UNITS)}, not {target!r}")
    scene = SceneEval(spec, geometries, journal=journal)
    out = Compiled(spec, scene.analysis, scene, f"{target}-synth" if synth else f"{target}-proxy")
    for name in names:
        reason = runs.rejection(name, spec, scene.analysis, scene.geometries)
        if reason:
            out.rejected[name] = reason
            continue
        out.results[name] = search_widths(scene, name, progress)
        if progress:
            progress(f"{name} searched")
    # the default widths are costed always (the manifest's "saved against the defaults"),
    # the searched ones only when they meet the requirement; an infeasible method's
    # defaults by the proxy only, since its synthesis (minutes) cannot change the choice
    designs = [(name, where, synth and r["feasible"]) for name, r in out.results.items()
               for where in ((r["default"], r) if r["feasible"] else (r["default"],))]
    steps = Candidates(sum(by_synth for *_, by_synth in designs), progress or (lambda text: None))
    for name, where, by_synth in designs:
        stage = steps.next(name, where["params"]) if by_synth else None
        where["cost"] = costed(name, runs.build(name, where["params"], scene.analysis), by_synth,
                               target=target, device=device, freq=freq, seed=seed, progress=stage)
    feasible = [r for r in out.results.values() if r["feasible"]]
    if feasible:  # an uncosted design (its synthesis failed) is chosen only if nothing else meets it
        ranked = sorted(feasible, key=lambda r: (r["cost"]["cost"] is None, r["cost"]["cost"] or 0))
        if prove:
            ranked = _proven(scene, ranked, prove_timeout, progress)
        if ranked:
            out.chosen = ranked[0]["method"]
            out.tie = tie(ranked, TIE_MARGIN)
    out.hint = hint(out)
    return out
