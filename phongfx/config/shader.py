"""Configuration of a whole shader: a shading unit and the blend of its terms to r, g, b."""

from dataclasses import dataclass

from .base import BlockConfig, check_int
from .blend import BlendConfig
from .datapath import DatapathConfig, fig7_config

__all__ = ["ShaderConfig", "unit_terms"]

def unit_terms(unit, config):
    """``(diffuse port, lane, specular port)`` of each light a copy of ``unit`` (a registry
    block name) computes at ``config``; None for a unit that has no place in a shader.

    A datapath (any :class:`~phongfx.config.DatapathConfig`, whatever its specular unit)
    holds every light (``diff<i>``, ``spec<i>``); a unit computing one light per copy says
    which of its outputs are its terms in its config class's ``TERMS`` (Schlick's unit has no
    diffuse output, None; the spherical unit's ``diff`` is its vector's first lane)."""
    if isinstance(config, DatapathConfig):
        return [(f"diff{i}", None, f"spec{i}") for i in range(config.lights)]
    terms = getattr(config, "TERMS", None)
    return None if terms is None else [terms]


@dataclass(frozen=True)
class ShaderConfig(BlockConfig):
    """A shading unit (``unit``, a registry block that :func:`unit_terms` knows), one copy per entry
    of ``units`` (their configs), and the blend (:class:`BlendConfig`) of every light's
    diffuse and specular terms to the pixel's ``r``, ``g``, ``b`` codes.

    Lyon's datapaths hold every light in one copy; a unit that computes one light takes
    one copy per light, each with its own config (a point light's copy interpolates its
    L, a directional light's does not).  With one copy the shader's inputs are the
    unit's; with several, each copy's inputs are prefixed ``c<j>_``.  The blend takes the
    copies' lights in order (``blend.lights`` of them) and, with several materials, a
    ``material`` input.  Every copy must have the same latency (they run side by side).
    """

    unit: str = "fig7"
    units: tuple = (fig7_config(),)
    blend: BlendConfig = BlendConfig()

    def validate(self):
        from phongfx.core.registry import REGISTRY
        if self.unit not in REGISTRY or unit_terms(self.unit, REGISTRY[self.unit].default_config()) is None:
            configs = {name: entry.default_config() for name, entry in REGISTRY.items()}
            names = sorted((name for name, config in configs.items() if unit_terms(name, config)),
                           key=lambda name: not isinstance(configs[name], DatapathConfig))
            raise ValueError(f"unit must be one of {', '.join(names)}, not {self.unit!r}")
        if isinstance(self.units, list):  # a tuple stays hashable: build caches key on configs
            object.__setattr__(self, "units", tuple(self.units))
        if not isinstance(self.units, tuple):
            raise ValueError(f"units must be a tuple of unit configs, not {self.units!r}")
        check_int("copies (len(units))", len(self.units), 1, 8)
        kind = type(REGISTRY[self.unit].default_config())
        for index, config in enumerate(self.units):
            if not isinstance(config, kind):
                raise TypeError(f"units[{index}] must be a {kind.__name__}, not {config!r}")
        if not isinstance(self.blend, BlendConfig):
            raise TypeError(f"blend must be a BlendConfig, not {self.blend!r}")
        terms = self.terms
        if self.blend.lights != len(terms):
            raise ValueError(f"blend.lights must be {len(terms)} (the lights the units compute), "
                             f"not {self.blend.lights}")
        for copy, diff, lane, spec in terms:
            ports = self.units[copy].outputs
            has_diff = diff is not None
            if has_diff != bool(self.blend.diff):
                raise ValueError(f"blend.diff must be {'a format' if has_diff else 'empty'}: the "
                                 f"{self.unit} unit has {'a' if has_diff else 'no'} diffuse output")
            if has_diff and ports[diff][0] != self.blend.fmt("diff"):
                raise ValueError(f"blend.diff ({self.blend.diff}) must equal the unit's {diff} "
                                 f"({ports[diff][0]}): they are connected")
            if ports[spec][0] != self.blend.fmt("spec"):
                raise ValueError(f"blend.spec ({self.blend.spec}) must equal the unit's {spec} "
                                 f"({ports[spec][0]}): they are connected")

    @property
    def copies(self):
        return len(self.units)

    @property
    def terms(self):
        """``(copy, diffuse port, lane, specular port)`` of each light, in the blend's order."""
        return [(copy, *term) for copy, config in enumerate(self.units) for term in unit_terms(self.unit, config)]

    def prefix(self, copy):
        """The prefix of copy ``copy``'s inputs on the shader (none for a single copy)."""
        return "" if self.copies == 1 else f"c{copy}_"

    @property
    def inputs(self):
        ports = {}
        for copy, config in enumerate(self.units):
            ports.update({self.prefix(copy) + name: port for name, port in config.inputs.items()})
        if "material" in self.blend.inputs:
            ports["material"] = self.blend.inputs["material"]
        return ports

    @property
    def outputs(self):
        return self.blend.outputs

    def replace(self, **changes):
        """This config with fields ``changes``; any other setting (``vec_frac``, a unit's
        field) goes to every unit's config, and ``pipeline`` to the blend's as well."""
        own = {name: changes.pop(name) for name in ("unit", "units", "blend") if name in changes}
        if "pipeline" in changes:
            own["blend"] = own.get("blend", self.blend).replace(pipeline=changes["pipeline"])
        config = super().replace(**own) if own else self
        if changes:
            config = super(ShaderConfig, config).replace(
                units=tuple(unit.replace(**changes) for unit in config.units))
        return config
