"""The registry of shading methods by name: one :class:`Method` per method, declared once.

A method is what ``phongfx compile`` chooses between, what a sweep varies and what
``phongfx render mesh`` shades with: Lyon's datapaths (a *specular unit* after the
normalizer of :class:`~phongfx.config.DatapathConfig`: ``fig7``, ``fig8``, ``halfway``)
and the standalone units (``spherical``, ``euler``, ...).  Its entry names its hardware
block (a name of :data:`phongfx.core.registry.REGISTRY`), the parameters the sweeps and
the compiler search with their defaults and inclusive ranges, and its *faces*: the
objects that carry its behaviour in each layer, as ``"module:name"`` paths written out
in full (one per line) and loaded on first use (as the block registry does), so that every
layer may read this registry and none imports a layer above it:

* ``unit`` (config), ``golden`` (golden), ``component`` (hdl): a specular unit's place
  in the datapath: its sub-configs, links and shininess port
  (:class:`phongfx.config.base.SpecularUnit`), its golden model per light and its
  wiring inside :class:`phongfx.hdl.datapath.Datapath`.  Only the datapath methods have them.
* ``inputs`` (scene): a standalone unit's raw input stream of a rasterized frame,
  ``inputs(spans, light, n=..., config=...)`` (:mod:`phongfx.scene.span_inputs`); the
  outputs are read back through its config's ``SHADES``.
* ``build`` and ``run`` (explore): the block config of a parameter point and the golden
  run on a reference scene with the float forms it is measured against
  (:meth:`Method.config`, :attr:`Method.run`).
* ``compile`` (explore): how the compiler fits the method to a scene file and feeds it
  (span-input layout, copies per light, the float form of ``against = "self"``;
  :class:`phongfx.explore.compile.units.Hooks`).
* ``contract`` (deliver): the input contract's entry of each of its unit's inputs
  (:mod:`phongfx.deliver.contract`), absent for a method the compiler never ships.
* ``certify`` (certify): the bounding method of its certificate
  (:mod:`phongfx.certify.bounding`), absent for a method no compiled design can be.
* ``shade`` (render): the per-pixel ``(diffuse, specular)`` of a mesh frame
  (``phongfx render mesh``), absent for a method that the renderer does not show.

Adding a method is its entry in :data:`METHODS` (and its block's in the block registry)
plus the objects its faces name.  A new specular unit ``NAME`` of the datapath writes its
block's four files as any block does (``phongfx/config/NAME.py`` with its
:class:`~phongfx.config.base.SpecularUnit` beside the block config, ``golden/NAME.py`` with
its golden face, ``hdl/NAME.py`` with its :class:`~phongfx.hdl.datapath.SpecularUnit`,
``sim/stimulus/NAME.py``), gives :class:`~phongfx.config.DatapathConfig` a field for its
sub-config, and names its float form (a row of :mod:`phongfx.golden.reference`, a sixth file
if it is new); the datapath, the sweeps, the compiler (``--methods``) and ``render mesh``
then take it, ``tests/core/test_adding_a_block.py`` shows how.
"""

import sys
from dataclasses import dataclass, field
from importlib import import_module

from .limits import K_MAX, check_param, check_range
from .registry import REGISTRY

__all__ = ["Method", "METHODS", "BASELINE", "FACES", "get_method", "method_names", "specular_units"]

#: The faces a method may name, lowest layer first.
FACES = ("unit", "golden", "component", "inputs", "shade", "contract", "build", "run", "compile", "certify")


