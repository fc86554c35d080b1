"""One point of a bit-width sweep: a method at given widths, its error and its cost.

Every method runs on the same pixels: the :class:`~phongfx.scene.mesh.Spans` of a named
reference scene (:data:`SCENES`: a 288-polygon torus in the spirit of Hast, Barrera &
Bengtsson §5, and a coarse UV sphere as Szirmay-Kalos et al. §6), one directional light
(:data:`phongfx.render.mesh.LIGHT`) and the viewer at infinity (``V = (0, 0, 1)``).

* Per-pixel datapaths (Lyon 1993 Figures 7, 8 and the halfway unit of Figure 5) get the
  span end normals ``N0``, ``N1`` and ``a = k/(length-1)``, as their LIRP needs; Schlick's
  unit gets ``t = N̂·H``, the Blinn–Phong and conventional Phong units the interpolated ``N``
  (:mod:`phongfx.scene.span_inputs`); the scanline units (Hast's Euler and Gouraud units,
  Szirmay-Kalos's spherical unit) get their per-span setup streams.
* The quantity compared is the **specular** term, except for ``euler`` and ``gouraud``,
  whose paper (Hast et al.) is about the **diffuse** ``N·L`` curve: theirs is ``N·L``.
* References, on the same pixels with the interpolated normal renormalized exactly
  (``N̂``): ``"phong"`` is per-pixel Phong of the same quantity — ``(R·L)^n`` for fig7 and
  fig8 (Lyon's reflection form), ``(N̂·H)^(4n)`` for the halfway datapath (Lyon's Blinn row
  5: the appendix scales its ``n`` by 4), ``(N̂·H)^n`` for spherical, schlick and
  blinn, Phong's own ``(R·V)^n`` for conventional, ``max(N̂·L, 0)`` for euler and
  gouraud.  ``"self"`` is the method's own float form: Lyon's ``f_k`` rows
  (:mod:`phongfx.golden.reference`; Figure 8 at ``n = m²``), ``A^n·cos²(a·x)`` (Szirmay-Kalos eq. 19, :mod:`phongfx.render.mesh`
  ``cos2``), the float corrected Euler curve (Hast eqs. 16–17), the float chord, Schlick's
  ``t/(n - n·t + t)`` on the float ``t``, float Phong for the Blinn–Phong baseline, and
  float Phong with its backside test (0 where ``N̂·L <= 0``) for the conventional unit.

Metrics are in 8-bit levels, ``e = 255·|fixed - float|`` over the visible pixels
(:func:`error_metrics`).  The **pixel** metrics ``<scene>.pixel-<ref>.*`` measure what a
shader built on the method shows: its raw diffuse and specular outputs through the
hardware blend (:mod:`phongfx.golden.blend`, the render weights ``AMBIENT + KD·diffuse +
KS·specular`` of :mod:`phongfx.render.mesh`, grey, :data:`PIXEL_COEF` fraction bits, the
backside test on the specular term) against the same formula in float on exact
``max(N̂·L, 0)`` and the reference's specular, both as 8-bit display codes
(:func:`pixel_metrics`; the terminator band as in the scene compiler,
:func:`phongfx.scene.geometry.terminator_lit`); a unit without a diffuse output (Schlick's)
blends its specular alone, and the diffuse-only units (Euler, Gouraud) have none.  The datapaths are evaluated with one light (the lights are
independent copies), while :meth:`Method.config <phongfx.core.methods.Method.config>`, which synthesis sees, keeps the
``lights`` parameter (registry default 2).
"""

import numpy as np

from phongfx.core.methods import METHODS
from phongfx.explore.methods import SCENES, Scene
from phongfx.explore.scene_files import file_views, is_scene_file

__all__ = ["Scene", "SCENES", "STATS", "REFERENCES", "PIXEL_COEF", "COST_KEYS",
           "ASIC_COST_KEYS", "error_metrics", "pixel_metrics", "pixel_errors", "evaluate"]

