"""The sweepable methods and the reference scenes of :mod:`phongfx.explore.evaluate`.

A method (:class:`phongfx.core.methods.Method`) names its block, its width parameters with
defaults and ranges, how to build the block config from them (its ``build`` face) and how to
run the golden model on a :class:`Scene` (its ``run`` face: the fixed-point result and its
float references per pixel); the ``build_NAME`` and ``run_NAME`` below are those faces.  The
quantities and references are described in :mod:`phongfx.explore.evaluate`.
"""


import functools
from dataclasses import dataclass

import numpy as np

from phongfx.core.limits import check_param
from phongfx.core.methods import get_method
from phongfx.core.registry import REGISTRY, get_block
from phongfx.golden import euler_setup
from phongfx.golden.reference import specular
from phongfx.render.mesh import LIGHT, shade
from phongfx.scene import mesh as meshes
from phongfx.scene.span_inputs import (VIEWER, blinn_inputs, conventional_inputs, decode, euler_inputs,
                                       gouraud_inputs, halfway, schlick_inputs, spherical_inputs)
from phongfx.sim.stimulus.datapath import encode

__all__ = ["Scene", "SCENES", "run_datapath",
           "build_spherical", "run_spherical", "build_euler", "run_euler", "build_gouraud", "run_gouraud",
           "build_schlick", "run_schlick", "build_blinn", "run_blinn", "build_conventional", "run_conventional"]


# --- configs -----------------------------------------------------------------------------

# The three Lyon datapaths take every direction-vector format from ``vec_frac`` through
# DatapathConfig's derived setting (Method.build), so a sweep point and ``--set vec_frac=F``
# agree.  Every other width is a field's fraction bits (``x2_frac``: ``x2``'s), its integer bits and sign
# those of the field's default (BlockConfig.frac_changes), never written here a second time.

def build_spherical(p):
    check_param("addr_bits", p["addr_bits"], 2, min(p["theta_frac"] + 1, 16))
    base = REGISTRY["spherical"].default_config()
    return base.replace(**base.frac_changes(theta=p["theta_frac"], rom=p["rom_bits"]), addr_bits=p["addr_bits"])


def build_euler(p):
    check_param("t_frac", p["t_frac"], 8, p["p_frac"])
    check_param("ds_frac", p["ds_frac"], 8, p["t_frac"])
    base = REGISTRY["euler"].default_config()
    return base.replace(**base.frac_changes(p=p["p_frac"], t=p["t_frac"], ds=p["ds_frac"]))


def build_gouraud(p):
    check_param("dp_frac", p["dp_frac"], 8, p["p_frac"])
    base = REGISTRY["gouraud"].default_config()
    return base.replace(**base.frac_changes(p=p["p_frac"], dp=p["dp_frac"]))


def build_schlick(p):
    base = REGISTRY["schlick"].default_config()
    return base.replace(**base.frac_changes(t=p["t_frac"], out=p["out_frac"]))


def _tables(block):
    """Builder of a unit on the tables of :mod:`phongfx.golden.blinn` (``blinn``,
    ``conventional``): ``vec`` at ``vec_frac`` fraction bits, the seed ROM's and the log and
    exp ROMs' address bits."""
    def build(p):
        base = REGISTRY[block].default_config()
        return base.replace(**base.frac_changes(vec=p["vec_frac"]), rsqrt_addr=p["rsqrt_addr"],
                            log_addr=p["table_addr"], exp_addr=p["table_addr"])
    return build


# --- scenes ------------------------------------------------------------------------------

@dataclass(frozen=True)
class Scene:
    """A reference frame: ``mesh`` (``"torus"``: ``polygons`` quads; ``"sphere"``: ``stacks ×
    slices``) at animation ``frame`` of 200 (:func:`phongfx.scene.mesh.rotation`), ``size``² pixels."""

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


# --- runs: (fixed, {"phong": float, "self": float}, terms) per pixel ------------------------
#
# ``terms`` are the unit's raw outputs that a shader's blend takes: ``{"diff": (codes,
# Format) or None, "spec": (codes, Format)}``, or None for the diffuse-only units (Euler,
# Gouraud), whose quantity compared is the diffuse term itself.


