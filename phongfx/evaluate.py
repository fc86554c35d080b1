"""One point of a bit-width sweep: a method at given widths, its error and its cost (issue 5 §2).

Every method runs on the same pixels: the :class:`~phongfx.mesh.Spans` of a named
reference scene (:data:`SCENES`: a 288-polygon torus in the spirit of Hast, Barrera &
Bengtsson §5, and a coarse UV sphere as Szirmay-Kalos et al. §6), one directional light
(:data:`phongfx.mesh_render.LIGHT`) and the viewer at infinity (``V = (0, 0, 1)``).

* Per-pixel datapaths (Lyon 1993 Figures 7, 8 and the halfway unit of Figure 5) get the
  span end normals ``N0``, ``N1`` and ``a = k/(length-1)``, as their LIRP needs; Schlick's
  unit gets ``t = N̂·H`` and the conventional baseline the interpolated ``N``
  (:mod:`phongfx.span_inputs`); the scanline units (Hast's Euler and Gouraud units,
  Szirmay-Kalos's spherical unit) get their per-span setup streams.
* The quantity compared is the **specular** term, except for ``euler`` and ``gouraud``,
  whose paper (Hast et al.) is about the **diffuse** ``N·L`` curve: theirs is ``N·L``.
* References, on the same pixels with the interpolated normal renormalized exactly
  (``N̂``): ``"phong"`` is per-pixel Phong of the same quantity — ``(R·L)^n`` for fig7 and
  fig8 (Lyon's reflection form), ``(N̂·H)^(4n)`` for the halfway datapath (Lyon's Blinn row
  5: the appendix scales its ``n`` by 4), ``(N̂·H)^n`` for spherical, schlick and
  conventional, ``max(N̂·L, 0)`` for euler and gouraud.  ``"self"`` is the method's own
  float form: Lyon's ``f_k`` rows (:mod:`phongfx.golden.reference`; Figure 8 at
  ``n = m²``), ``A^n·cos²(a·x)`` (Szirmay-Kalos eq. 19, :mod:`phongfx.mesh_render`
  ``cos2``), the float corrected Euler curve (Hast eqs. 16–17), the float chord, Schlick's
  ``t/(n - n·t + t)`` on the float ``t``, and float Phong for the conventional baseline.

Metrics are in 8-bit levels, ``e = 255·|fixed - float|`` over the visible pixels
(:func:`error_metrics`).  The datapaths are evaluated with one light (the lights are
independent copies), while :meth:`MethodSpec.config`, which synthesis sees, keeps the
``lights`` parameter (registry default 2).
"""

import functools
from dataclasses import dataclass, field

import numpy as np

from . import mesh as meshes
from .blocks import REGISTRY, get_block
from .golden import euler_setup
from .golden.reference import specular
from .mesh_render import LIGHT, shade
from .span_inputs import (VIEWER, conventional_inputs, decode, euler_inputs, gouraud_inputs, halfway,
                          schlick_inputs, spherical_inputs)
from .sim.vectors.datapath import encode

__all__ = ["MethodSpec", "METHODS", "Scene", "SCENES", "STATS", "REFERENCES", "COST_KEYS",
           "error_metrics", "evaluate"]

STATS = ("max", "mean", "psnr", "pct_over1")
REFERENCES = ("phong", "self")
COST_KEYS = ("lut4", "ff", "carry", "dsp", "bram_bits", "fmax_mhz", "mpixels_per_s", "latency")
_SYNTH_OPTIONS = ("target", "freq", "device", "seed", "workdir")


def _check_int(name, value, lo, hi):
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or not lo <= value <= hi:
        raise ValueError(f"{name} must be an integer in {lo}..{hi}, not {value!r}")
    return int(value)