STATS = ("max", "mean", "psnr", "pct_over1")
REFERENCES = ("phong", "self")
#: Fraction bits of the pixel metrics' blend constants (:func:`pixel_metrics`).
PIXEL_COEF = 8
COST_KEYS = ("lut4", "ff", "carry", "dsp", "bram_bits", "fmax_mhz", "mpixels_per_s", "latency")
#: The cost of a standard-cell synthesis (``target = "asic"``): area in µm², cells, area × delay.
ASIC_COST_KEYS = ("area_um2", "cell_count", "ff", "fmax_mhz", "mpixels_per_s", "area_delay", "latency")
_SYNTH_OPTIONS = ("target", "freq", "device", "seed", "workdir")


# --- metrics and the point ---------------------------------------------------------------

def error_metrics(value, reference, visible=None):
    """``{max, mean, psnr, pct_over1}`` of ``e = 255·|value - reference|`` (8-bit levels)
    over the ``visible`` pixels (all when None): ``psnr = 10·log10(255² / mean(e²))`` dB
    (``inf`` for no error), ``pct_over1`` the percentage of pixels with ``e > 1``."""
    return _stats(255 * np.abs(np.asarray(value, dtype=np.float64) - np.asarray(reference, dtype=np.float64)),
                  visible)


def _stats(e, visible=None):
    """:func:`error_metrics` of errors ``e`` already in levels."""
    e = np.asarray(e, dtype=np.float64)
    e = e if visible is None else e[np.asarray(visible, dtype=bool)]
    if not e.size:
        raise ValueError("visible must select at least one pixel, not 0")
    mse = float(np.mean(e * e))
    return {"max": float(e.max()), "mean": float(e.mean()),
            "psnr": float(10 * np.log10(255.0 ** 2 / mse)) if mse > 0 else float("inf"),
            "pct_over1": float(100 * np.mean(e > 1))}


def pixel_metrics(terms, reference_spec, scene):
    """:func:`error_metrics` of a shader's 8-bit display codes (module docstring) from the unit's
    raw ``terms`` (``{"diff": (codes, Format) or None, "spec": (codes, Format)}``) against the
    float blend of exact diffuse and ``reference_spec``, over the scene's visible pixels."""
    return _stats(pixel_errors(terms, reference_spec, scene), scene.data["visible"])


def pixel_errors(terms, reference_spec, scene):
    """Per pixel, the display codes' distance of :func:`pixel_metrics` (every pixel, visible
    or not), so that several frames can be pooled into one set of statistics."""
    from phongfx.config import BlendConfig
    from phongfx.core.registry import get_block
    from phongfx.render.mesh import AMBIENT, KD, KS
    from phongfx.scene.geometry import levels, terminator_lit

    d = scene.data
    diff, spec = terms["diff"], terms["spec"]
    def grey(k):  # one material, one light, one grey RGB triple
        return (((k, k, k),),)

    blend = BlendConfig(lights=1, diff=str(diff[1]) if diff else "", spec=str(spec[1]), coef_frac=PIXEL_COEF,
                        bits=8, ambient=((AMBIENT,) * 3,), diffuse=grey(KD if diff else 0.0),
                        specular=grey(KS), gate=diff is not None)
    raw = {"spec0": spec[0], **({"diff0": diff[0]} if diff else {})}
    codes = get_block("blend", config=blend).golden(raw)["r"]
    cosine = d["normal"] @ d["light"]
    lit = terminator_lit(cosine, diff[0] > 0 if diff else None, 8)
    exact = (KD * np.maximum(cosine, 0.0) if diff else 0.0) + KS * np.where(lit, reference_spec, 0.0)
    reference = levels(np.clip(AMBIENT + exact, 0.0, 1.0), 8)
    return np.abs(codes - reference)  # whole codes, exactly


def _cost(block, config, options):
    from phongfx.explore.synth import fpga as synth_module

    if not isinstance(options, dict):
        raise ValueError(f"synth must be a dict of options, not {type(options).__name__}")
    unknown = sorted(set(options) - set(_SYNTH_OPTIONS))
    if unknown:
        raise ValueError(f"synth option {unknown[0]!r} is not one of {', '.join(_SYNTH_OPTIONS)}")
    result = synth_module.synth(block, config=config, **options)
    keys = ASIC_COST_KEYS if options.get("target") == "asic" else COST_KEYS
    cost = {key: result[key] for key in keys if key != "mpixels_per_s"}
    cost["mpixels_per_s"] = result["pixels_per_second"] / 1e6
    return {key: cost[key] for key in keys}


