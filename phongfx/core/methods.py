"""The registry of shading methods by name: one :class:`Method` per method, declared once.

A method is what ``phongfx compile`` chooses between, what a sweep varies and what
``phongfx render mesh`` shades with: Lyon's datapaths (a *specular unit* after the
normalizer of :class:`~phongfx.config.DatapathConfig`: ``fig7``, ``fig8``, ``halfway``)
and the standalone units (``spherical``, ``euler``, ...).  Its entry names its hardware
block (a name of :data:`phongfx.core.registry.REGISTRY`), the parameters the sweeps and
the compiler search with their defaults and inclusive ranges, and its *faces*: the
objects that carry its behaviour in each layer, as ``"module:name"`` paths loaded on
first use (as the block registry does), so that every layer may read this registry and
none imports a layer above it:

* ``unit`` (config), ``golden`` (golden), ``component`` (hdl): a specular unit's place
  in the datapath: its sub-configs, links and shininess port
  (:class:`phongfx.config.base.SpecularUnit`), its golden model per light and its
  wiring inside :class:`phongfx.hdl.datapath.Datapath`.  Only the datapath methods have them.
* ``build`` and ``run`` (explore): the block config of a parameter point and the golden
  run on a reference scene with the float forms it is measured against
  (:class:`phongfx.explore.methods.MethodSpec`).
* ``compile`` (explore): how the compiler fits the method to a scene file and feeds it
  (span-input layout, copies per light, the float form of ``against = "self"``;
  :class:`phongfx.explore.compile.units.Hooks`).
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

from .limits import K_MAX, check_range

__all__ = ["Method", "METHODS", "FACES", "get_method", "method_names", "specular_units"]

#: The faces a method may name, lowest layer first.
FACES = ("unit", "golden", "component", "build", "run", "compile", "shade")


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

    @property
    def is_datapath(self):
        """Whether the method is a specular unit of Lyon's datapath (it has a ``unit`` face)."""
        return "unit" in self.faces


def _datapath(name, block, faces, params, ranges, float_form, shade=True, compile="DATAPATH"):
    """A specular unit of the datapath: ``faces`` ``(unit, golden, component)``, the first in
    ``phongfx.config`` (the config module of its block), the others in
    :mod:`phongfx.golden.datapath` and :mod:`phongfx.hdl.datapath`; the sweep run of every
    datapath and the compiler hooks of :mod:`phongfx.explore.compile.units`."""
    unit, golden, component = faces
    faces = {"unit": f"phongfx.config.{unit}", "golden": f"phongfx.golden.datapath:{golden}",
             "component": f"phongfx.hdl.datapath:{component}",
             "run": "phongfx.explore.methods:run_datapath", "compile": f"phongfx.explore.compile.units:{compile}"}
    if shade:
        faces["shade"] = "phongfx.render.mesh:shade_datapath"
    return Method(name, block, params, ranges, faces, float_form)


def _unit(name, params, ranges, compile, shade):
    """A standalone unit named as its block, its builder and run in :mod:`phongfx.explore.methods`."""
    faces = {"build": f"phongfx.explore.methods:build_{name}", "run": f"phongfx.explore.methods:run_{name}",
             "compile": f"phongfx.explore.compile.units:{compile}"}
    if shade:
        faces["shade"] = f"phongfx.render.mesh:{shade}"
    return Method(name, name, params, ranges, faces)


# Search ranges; those of a setting with a limit (phongfx.core.limits) are checked inside it.
_VEC, _N, _LIGHTS, _K = (4, 16), (1, 8000), (1, 8), (0, K_MAX)
_SHAPE = {"vec_frac": 10, "x2_frac": 12, "shape_t_frac": 15, "k": 2, "n": 16, "lights": 2}
_TABLES = {"vec_frac": 15, "rsqrt_addr": 9, "table_addr": 8, "n": 16}
_TABLE_RANGES = {"vec_frac": (6, 18), "rsqrt_addr": (2, 16), "table_addr": (1, 14), "n": _N}

#: name -> :class:`Method`; the order is that of ``phongfx compile --methods`` and the sweeps.
METHODS = {method.name: method for method in (
    _datapath("fig7", "fig7", ("shape:FIG7", "fig7", "Fig7Unit"), _SHAPE,
              {"vec_frac": _VEC, "x2_frac": (4, 20), "shape_t_frac": (4, 24), "k": _K, "n": _N,
               "lights": _LIGHTS}, "lyon-k{k}", shade=False),
    _datapath("fig8", "fig8", ("root:FIG8", "fig8", "Fig8Unit"),
              {"vec_frac": 10, "root_frac": 9, "t_frac": 15, "k": 1, "n": 16, "lights": 2},
              {"vec_frac": _VEC, "root_frac": (4, 16), "t_frac": (4, 24), "k": _K, "n": (1, 63 * 63),
               "lights": _LIGHTS}, "lyon-k{k}", shade=False, compile="FIG8"),
    _datapath("halfway", "halfway_datapath", ("halfway:HALFWAY", "halfway_unit", "HalfwayUnit"), _SHAPE,
              {"vec_frac": _VEC, "x2_frac": (4, 20), "shape_t_frac": (4, 24), "k": (1, _K[1]), "n": _N,
               "lights": _LIGHTS}, "halfway-g2proj-k{k}", shade=False, compile="HALFWAY"),
    _unit("spherical", {"addr_bits": 6, "rom_bits": 6, "theta_frac": 11, "n": 16},
          {"addr_bits": (2, 16), "rom_bits": (2, 16), "theta_frac": (4, 20), "n": (1, 1000)},
          "SPHERICAL", "shade_spherical"),
    _unit("euler", {"p_frac": 30, "t_frac": 30, "ds_frac": 30, "n": 16},
          {"p_frac": (8, 40), "t_frac": (8, 40), "ds_frac": (8, 40), "n": _N}, "DIFFUSE_ONLY", "shade_euler"),
    _unit("gouraud", {"p_frac": 30, "dp_frac": 30, "n": 16},
          {"p_frac": (8, 40), "dp_frac": (8, 40), "n": _N}, "DIFFUSE_ONLY", "shade_gouraud"),
    _unit("schlick", {"t_frac": 15, "out_frac": 15, "n": 16},
          {"t_frac": (2, 30), "out_frac": (2, 30), "n": _N}, "SCHLICK", None),
    _unit("blinn", _TABLES, _TABLE_RANGES, "BLINN", "shade_blinn"),
    _unit("conventional", _TABLES, _TABLE_RANGES, "CONVENTIONAL", "shade_conventional"),
)}


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