@dataclass(frozen=True)
class MethodSpec:
    """A sweepable method: its registry block, its parameters and how to build and run it.

    ``params`` maps each parameter to its default, ``ranges`` to its ``(lo, hi)``
    (inclusive; a builder may narrow a range from another parameter, e.g. Euler's
    ``t_frac <= p_frac``).  The defaults build the registry's default config exactly.
    """

    name: str
    block: str
    params: dict
    ranges: dict
    build: object = field(repr=False, compare=False)
    run: object = field(repr=False, compare=False)

    def resolve(self, params):
        """``params`` over the defaults, every value checked against its range."""
        if not isinstance(params, dict):
            raise ValueError(f"params must be a dict, not {type(params).__name__}")
        unknown = sorted(set(params) - set(self.params))
        if unknown:
            raise ValueError(f"{unknown[0]} is not a parameter of {self.name}; "
                             f"parameters: {', '.join(self.params)}")
        merged = {**self.params, **params}
        return {name: _check_int(name, merged[name], *self.ranges[name]) for name in self.params}

    def config(self, params):
        """The block config of ``params`` (missing ones at their defaults)."""
        return self.build(self.resolve(params))


# --- configs -----------------------------------------------------------------------------

def _vec_formats(base, f, vec_int=1):
    """Lyon's direction-vector formats at ``f`` fraction bits, guard bits kept as the
    defaults have them (dot and normalizer ``+2``, ``D·D`` exact ``2f``)."""
    vec, guard = f"S{vec_int}.{f}", f"1.{f + 2}"
    return dict(lirp=base.lirp.replace(vec=vec, a=f"1.{f}", out=vec),
                normalize=base.normalize.replace(vec=vec, out=vec, z=guard, y2=guard, g=guard),
                diffuse=base.diffuse.replace(vec=vec))


def _build_fig7(p):
    base = REGISTRY["fig7"][0]()
    f, vec, x2 = p["vec_frac"], f"S1.{p['vec_frac']}", f"13.{p['x2_frac']}"
    return base.replace(**_vec_formats(base, f), lights=p["lights"],
                        reflect=base.reflect.replace(vec=vec, dot=f"S1.{f + 2}", out=vec),
                        difference=base.difference.replace(vec=vec, d=vec, dd=f"2.{2 * f}", x2=x2),
                        shape=base.shape.replace(x2=x2, t=f"1.{p['shape_t_frac']}", k=p["k"]))


def _build_fig8(p):
    base = REGISTRY["fig8"][0]()
    f, vec = p["vec_frac"], f"S1.{p['vec_frac']}"
    return base.replace(**_vec_formats(base, f), lights=p["lights"],
                        reflect=base.reflect.replace(vec=vec, dot=f"S1.{f + 2}", out=vec),
                        root=base.root.replace(vec=vec, d=vec, frac=f"0.{p['root_frac']}",
                                               t=f"1.{p['t_frac']}", k=p["k"]))


def _build_halfway(p):
    base = REGISTRY["halfway_datapath"][0]()
    f, x2 = p["vec_frac"], f"13.{p['x2_frac']}"
    h, guard = f"S2.{f + 1}", f"1.{f + 2}"
    unit = base.halfway.replace(vec=f"S1.{f}", hvec=h, dot=f"S2.{f + 2}", out=f"S2.{f}",
                                normalize=base.halfway.normalize.replace(vec=h, out=h, z=guard,
                                                                         y2=guard, g=guard))
    return base.replace(**_vec_formats(base, f), lights=p["lights"], halfway=unit,
                        difference=base.difference.replace(vec=f"S2.{f}", d=f"S1.{f}",
                                                           dd=f"2.{2 * f}", x2=x2),
                        shape=base.shape.replace(x2=x2, t=f"1.{p['shape_t_frac']}", k=p["k"]))


def _build_spherical(p):
    _check_int("addr_bits", p["addr_bits"], 2, min(p["theta_frac"] + 1, 16))
    return REGISTRY["spherical"][0]().replace(theta=f"S0.{p['theta_frac']}", addr_bits=p["addr_bits"],
                                              rom=f"0.{p['rom_bits']}")


def _build_euler(p):
    _check_int("t_frac", p["t_frac"], 8, p["p_frac"])
    _check_int("ds_frac", p["ds_frac"], 8, p["t_frac"])
    return REGISTRY["euler"][0]().replace(p=f"S1.{p['p_frac']}", t=f"S3.{p['t_frac']}",
                                          ds=f"S3.{p['ds_frac']}")