@dataclass(frozen=True)
class Method:
    """One shading method: its ``block``, its search ``params`` (name -> default) and
    ``ranges`` (name -> inclusive ``(lo, hi)``), and its ``faces`` (:data:`FACES` ->
    ``"module:name"``).  The defaults build the block registry's default config exactly.

    ``float_form``: a datapath unit's float form, the reference it is measured against
    (``against = "self"``): a method of :func:`phongfx.golden.reference.specular`, ``{k}``
    standing for the parameter ``k``.  A datapath method without a ``build`` face is built
    by its unit's :meth:`~phongfx.config.base.SpecularUnit.sweep`."""

    name: str
    block: str
    params: dict = field(compare=False)
    ranges: dict = field(compare=False)
    faces: dict = field(compare=False)
    float_form: str = ""

    def __post_init__(self):
        unknown = sorted(set(self.faces) - set(FACES))
        if unknown:
            raise ValueError(f"faces must be among {', '.join(FACES)}, not {unknown[0]!r}")
        if set(self.params) != set(self.ranges):
            raise ValueError(f"ranges must name the parameters of {self.name} ({', '.join(self.params)}), "
                             f"not {', '.join(self.ranges)}")
        for name, (lo, hi) in self.ranges.items():
            check_range(self.name, name, lo, hi)

    def has(self, face):
        return face in self.faces

    def load(self, face):
        """The object behind face ``face``."""
        if face not in self.faces:
            raise ValueError(f"method {self.name} has no {face} face; it has {', '.join(self.faces)}")
        module, _, name = self.faces[face].partition(":")
        # the golden models ask for faces on every call: an imported module straight from
        # sys.modules (import_module's own look-up costs ten times more)
        return getattr(sys.modules.get(module) or import_module(module), name)

    def resolve(self, params):
        """``params`` over the defaults, every value checked against its range."""
        if not isinstance(params, dict):
            raise ValueError(f"params must be a dict, not {type(params).__name__}")
        unknown = sorted(set(params) - set(self.params))
        if unknown:
            raise ValueError(f"{unknown[0]} is not a parameter of {self.name}; "
                             f"parameters: {', '.join(self.params)}")
        merged = {**self.params, **params}
        return {name: check_param(name, merged[name], *self.ranges[name]) for name in self.params}

    @property
    def build(self):
        """``build(params)``: the block config of resolved ``params``, its ``build`` face; a
        datapath method without one: its block's default config with every direction vector
        at ``vec_frac`` and ``lights``, then its unit's own parameters
        (:meth:`~phongfx.config.base.SpecularUnit.sweep`)."""
        if self.has("build"):
            return self.load("build")
        return self._sweep_datapath

    def _sweep_datapath(self, p):
        base = REGISTRY[self.block].default_config().replace(vec_frac=p["vec_frac"], lights=p["lights"])
        return base.unit.sweep(base, p)

    @property
    def run(self):
        """``run(method, config, params, scene)``: its golden run on a reference scene of the
        sweeps, with the float forms it is measured against (its ``run`` face)."""
        return self.load("run")

    def config(self, params):
        """The block config of ``params`` (missing ones at their defaults)."""
        return self.build(self.resolve(params))

    @property
    def is_datapath(self):
        """Whether the method is a specular unit of Lyon's datapath (it has a ``unit`` face)."""
        return "unit" in self.faces


# Search ranges; those of a setting with a limit (phongfx.core.limits) are checked inside it.
_VEC, _N, _LIGHTS, _K = (4, 16), (1, 8000), (1, 8), (0, K_MAX)
_SHAPE = {"vec_frac": 10, "x2_frac": 12, "shape_t_frac": 15, "k": 2, "n": 16, "lights": 2}
_TABLES = {"vec_frac": 15, "rsqrt_addr": 9, "table_addr": 8, "n": 16}
_TABLE_RANGES = {"vec_frac": (6, 18), "rsqrt_addr": (2, 16), "table_addr": (1, 14), "n": _N}

