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

Adding a block is one entry below (the five paths, written out) plus its four files (and
their tests).
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

    @property
    def module(self):
        """The name of the block's files (``"root"``; ``"datapath"`` for the three datapaths):
        the end of its golden path, as of every other."""
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


# Every path is written out, one per line, so that grep, an IDE and tests/test_imports.py
# follow a block to each of its files.
#: name -> :class:`Entry`; the order is that of ``phongfx blocks`` and the tables.
REGISTRY = {entry.name: entry for entry in (
    Entry("lirp",
          config="phongfx.config.lirp:LirpConfig",
          golden="phongfx.golden.lirp:lirp",
          component="phongfx.hdl.lirp:Lirp",
          stimulus="phongfx.sim.stimulus.lirp:stimulus",
          extremes="phongfx.sim.stimulus.lirp:extremes"),
    Entry("normalize",
          config="phongfx.config.normalize:NormalizeConfig",
          golden="phongfx.golden.normalize:normalize",
          component="phongfx.hdl.normalize:Normalize",
          stimulus="phongfx.sim.stimulus.normalize:stimulus",
          extremes="phongfx.sim.stimulus.normalize:extremes"),
    Entry("reflect",
          config="phongfx.config.reflect:ReflectConfig",
          golden="phongfx.golden.reflect:reflect",
          component="phongfx.hdl.reflect:Reflect",
          stimulus="phongfx.sim.stimulus.reflect:stimulus",
          extremes="phongfx.sim.stimulus.reflect:extremes"),
    Entry("difference",
          config="phongfx.config.difference:DifferenceConfig",
          golden="phongfx.golden.difference:difference",
          component="phongfx.hdl.difference:Difference",
          stimulus="phongfx.sim.stimulus.difference:stimulus",
          extremes="phongfx.sim.stimulus.difference:extremes"),
    Entry("shape",
          config="phongfx.config.shape:ShapeConfig",
          golden="phongfx.golden.shape:shape",
          component="phongfx.hdl.shape:Shape",
          stimulus="phongfx.sim.stimulus.shape:stimulus",
          extremes="phongfx.sim.stimulus.shape:extremes"),
    Entry("diffuse",
          config="phongfx.config.diffuse:DiffuseConfig",
          golden="phongfx.golden.diffuse:diffuse",
          component="phongfx.hdl.diffuse:Diffuse",
          stimulus="phongfx.sim.stimulus.diffuse:stimulus",
          extremes="phongfx.sim.stimulus.diffuse:extremes"),
    Entry("root",
          config="phongfx.config.root:RootConfig",
          golden="phongfx.golden.root:root",
          component="phongfx.hdl.root:Root",
          stimulus="phongfx.sim.stimulus.root:stimulus",
          extremes="phongfx.sim.stimulus.root:extremes"),
    Entry("halfway",
          config="phongfx.config.halfway:HalfwayConfig",
          golden="phongfx.golden.halfway:halfway",
          component="phongfx.hdl.halfway:Halfway",
          stimulus="phongfx.sim.stimulus.halfway:stimulus",
          extremes="phongfx.sim.stimulus.halfway:extremes"),
    Entry("schlick",
          config="phongfx.config.schlick:SchlickConfig",
          golden="phongfx.golden.schlick:schlick",
          component="phongfx.hdl.schlick:Schlick",
          stimulus="phongfx.sim.stimulus.schlick:stimulus",
          extremes="phongfx.sim.stimulus.schlick:extremes"),
    Entry("spherical",
          config="phongfx.config.spherical:SphericalConfig",
          golden="phongfx.golden.spherical:spherical",
          component="phongfx.hdl.spherical:Spherical",
          stimulus="phongfx.sim.stimulus.spherical:stimulus",
          extremes="phongfx.sim.stimulus.spherical:extremes"),
    Entry("euler",
          config="phongfx.config.euler:EulerConfig",
          golden="phongfx.golden.euler:euler",
          component="phongfx.hdl.euler:Euler",
          stimulus="phongfx.sim.stimulus.euler:stimulus",
          extremes="phongfx.sim.stimulus.euler:extremes"),
    Entry("gouraud",
          config="phongfx.config.gouraud:GouraudConfig",
          golden="phongfx.golden.gouraud:gouraud",
          component="phongfx.hdl.gouraud:Gouraud",
          stimulus="phongfx.sim.stimulus.gouraud:stimulus",
          extremes="phongfx.sim.stimulus.gouraud:extremes"),
    Entry("blinn",
          config="phongfx.config.blinn:BlinnConfig",
          golden="phongfx.golden.blinn:blinn",
          component="phongfx.hdl.blinn:Blinn",
          stimulus="phongfx.sim.stimulus.blinn:stimulus",
          extremes="phongfx.sim.stimulus.blinn:extremes"),
    Entry("conventional",
          config="phongfx.config.conventional:ConventionalConfig",
          golden="phongfx.golden.conventional:conventional",
          component="phongfx.hdl.conventional:Conventional",
          stimulus="phongfx.sim.stimulus.conventional:stimulus",
          extremes="phongfx.sim.stimulus.conventional:extremes"),
    Entry("blend",
          config="phongfx.config.blend:BlendConfig",
          golden="phongfx.golden.blend:blend",
          component="phongfx.hdl.blend:Blend",
          stimulus="phongfx.sim.stimulus.blend:stimulus",
          extremes="phongfx.sim.stimulus.blend:extremes"),
    # the three datapaths of Lyon's Figures 7, 8 and 5: one component, three configs
    Entry("fig7",
          config="phongfx.config.datapath:fig7_config",
          golden="phongfx.golden.datapath:datapath",
          component="phongfx.hdl.datapath:Datapath",
          stimulus="phongfx.sim.stimulus.datapath:stimulus",
          extremes="phongfx.sim.stimulus.datapath:extremes"),
    Entry("fig8",
          config="phongfx.config.datapath:fig8_config",
          golden="phongfx.golden.datapath:datapath",
          component="phongfx.hdl.datapath:Datapath",
          stimulus="phongfx.sim.stimulus.datapath:stimulus",
          extremes="phongfx.sim.stimulus.datapath:extremes"),
    Entry("halfway_datapath",
          config="phongfx.config.datapath:halfway_config",
          golden="phongfx.golden.datapath:datapath",
          component="phongfx.hdl.datapath:Datapath",
          stimulus="phongfx.sim.stimulus.datapath:stimulus",
          extremes="phongfx.sim.stimulus.datapath:extremes"),
    # a whole shader: a unit above (one copy, or one per light) and the blend to r, g, b
    Entry("shader",
          config="phongfx.config.shader:ShaderConfig",
          golden="phongfx.golden.shader:shader",
          component="phongfx.hdl.shader:Shader",
          stimulus="phongfx.sim.stimulus.shader:stimulus",
          extremes="phongfx.sim.stimulus.shader:extremes"),
)}


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