def _build_gouraud(p):
    _check_int("dp_frac", p["dp_frac"], 8, p["p_frac"])
    return REGISTRY["gouraud"][0]().replace(p=f"S1.{p['p_frac']}", dp=f"S3.{p['dp_frac']}")


def _build_schlick(p):
    return REGISTRY["schlick"][0]().replace(t=f"1.{p['t_frac']}", out=f"1.{p['out_frac']}")


def _build_conventional(p):
    return REGISTRY["conventional"][0]().replace(vec=f"S1.{p['vec_frac']}", rsqrt_addr=p["rsqrt_addr"],
                                                 log_addr=p["table_addr"], exp_addr=p["table_addr"])


# --- scenes ------------------------------------------------------------------------------

@dataclass(frozen=True)
class Scene:
    """A reference frame: ``mesh`` (``"torus"``: ``polygons`` quads; ``"sphere"``: ``stacks ×
    slices``) at animation ``frame`` of 200 (:func:`phongfx.mesh.rotation`), ``size``² pixels."""

    mesh: str
    frame: int
    size: int = 96
    polygons: int = 288
    stacks: int = 16
    slices: int = 32

    @functools.cached_property
    def data(self):
        """Spans, unit light and halfway vector, ``N̂`` (P, 3) and the visible mask."""
        shape = (meshes.torus(self.polygons) if self.mesh == "torus"
                 else meshes.uv_sphere(self.stacks, self.slices))
        spans = meshes.rasterize(shape, meshes.rotation(self.frame), self.size, self.size)
        light = np.asarray(LIGHT, dtype=np.float64) / np.linalg.norm(LIGHT)
        normals = spans.interpolated_normals()
        unit = normals / np.maximum(np.linalg.norm(normals, axis=-1, keepdims=True), 1e-300)
        return {"spans": spans, "light": light, "h": halfway(light), "normal": unit,
                "visible": spans.visible}


#: Frame 30 of the torus has part of the ring behind the rest (3516 of 3730 pixels visible).
SCENES = {"torus": Scene("torus", frame=30), "sphere": Scene("sphere", frame=20)}


# --- runs: (fixed, {"phong": float, "self": float}) per pixel ------------------------------

def _power(c, n):
    return np.where(c > 0, np.maximum(c, 0.0) ** n, 0.0)


def _datapath(spec, config, p, scene, own, phong="phong", n_self=None):
    """Figure 7 / 8 / halfway datapath on one light; floats by Lyon's ``specfuns.m`` rows."""
    d = scene.data
    spans, n = d["spans"], float(p["n"])
    span = spans.pixel_span()
    one = config.replace(lights=1)
    count = len(span)
    raw = encode(one, spans.na[span], spans.nb[span], spans.pixel_t(), np.full(count, n),
                 VIEWER, VIEWER, [d["light"]], [d["light"]])
    out = get_block(spec.block, config=one).golden(raw)
    fixed = out["spec0"] * one.outputs["spec0"][0].lsb
    args = (d["normal"], d["light"], VIEWER)
    return fixed, {"phong": specular(phong, *args, n),
                   "self": specular(own, *args, n if n_self is None else n_self)}


def _run_fig7(spec, config, p, scene):
    return _datapath(spec, config, p, scene, f"lyon-k{p['k']}")


def _run_fig8(spec, config, p, scene):
    m = min(max(round(np.sqrt(p["n"])), 1), config.root.m_max)  # what encode feeds
    return _datapath(spec, config, p, scene, f"lyon-k{p['k']}", n_self=float(m * m))


def _run_halfway(spec, config, p, scene):
    return _datapath(spec, config, p, scene, f"halfway-g2proj-k{p['k']}", phong="blinn")


def _nh_phong(scene, n):
    return _power(scene.data["normal"] @ scene.data["h"], n)