def _proxy(block, config, target):
    """The tool-free cost of ``block`` at ``config`` on ``target``
    (:func:`~phongfx.explore.synth.proxy.proxy_estimate`): µm² on ``"asic"`` (osu018), else
    LUT-eq and DSP tiles; ``model`` says it is a proxy."""
    from phongfx.core.registry import get_block

    from phongfx.explore.synth.proxy import proxy_estimate

    estimate = proxy_estimate(get_block(block, config), target)
    return {k: estimate[k] for k in ("area_um2", "lut_eq", "dsp", "model") if k in estimate}


def evaluate(method, params, *, scenes=("torus", "sphere"), synth=None, proxy=None):
    """Error (and, with ``synth``, cost) of ``method`` at ``params`` (module docstring).

    Parameters
    ----------
    method : str
        A key of :data:`METHODS`.
    params : dict
        Parameters of the method; missing ones take their defaults.
    scenes : sequence of str
        Keys of :data:`SCENES`, or paths of scene files (``.toml``,
        :mod:`phongfx.explore.scene_files`: every frame and light pooled, metrics named
        after the file's stem).
    synth : dict, optional
        Options of :func:`phongfx.explore.synth.fpga.synth` (``target``, ``freq``, ``device``, ``seed``,
        ``workdir``); None skips synthesis.
    proxy : str, optional
        Without ``synth``: a target (``"ecp5"``, ``"ice40"``, ``"asic"``) whose tool-free
        proxy gives the ``cost`` (``lut_eq`` or ``area_um2``, and ``model``).

    Returns
    -------
    dict
        ``metrics``: ``{"<scene>.<ref>.<stat>": float}`` for ``ref`` in :data:`REFERENCES`
        and ``stat`` in :data:`STATS`, and ``"<scene>.pixel-<ref>.<stat>"`` (the pixel
        metrics, every method but the diffuse-only ones); ``cost``: ``{key: number}`` for :data:`COST_KEYS`
        (``mpixels_per_s`` = Fmax at one pixel per clock), or None without ``synth``.

    Raises
    ------
    ValueError
        For an unknown method, scene or synth option, or a parameter out of range.
    phongfx.explore.synth.fpga.SynthError
        When a synthesis tool fails.
    """
    if method not in METHODS:
        raise ValueError(f"method must be one of {', '.join(METHODS)}, not {method!r}")
    if isinstance(scenes, str):
        scenes = (scenes,)
    views = {}
    for name in scenes:  # every scene checked before any is run
        if name in SCENES:
            views[name] = (SCENES[name],)
        elif is_scene_file(name):
            label, frames = file_views(name)
            views[label] = frames
        else:
            raise ValueError(f"scene must be one of {', '.join(SCENES)} or a scene file (.toml), not {name!r}")
    spec = METHODS[method]
    p = spec.resolve(params)
    config = spec.build(p)
    metrics = {}
    for name, frames in views.items():
        runs = [spec.run(spec, config, p, frame) for frame in frames]
        visible = np.concatenate([frame.data["visible"] for frame in frames])
        for ref in REFERENCES:
            # a scene file's frames and lights pool into one set of statistics
            errors = np.concatenate([255 * np.abs(np.asarray(fixed, dtype=np.float64)
                                                  - np.asarray(floats[ref], dtype=np.float64))
                                     for fixed, floats, _ in runs])
            for stat, value in _stats(errors, visible).items():
                metrics[f"{name}.{ref}.{stat}"] = value
            if runs[0][2] is not None:
                codes = np.concatenate([pixel_errors(terms, floats[ref], frame)
                                        for (_, floats, terms), frame in zip(runs, frames)])
                for stat, value in _stats(codes, visible).items():
                    metrics[f"{name}.pixel-{ref}.{stat}"] = value
    if synth is not None:
        cost = _cost(spec.block, config, synth)
    else:
        cost = None if proxy is None else _proxy(spec.block, config, proxy)
    return {"metrics": metrics, "cost": cost}
