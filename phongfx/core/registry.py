"""The registry of datapath blocks by name: one :class:`Entry` per block.

A block exists in four places, one file each, all named after it:
``phongfx/config/NAME.py`` (its formats), ``golden/NAME.py`` (what the numbers must be),
``hdl/NAME.py`` (the Amaranth component) and ``sim/stimulus/NAME.py`` (its test input
codes and its extreme-input rows).  An entry names the objects in those files; they are
imported on first use (as is what a :class:`Block` needs of the golden and hdl layers), so
this module imports nothing of phongfx, not even inside a function, and every layer may use
it.  ``get_block("shape", k=1)`` gives a :class:`Block`: the block with those config fields
changed.  The CLI (``phongfx verilog``, ``phongfx sim``), the tables
and the tests choose blocks from here.

Adding a block is one line below plus its four files (and their tests).
"""

import sys
from dataclasses import dataclass
from importlib import import_module

import numpy as np

__all__ = ["Entry", "Block", "REGISTRY", "get_block", "block_names"]


#: What a :class:`Block` needs of the layers above, loaded by path as the faces are: the
#: golden value type its raw codes become, the chunk-by-chunk run of a golden model
#: (:mod:`phongfx.golden.chunks`), and the marking of a component built only to be asked
#: its latency (:func:`phongfx.hdl.block.unbuilt`).
FIXED = "phongfx.golden.fixed:Fixed"
CHUNKS = "phongfx.golden.chunks"
UNBUILT = "phongfx.hdl.block:unbuilt"


def _load(path):
    module, _, name = path.partition(":")
    return getattr(sys.modules.get(module) or import_module(module), name)


@dataclass(frozen=True)
class Entry:
    """Where the faces of one registered block live, as ``"module:name"`` paths.

    ``config`` is the config class or factory whose no-argument call is the block's
    default configuration; ``golden`` the golden function ``golden(config, **inputs)``;
    ``component`` the Amaranth component class ``component(config)``; ``stimulus`` the
    function ``stimulus(config, count, seed)`` of raw input codes; ``extremes`` the
    function ``extremes(block_name)`` of its :class:`~phongfx.sim.stimulus.extreme.Extreme` rows.
    """

    name: str
    config: str
    golden: str
    component: str
    stimulus: str
    extremes: str

    @classmethod
    def of(cls, name, config, component, *, module=None, golden=None):
        """The entry of a block whose four files are named ``module`` (default ``name``):
        ``config`` and ``component`` are class names, ``golden`` the golden function's
        name (default ``module``)."""
        module = module or name
        return cls(name, f"phongfx.config.{module}:{config}",
                   f"phongfx.golden.{module}:{golden or module}",
                   f"phongfx.hdl.{module}:{component}",
                   f"phongfx.sim.stimulus.{module}:stimulus",
                   f"phongfx.sim.stimulus.{module}:extremes")

    @property
    def module(self):
        """The name of the block's files (``"root"``; ``"datapath"`` for the three datapaths),
        as the naming rule of :meth:`of` puts it at the end of every path."""
        return self.golden.partition(":")[0].rpartition(".")[2]

    def load(self, face):
        """The object behind the path of field ``face`` (``"config"``, ``"golden"``, ...)."""
        return _load(getattr(self, face))

    def default_config(self):
        """The block's default configuration."""
        return self.load("config")()


@dataclass(frozen=True)
class Block:
    """One datapath block: its configuration and its faces, loaded (a test may swap one,
    e.g. ``dataclasses.replace(block, component_class=Other)``)."""

    name: str
    config: object
    golden_function: object
    component_class: object
    stimulus_function: object
    extremes_function: object

    def golden(self, raw_inputs, whole=False):
        """Run the golden model on raw input codes; returns raw output codes (int64 arrays).

        A block without state runs :data:`phongfx.golden.chunks.CHUNK` pixels at a time
        unless ``whole``: the same outputs, faster (:mod:`phongfx.golden.chunks`)."""
        chunks = sys.modules.get(CHUNKS) or import_module(CHUNKS)
        raw = {name: np.asarray(raw_inputs[name], dtype=np.int64) for name in self.config.inputs}
        if whole or not chunks.stateless(raw):
            return self._golden(raw)
        return chunks.chunked(self._golden, raw)

    def _golden(self, raw_inputs):
        fixed_type = _load(FIXED)
        fixed = {name: fixed_type(raw_inputs[name], fmt) for name, (fmt, lanes) in self.config.inputs.items()}
        outputs = self.golden_function(self.config, **fixed)
        result = {}
        for name, (fmt, lanes) in self.config.outputs.items():
            value = outputs[name]
            if value.fmt != fmt:
                raise ValueError(f"golden {self.name} output {name} has format {value.fmt}, "
                                 f"the config declares {fmt}")
            result[name] = value.raw
        return result

    def component(self):
        return self.component_class(self.config)

    @property
    def latency(self):
        """The component's latency in cycles (builds it without elaborating)."""
        return _load(UNBUILT)(self.component()).latency

    def stimulus(self, count=1000, seed=0):
        """Raw input codes: directed extremes, exhaustive sets where small, then seeded random."""
        return self.stimulus_function(self.config, count=count, seed=seed)

    def extremes(self):
        """The block's extreme-input rows (:class:`~phongfx.sim.stimulus.extreme.Extreme`)."""
        return self.extremes_function(self.name)


_ = Entry.of
#: name -> :class:`Entry`; the order is that of ``phongfx blocks`` and the tables.
REGISTRY = {entry.name: entry for entry in (
    _("lirp", "LirpConfig", "Lirp"),
    _("normalize", "NormalizeConfig", "Normalize"),
    _("reflect", "ReflectConfig", "Reflect"),
    _("difference", "DifferenceConfig", "Difference"),
    _("shape", "ShapeConfig", "Shape"),
    _("diffuse", "DiffuseConfig", "Diffuse"),
    _("root", "RootConfig", "Root"),
    _("halfway", "HalfwayConfig", "Halfway"),
    _("schlick", "SchlickConfig", "Schlick"),
    _("spherical", "SphericalConfig", "Spherical"),
    _("euler", "EulerConfig", "Euler"),
    _("gouraud", "GouraudConfig", "Gouraud"),
    _("blinn", "BlinnConfig", "Blinn"),
    _("conventional", "ConventionalConfig", "Conventional"),
    _("blend", "BlendConfig", "Blend"),
    # the three datapaths of Lyon's Figures 7, 8 and 5: one component, three configs
    _("fig7", "fig7_config", "Datapath", module="datapath"),
    _("fig8", "fig8_config", "Datapath", module="datapath"),
    _("halfway_datapath", "halfway_config", "Datapath", module="datapath"),
    # a whole shader: a unit above (one copy, or one per light) and the blend to r, g, b
    _("shader", "ShaderConfig", "Shader"),
)}
del _


def block_names():
    return tuple(REGISTRY)


def get_block(name, config=None, **changes):
    """The block called ``name`` with its default config (or ``config``), fields ``changes`` applied."""
    if name not in REGISTRY:
        raise ValueError(f"unknown block {name!r}; valid blocks: {', '.join(REGISTRY)}")
    entry = REGISTRY[name]
    if config is None:
        config = entry.default_config()
    if changes:
        config = config.replace(**changes)
    return Block(name, config, entry.load("golden"), entry.load("component"), entry.load("stimulus"),
                 entry.load("extremes"))