def _run_spherical(spec, config, p, scene):
    d = scene.data
    out = get_block("spherical", config=config).golden(spherical_inputs(d["spans"], d["light"], p["n"], config))
    self_ = shade(d["spans"], "cos2", light=d["light"], n=p["n"])[1]
    return decode("spherical", out, config, "spec"), {"phong": _nh_phong(scene, p["n"]), "self": self_}


def _diffuse_curves(scene):
    d = scene.data
    spans = d["spans"]
    setups = euler_setup.span_setups(spans.na, spans.nb, d["light"], spans.length)
    curves = euler_setup.curves_at(setups, spans.pixel_span(), spans.pixel_step())
    return {name: np.maximum(value, 0.0) for name, value in curves.items()}


def _run_scanline(unit, feed, own):
    def run(spec, config, p, scene):
        d = scene.data
        out = get_block(unit, config=config).golden(feed(d["spans"], d["light"], config))
        curves = _diffuse_curves(scene)
        return decode(unit, out, config), {"phong": curves["phong"], "self": curves[own]}
    return run


def _run_schlick(spec, config, p, scene):
    d, n = scene.data, p["n"]
    out = get_block("schlick", config=config).golden(schlick_inputs(d["spans"], d["light"], n, config))
    t = np.clip(d["normal"] @ d["h"], 0.0, 1.0)
    return decode("schlick", out, config), {"phong": _nh_phong(scene, n), "self": t / (n - n * t + t)}


def _run_conventional(spec, config, p, scene):
    d, n = scene.data, p["n"]
    out = get_block("conventional", config=config).golden(conventional_inputs(d["spans"], d["light"], n, config))
    phong = _nh_phong(scene, n)
    return decode("conventional", out, config, "spec"), {"phong": phong, "self": phong}


_VEC, _N, _LIGHTS = (4, 16), (1, 8000), (1, 8)
METHODS = {spec.name: spec for spec in (
    MethodSpec("fig7", "fig7", {"vec_frac": 10, "x2_frac": 12, "shape_t_frac": 15, "k": 2, "n": 16, "lights": 2},
               {"vec_frac": _VEC, "x2_frac": (4, 20), "shape_t_frac": (4, 24), "k": (0, 2), "n": _N,
                "lights": _LIGHTS}, _build_fig7, _run_fig7),
    MethodSpec("fig8", "fig8", {"vec_frac": 10, "root_frac": 9, "t_frac": 15, "k": 1, "n": 16, "lights": 2},
               {"vec_frac": _VEC, "root_frac": (4, 16), "t_frac": (4, 24), "k": (0, 2), "n": (1, 63 * 63),
                "lights": _LIGHTS}, _build_fig8, _run_fig8),
    MethodSpec("halfway", "halfway_datapath",
               {"vec_frac": 10, "x2_frac": 12, "shape_t_frac": 15, "k": 2, "n": 16, "lights": 2},
               {"vec_frac": _VEC, "x2_frac": (4, 20), "shape_t_frac": (4, 24), "k": (1, 2), "n": _N,
                "lights": _LIGHTS}, _build_halfway, _run_halfway),
    MethodSpec("spherical", "spherical", {"addr_bits": 6, "rom_bits": 6, "theta_frac": 11, "n": 16},
               {"addr_bits": (2, 16), "rom_bits": (2, 16), "theta_frac": (4, 20), "n": (1, 1000)},
               _build_spherical, _run_spherical),
    MethodSpec("euler", "euler", {"p_frac": 30, "t_frac": 30, "ds_frac": 30, "n": 16},
               {"p_frac": (8, 40), "t_frac": (8, 40), "ds_frac": (8, 40), "n": _N},
               _build_euler, _run_scanline("euler", euler_inputs, "corrected")),
    MethodSpec("gouraud", "gouraud", {"p_frac": 30, "dp_frac": 30, "n": 16},
               {"p_frac": (8, 40), "dp_frac": (8, 40), "n": _N},
               _build_gouraud, _run_scanline("gouraud", gouraud_inputs, "gouraud")),
    MethodSpec("schlick", "schlick", {"t_frac": 15, "out_frac": 15, "n": 16},
               {"t_frac": (2, 30), "out_frac": (2, 30), "n": _N}, _build_schlick, _run_schlick),
    MethodSpec("conventional", "conventional", {"vec_frac": 15, "rsqrt_addr": 9, "table_addr": 8, "n": 16},
               {"vec_frac": (6, 18), "rsqrt_addr": (2, 16), "table_addr": (1, 14), "n": _N},
               _build_conventional, _run_conventional),
)}