def _terms(outputs, ports, diff, spec, lane=None):
    """The blend's inputs among a unit's raw ``outputs``: ports ``diff`` (None: no diffuse
    output; ``lane``: a vector's lane) and ``spec``, with their formats from ``ports``."""
    def term(name):
        codes = np.asarray(outputs[name])
        return codes if lane is None or codes.ndim == 1 else codes[:, lane], ports[name][0]
    return {"diff": term(diff) if diff else None, "spec": term(spec)}

def _power(c, n):
    return np.where(c > 0, np.maximum(c, 0.0) ** n, 0.0)


def run_datapath(spec, config, p, scene):
    """A specular unit of the datapath on one light (the ``run`` face of every datapath
    method), against its float form (its registry entry's, e.g. Lyon's ``specfuns.m`` rows,
    at the shininess the hardware applies: Figure 8's ``m²``) and its compile face's
    ``phong_form``."""
    d = scene.data
    hooks = get_method(spec.name).load("compile")
    spans, n = d["spans"], float(p["n"])
    span = spans.pixel_span()
    one = config.replace(lights=1)
    count = len(span)
    raw = encode(one, spans.na[span], spans.nb[span], spans.pixel_t(), np.full(count, n),
                 VIEWER, VIEWER, [d["light"]], [d["light"]])
    out = get_block(spec.block, config=one).golden(raw)
    fixed = out["spec0"] * one.outputs["spec0"][0].lsb
    args = (d["normal"], d["light"], VIEWER)
    n_self = float(one.unit.applied_n(one, np.float64(n)))
    return fixed, {"phong": specular(hooks.phong_form, *args, n),
                   "self": specular(hooks.float_form(spec.name, p), *args, n_self)}, \
        _terms(out, one.outputs, "diff0", "spec0")


def _nh_phong(scene, n):
    return _power(scene.data["normal"] @ scene.data["h"], n)


def run_spherical(spec, config, p, scene):
    d = scene.data
    out = get_block("spherical", config=config).golden(spherical_inputs(d["spans"], d["light"], p["n"], config))
    self_ = shade(d["spans"], "cos2", light=d["light"], n=p["n"])[1]
    return decode(out, config, "spec"), {"phong": _nh_phong(scene, p["n"]), "self": self_}, \
        _terms(out, config.outputs, "diff", "spec", lane=0)


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
        return decode(out, config), {"phong": curves["phong"], "self": curves[own]}, None
    return run


def run_schlick(spec, config, p, scene):
    d, n = scene.data, p["n"]
    out = get_block("schlick", config=config).golden(schlick_inputs(d["spans"], d["light"], n, config))
    t = np.clip(d["normal"] @ d["h"], 0.0, 1.0)
    return decode(out, config), {"phong": _nh_phong(scene, n), "self": t / (n - n * t + t)}, \
        _terms(out, config.outputs, None, "spec")


def run_blinn(spec, config, p, scene):
    d, n = scene.data, p["n"]
    out = get_block("blinn", config=config).golden(blinn_inputs(d["spans"], d["light"], n, config))
    phong = _nh_phong(scene, n)
    return decode(out, config, "spec"), {"phong": phong, "self": phong}, \
        _terms(out, config.outputs, "diffuse", "specular")


def run_conventional(spec, config, p, scene):
    """Phong's own ``(R·V)^n`` on the interpolated ``N``; its float form is Phong with the
    backside test (0 where ``N̂·L <= 0``), which on these frames is Phong (lights in front of
    the viewer: ``R·V < 0`` wherever ``N̂·L < 0`` and ``N̂·V >= 0``)."""
    d, n = scene.data, p["n"]
    raw = conventional_inputs(d["spans"], d["light"], n, config)
    out = get_block("conventional", config=config).golden(raw)
    phong = specular("phong", d["normal"], d["light"], VIEWER, n)
    own = np.where(d["normal"] @ d["light"] > 0, phong, 0.0)
    return decode(out, config, "spec"), {"phong": phong, "self": own}, \
        _terms(out, config.outputs, "diffuse", "specular")


build_blinn, build_conventional = _tables("blinn"), _tables("conventional")
run_euler = _run_scanline("euler", euler_inputs, "corrected")
run_gouraud = _run_scanline("gouraud", gouraud_inputs, "gouraud")


