"""Registry of datapath blocks by name: config, golden model, component, test vectors.

Each entry names where the three faces of a block live; they are imported on
first use.  ``get_block("shape", k=1)`` gives a :class:`Block` whose config has
those fields changed.  The CLI (``phongfx verilog``, ``phongfx sim``) and the
tests choose blocks from here.
"""

from dataclasses import dataclass
from importlib import import_module

import numpy as np

from . import config as _config

__all__ = ["Block", "REGISTRY", "get_block", "block_names"]


@dataclass(frozen=True)
class Block:
    """One datapath block: its configuration and how to model, build and exercise it."""

    name: str
    config: _config.BlockConfig
    golden_function: object
    component_class: object
    vectors_function: object

    def golden(self, raw_inputs):
        """Run the golden model on raw input codes; returns raw output codes (int64 arrays)."""
        from .golden.fixed import Fixed
        fixed = {}
        for name, (fmt, lanes) in self.config.inputs.items():
            raw = np.asarray(raw_inputs[name], dtype=np.int64)
            fixed[name] = Fixed(raw, fmt)
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
        component = self.component()
        component._MustUse__silence = True  # only asked for a number; not meant to be built
        return component.latency

    def vectors(self, count=1000, seed=0):
        """Raw input codes: directed extremes, exhaustive sets where small, then seeded random."""
        return self.vectors_function(self.config, count=count, seed=seed)


def _load(path):
    module, name = path.split(":")
    return getattr(import_module(module), name)


_DATAPATH = ("phongfx.golden.datapath:datapath", "phongfx.hdl.datapath:Datapath",
             "phongfx.sim.vectors.datapath:vectors")

# name: (config factory, golden function, component class, vectors function)
REGISTRY = {
    "lirp": (_config.LirpConfig, "phongfx.golden.lirp:lirp", "phongfx.hdl.lirp:Lirp",
             "phongfx.sim.vectors.lirp:vectors"),
    "normalize": (_config.NormalizeConfig, "phongfx.golden.normalize:normalize",
                  "phongfx.hdl.normalize:Normalize", "phongfx.sim.vectors.normalize:vectors"),
    "reflect": (_config.ReflectConfig, "phongfx.golden.reflect:reflect",
                "phongfx.hdl.reflect:Reflect", "phongfx.sim.vectors.reflect:vectors"),
    "difference": (_config.DifferenceConfig, "phongfx.golden.difference:difference",
                   "phongfx.hdl.difference:Difference", "phongfx.sim.vectors.difference:vectors"),
    "shape": (_config.ShapeConfig, "phongfx.golden.shape:shape", "phongfx.hdl.shape:Shape",
              "phongfx.sim.vectors.shape:vectors"),
    "diffuse": (_config.DiffuseConfig, "phongfx.golden.diffuse:diffuse",
                "phongfx.hdl.diffuse:Diffuse", "phongfx.sim.vectors.diffuse:vectors"),
    "root": (_config.RootConfig, "phongfx.golden.root:root", "phongfx.hdl.root:Root",
             "phongfx.sim.vectors.root:vectors"),
    "halfway": (_config.HalfwayConfig, "phongfx.golden.halfway:halfway",
                "phongfx.hdl.halfway:Halfway", "phongfx.sim.vectors.halfway:vectors"),
    "schlick": (_config.SchlickConfig, "phongfx.golden.schlick:schlick", "phongfx.hdl.schlick:Schlick",
                "phongfx.sim.vectors.schlick:vectors"),
    "spherical": (_config.SphericalConfig, "phongfx.golden.spherical:spherical",
                  "phongfx.hdl.spherical:Spherical", "phongfx.sim.vectors.spherical:vectors"),
    "euler": (_config.EulerConfig, "phongfx.golden.euler:euler", "phongfx.hdl.euler:Euler",
              "phongfx.sim.vectors.euler:vectors"),
    "gouraud": (_config.GouraudConfig, "phongfx.golden.gouraud:gouraud",
                "phongfx.hdl.gouraud:Gouraud", "phongfx.sim.vectors.gouraud:vectors"),
    "conventional": (_config.ConventionalConfig, "phongfx.golden.conventional:conventional",
                     "phongfx.hdl.conventional:Conventional", "phongfx.sim.vectors.conventional:vectors"),
    "fig7": (_config.fig7_config, *_DATAPATH),
    "fig8": (_config.fig8_config, *_DATAPATH),
    "halfway_datapath": (_config.halfway_config, *_DATAPATH),
}


def block_names():
    return tuple(REGISTRY)


def get_block(name, config=None, **changes):
    """The block called ``name`` with its default config (or ``config``), fields ``changes`` applied."""
    if name not in REGISTRY:
        raise ValueError(f"unknown block {name!r}; valid blocks: {', '.join(REGISTRY)}")
    config_class, golden, component, vectors = REGISTRY[name]
    if config is None:
        config = config_class()
    if changes:
        config = config.replace(**changes)
    return Block(name, config, _load(golden), _load(component), _load(vectors))