# Every face is written out as the import path of its object, one per line, so that grep, an
# IDE and tests/test_imports.py follow a method to each of its objects.
#: name -> :class:`Method`; the order is that of ``phongfx compile --methods`` and the sweeps.
METHODS = {method.name: method for method in (
    Method("fig7", "fig7", _SHAPE,
           {"vec_frac": _VEC, "x2_frac": (4, 20), "shape_t_frac": (4, 24), "k": _K, "n": _N, "lights": _LIGHTS},
           {"unit": "phongfx.config.shape:FIG7",
            "golden": "phongfx.golden.datapath:fig7",
            "component": "phongfx.hdl.datapath:Fig7Unit",
            "run": "phongfx.explore.methods:run_datapath",
            "contract": "phongfx.deliver.contract:datapath_entry",
            "compile": "phongfx.explore.compile.units:DATAPATH",
            "certify": "phongfx.certify.figures:FIG7_BOUND"},
           "lyon-k{k}"),
    Method("fig8", "fig8", {"vec_frac": 10, "root_frac": 9, "t_frac": 15, "k": 1, "n": 16, "lights": 2},
           {"vec_frac": _VEC, "root_frac": (4, 16), "t_frac": (4, 24), "k": _K, "n": (1, 63 * 63),
            "lights": _LIGHTS},
           {"unit": "phongfx.config.root:FIG8",
            "golden": "phongfx.golden.datapath:fig8",
            "component": "phongfx.hdl.datapath:Fig8Unit",
            "run": "phongfx.explore.methods:run_datapath",
            "contract": "phongfx.deliver.contract:datapath_entry",
            "compile": "phongfx.explore.compile.units:FIG8",
            "certify": "phongfx.certify.figures:FIG8_BOUND"},
           "lyon-k{k}"),
    Method("halfway", "halfway_datapath", _SHAPE,
           {"vec_frac": _VEC, "x2_frac": (4, 20), "shape_t_frac": (4, 24), "k": (1, _K[1]), "n": _N,
            "lights": _LIGHTS},
           {"unit": "phongfx.config.halfway:HALFWAY",
            "golden": "phongfx.golden.datapath:halfway_unit",
            "component": "phongfx.hdl.datapath:HalfwayUnit",
            "run": "phongfx.explore.methods:run_datapath",
            "contract": "phongfx.deliver.contract:datapath_entry",
            "compile": "phongfx.explore.compile.units:HALFWAY",
            "certify": "phongfx.certify.figures:HALFWAY_BOUND"},
           "halfway-g2proj-k{k}"),
    Method("spherical", "spherical", {"addr_bits": 6, "rom_bits": 6, "theta_frac": 11, "n": 16},
           {"addr_bits": (2, 16), "rom_bits": (2, 16), "theta_frac": (4, 20), "n": (1, 1000)},
           {"inputs": "phongfx.scene.span_inputs:spherical_inputs",
            "shade": "phongfx.render.mesh:shade_spherical",
            "build": "phongfx.explore.methods:build_spherical",
            "run": "phongfx.explore.methods:run_spherical",
            "contract": "phongfx.deliver.contract:spherical_entry",
            "compile": "phongfx.explore.compile.units:SPHERICAL",
            "certify": "phongfx.certify.spherical:SPHERICAL"}),
    Method("euler", "euler", {"p_frac": 30, "t_frac": 30, "ds_frac": 30, "n": 16},
           {"p_frac": (8, 40), "t_frac": (8, 40), "ds_frac": (8, 40), "n": _N},
           {"inputs": "phongfx.scene.span_inputs:euler_inputs",
            "shade": "phongfx.render.mesh:shade_euler",
            "build": "phongfx.explore.methods:build_euler",
            "run": "phongfx.explore.methods:run_euler",
            "compile": "phongfx.explore.compile.units:DIFFUSE_ONLY"}),
    Method("gouraud", "gouraud", {"p_frac": 30, "dp_frac": 30, "n": 16},
           {"p_frac": (8, 40), "dp_frac": (8, 40), "n": _N},
           {"inputs": "phongfx.scene.span_inputs:gouraud_inputs",
            "shade": "phongfx.render.mesh:shade_gouraud",
            "build": "phongfx.explore.methods:build_gouraud",
            "run": "phongfx.explore.methods:run_gouraud",
            "compile": "phongfx.explore.compile.units:DIFFUSE_ONLY"}),
    Method("schlick", "schlick", {"t_frac": 15, "out_frac": 15, "n": 16},
           {"t_frac": (2, 30), "out_frac": (2, 30), "n": _N},
           {"inputs": "phongfx.scene.span_inputs:schlick_inputs",
            "build": "phongfx.explore.methods:build_schlick",
            "run": "phongfx.explore.methods:run_schlick",
            "compile": "phongfx.explore.compile.units:SCHLICK"}),
    Method("blinn", "blinn", _TABLES, _TABLE_RANGES,
           {"inputs": "phongfx.scene.span_inputs:blinn_inputs",
            "shade": "phongfx.render.mesh:shade_blinn",
            "build": "phongfx.explore.methods:build_blinn",
            "run": "phongfx.explore.methods:run_blinn",
            "contract": "phongfx.deliver.contract:per_pixel_entry",
            "compile": "phongfx.explore.compile.units:BLINN",
            "certify": "phongfx.certify.table_units:BLINN_BOUND"}),
    Method("conventional", "conventional", _TABLES, _TABLE_RANGES,
           {"inputs": "phongfx.scene.span_inputs:conventional_inputs",
            "shade": "phongfx.render.mesh:shade_conventional",
            "build": "phongfx.explore.methods:build_conventional",
            "run": "phongfx.explore.methods:run_conventional",
            "contract": "phongfx.deliver.contract:per_pixel_entry",
            "compile": "phongfx.explore.compile.units:CONVENTIONAL",
            "certify": "phongfx.certify.table_units:CONVENTIONAL_BOUND"}),
)}


#: The method every compiled design is set against (the manifest's ``"conventional_baseline"``):
#: Phong's own unit (rsqrt, reflect, power tables), what a designer would build without Lyon.
BASELINE = "conventional"


def method_names():
    return tuple(METHODS)


def specular_units():
    """The names of the datapath's specular units (the methods with a ``unit`` face)."""
    return tuple(name for name, method in METHODS.items() if method.is_datapath)


def get_method(name):
    """The :class:`Method` called ``name``; ValueError naming the methods otherwise."""
    if name not in METHODS:
        raise ValueError(f"method must be one of {', '.join(METHODS)}, not {name!r}")
    return METHODS[name]
