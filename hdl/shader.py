"""A whole shader as one pipelined component: the shading unit's copies and the blend."""

from phongfx.config import ShaderConfig
from phongfx.core.registry import REGISTRY

from .blend import Blend
from .block import PipelinedBlock, unbuilt

__all__ = ["Shader"]


class Shader(PipelinedBlock):
    """The shading unit (one copy, or one per light) feeding :class:`~phongfx.hdl.blend.Blend`.

    The copies run side by side on their own inputs and the shared ones, one wire fanned
    out to every copy (:attr:`~phongfx.config.ShaderConfig.shared`);
    every light's diffuse and specular outputs and the pixel's ``material`` (delayed by the
    cycle tags to meet the slowest copy's) go to the blend, whose ``r``, ``g``, ``b`` are the
    shader's outputs.

    Latency: ``max(copy latencies) + blend``, each at its own pipeline depth.
    """

    config_class = ShaderConfig

    def __init__(self, config):
        super().__init__(config)
        component = REGISTRY[config.unit].load("component")
        self._units = [unbuilt(component(sub)) for sub in config.units]
        self._blend = unbuilt(Blend(config.blend))

    @property
    def _slowest(self):
        """The copy whose outputs come last: the others' wait for it (a point light's copy of
        the conventional unit normalizes its L, three cycles more than a directional one's)."""
        return max(self._units, key=lambda unit: unit.latency)

    @property
    def latency(self):
        return self._slowest.latency + self._blend.latency

    def datapath(self, m, i):
        c = self.config
        for copy, (unit, feed) in enumerate(zip(self._units, c.feeds(0))):
            m.submodules[f"unit{copy}"] = unit
            unit.feed(m, self.i.valid, {name: i[port] for name, port in feed.items()})
        m.submodules.blend = self._blend
        results = [unit.results() for unit in self._units]
        terms = {}
        for light, (copy, diff, lane, spec) in enumerate(c.terms):
            if diff is not None:
                value = results[copy][diff]
                terms[f"diff{light}"] = value if lane is None else value[lane]
            terms[f"spec{light}"] = results[copy][spec]
        if "material" in c.inputs:
            terms["material"] = i["material"]
        self._blend.feed(m, self._slowest.o.valid, terms)  # feed delays the faster copies' terms
        return {**self._blend.results(), "valid": self._blend.o.valid}