# --- metrics and the point ---------------------------------------------------------------

def error_metrics(value, reference, visible=None):
    """``{max, mean, psnr, pct_over1}`` of ``e = 255·|value - reference|`` (8-bit levels)
    over the ``visible`` pixels (all when None): ``psnr = 10·log10(255² / mean(e²))`` dB
    (``inf`` for no error), ``pct_over1`` the percentage of pixels with ``e > 1``."""
    e = 255 * np.abs(np.asarray(value, dtype=np.float64) - np.asarray(reference, dtype=np.float64))
    e = e if visible is None else e[np.asarray(visible, dtype=bool)]
    if not e.size:
        raise ValueError("visible must select at least one pixel, not 0")
    mse = float(np.mean(e * e))
    return {"max": float(e.max()), "mean": float(e.mean()),
            "psnr": float(10 * np.log10(255.0 ** 2 / mse)) if mse > 0 else float("inf"),
            "pct_over1": float(100 * np.mean(e > 1))}


def _cost(block, config, options):
    from . import synth as synth_module

    if not isinstance(options, dict):
        raise ValueError(f"synth must be a dict of options, not {type(options).__name__}")
    unknown = sorted(set(options) - set(_SYNTH_OPTIONS))
    if unknown:
        raise ValueError(f"synth option {unknown[0]!r} is not one of {', '.join(_SYNTH_OPTIONS)}")
    result = synth_module.synth(block, config=config, **options)
    cost = {key: result[key] for key in COST_KEYS if key != "mpixels_per_s"}
    cost["mpixels_per_s"] = result["pixels_per_second"] / 1e6
    return {key: cost[key] for key in COST_KEYS}


def evaluate(method, params, *, scenes=("torus", "sphere"), synth=None):
    """Error (and, with ``synth``, cost) of ``method`` at ``params`` (module docstring).

    Parameters
    ----------
    method : str
        A key of :data:`METHODS`.
    params : dict
        Parameters of the method; missing ones take their defaults.
    scenes : sequence of str
        Keys of :data:`SCENES`.
    synth : dict, optional
        Options of :func:`phongfx.synth.synth` (``target``, ``freq``, ``device``, ``seed``,
        ``workdir``); None skips synthesis.

    Returns
    -------
    dict
        ``metrics``: ``{"<scene>.<ref>.<stat>": float}`` for ``ref`` in :data:`REFERENCES`
        and ``stat`` in :data:`STATS`; ``cost``: ``{key: number}`` for :data:`COST_KEYS`
        (``mpixels_per_s`` = Fmax at one pixel per clock), or None without ``synth``.

    Raises
    ------
    ValueError
        For an unknown method, scene or synth option, or a parameter out of range.
    phongfx.synth.SynthError
        When a synthesis tool fails.
    """
    if method not in METHODS:
        raise ValueError(f"method must be one of {', '.join(METHODS)}, not {method!r}")
    if isinstance(scenes, str):
        scenes = (scenes,)
    for name in scenes:
        if name not in SCENES:
            raise ValueError(f"scene must be one of {', '.join(SCENES)}, not {name!r}")
    spec = METHODS[method]
    p = spec.resolve(params)
    config = spec.build(p)
    metrics = {}
    for name in scenes:
        scene = SCENES[name]
        fixed, floats = spec.run(spec, config, p, scene)
        for ref in REFERENCES:
            for stat, value in error_metrics(fixed, floats[ref], scene.data["visible"]).items():
                metrics[f"{name}.{ref}.{stat}"] = value
    cost = None if synth is None else _cost(spec.block, config, synth)
    return {"metrics": metrics, "cost": cost}
