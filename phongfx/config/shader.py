"""Configuration of a whole shader: a shading unit and the blend of its terms to r, g, b."""

from dataclasses import dataclass

from .base import BlockConfig, check_int
from .blend import BlendConfig
from .datapath import DatapathConfig, fig7_config

__all__ = ["ShaderConfig", "intervals", "unit_terms"]

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


def intervals(lights):
    """The initiation intervals a shader of ``lights`` lights can take: each ``I`` in
    ``1..lights`` whose ``ceil(lights / I)`` lights per cycle need all ``I`` cycles (4 lights
    take 1, 2 or 4: at 3, two lights per cycle are done in 2 cycles and one would idle)."""
    return [i for i in range(1, lights + 1) if -(-lights // -(-lights // i)) == i]


@dataclass(frozen=True)
class ShaderConfig(BlockConfig):
    """A shading unit (``unit``, a registry block that
    :func:`~phongfx.config.shader.unit_terms` knows), one copy per entry of ``units`` (their
    configs), and the blend (:class:`BlendConfig`) of every light's diffuse and specular terms
    to the pixel's ``r``, ``g``, ``b`` codes.

    Lyon's datapaths hold every light in one copy; a unit that computes one light takes
    one copy per light, each with its own config (a point light's copy interpolates its
    L, a directional light's does not).  With one copy the shader's inputs are the
    unit's; with several, each copy's inputs are prefixed ``c<j>_``, except the
    :attr:`shared` ones.  The blend takes the copies' lights in order (``blend.lights`` of
    them) and, with several materials, a ``material`` input.  Every copy must have the same
    latency (they run side by side).

    **Shared per-pixel work** (``share``, default True).  What does not depend on the light
    -- the normal N's inputs, ``n``, V's when every copy takes it alike -- is one input of the
    shader, unprefixed, that fans out to every copy (each unit class names its per-light
    inputs in ``PER_LIGHT``).  The top takes the normal once whatever the number of lights,
    where per-copy inputs could contradict each other, and a synthesizer merges the copies'
    identical work on it (N's normalizer, and N̂·V): two lights of the conventional unit at
    its defaults after Yosys' ``proc; flatten; opt_merge; opt_clean`` are 597 cells shared
    against 693 per copy (−14 %; 2,964 against 3,481 with the ROMs mapped to logic,
    ``memory_map``), Blinn's 518 against 589 (−12 %); on ECP5 (``synth_ecp5``, LFE5U-45F) the
    conventional pair is 3,573 LUT4 and 42 DSPs shared against 4,388 and 48 per copy (LUT-eq
    −13 %).  ``share=False`` keeps one input per copy, to measure that saving.

    **Light sharing** (``interval``, default 1).  The ``lights`` lights are computed in
    ``interval`` clock cycles by ``ceil(lights / interval)`` lights' worth of hardware
    (:attr:`per_cycle`): for a one-light unit that many physical copies, copy ``j`` serving
    light ``t·per_cycle + j`` in cycle ``t``; for Lyon's datapath one datapath of
    ``per_cycle`` lights fed light group ``t`` in cycle ``t``.  The shader takes every
    light's inputs at once, at most one pixel per ``interval`` clocks, and blends once all
    groups are done: the same codes as at interval 1.  Lights that share a physical unit
    must have equal configs (the same unit config; for a datapath, the same local flag).
    ``interval`` must be one of :func:`~phongfx.config.shader.intervals`.  Two lights of the conventional unit at
    interval 2 on ECP5: 2,510 LUT4 and 24 DSPs, 41.3 MHz (20.6 Mpixel/s), against 3,573, 42
    and 37.5 MHz (37.5 Mpixel/s) at interval 1 (LUT-eq −42 %).
    """

    unit: str = "fig7"
    units: tuple = (fig7_config(),)
    blend: BlendConfig = BlendConfig()
    share: bool = True
    interval: int = 1

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
        if not isinstance(self.share, bool):
            raise ValueError(f"share must be True or False, not {self.share!r}")
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
        self._check_interval()

    def _check_interval(self):
        lights = len(self.terms)
        check_int(f"interval ({lights} lights)", self.interval, 1, lights)
        if self.interval not in intervals(lights):
            per = -(-lights // self.interval)
            raise ValueError(f"interval must be one of {', '.join(map(str, intervals(lights)))} for "
                             f"{lights} lights, not {self.interval}: {per} lights per cycle are done in "
                             f"{-(-lights // per)} cycles")
        if self.interval == 1:
            return
        per = self.per_cycle
        if isinstance(self.units[0], DatapathConfig):
            if self.copies != 1:
                raise ValueError(f"interval must be 1 for {self.copies} copies of a datapath, not "
                                 f"{self.interval} (one datapath holds every light)")
            unit = self.units[0]
            for light in range(per, lights):
                if unit.local_light(light) != unit.local_light(light % per):
                    raise ValueError(f"lights {light % per} and {light} share one datapath light at "
                                     f"interval {self.interval}, so local_lights must be equal for "
                                     f"them, not {unit.local_light(light % per)} and {unit.local_light(light)}")
            return
        for light in range(per, lights):
            if self.units[light] != self.units[light % per]:
                raise ValueError(f"units[{light % per}] and units[{light}] (lights {light % per} and "
                                 f"{light}) share one physical unit at interval {self.interval}, so "
                                 f"they must be equal: {self.units[light % per]!r} and {self.units[light]!r}")

    @property
    def copies(self):
        return len(self.units)

    @property
    def lights(self):
        """The lights the shader shades (logical lights, whatever its ``interval``)."""
        return self.blend.lights

    @property
    def terms(self):
        """``(copy, diffuse port, lane, specular port)`` of each light, in the blend's order."""
        return [(copy, *term) for copy, config in enumerate(self.units) for term in unit_terms(self.unit, config)]

    @property
    def shared(self):
        """The unit inputs that enter the shader once, unprefixed, and fan out to every copy:
        with ``share`` and several copies, those the unit class does not name in ``PER_LIGHT``
        that every copy declares alike (the same format and the same values of the fields
        its ``SHARED_ALIKE`` names for it).  A unit class without ``PER_LIGHT`` shares none."""
        kind = type(self.units[0])
        per_light = getattr(kind, "PER_LIGHT", None)
        if not self.share or self.copies == 1 or per_light is None:
            return ()
        first, others = self.units[0], self.units[1:]
        alike = getattr(kind, "SHARED_ALIKE", {})
        return tuple(name for name, port in first.inputs.items() if name not in per_light
                     and all(sub.inputs.get(name) == port for sub in others)
                     and all(getattr(sub, field) == getattr(first, field)
                             for sub in others for field in alike.get(name, ())))

    def prefix(self, copy):
        """The prefix of copy ``copy``'s own inputs on the shader (none for a single copy)."""
        return "" if self.copies == 1 else f"c{copy}_"

    def port_name(self, copy, name):
        """The shader input that feeds input ``name`` of copy ``copy``."""
        return name if name in self.shared else self.prefix(copy) + name

    @property
    def per_cycle(self):
        """Lights computed per clock cycle: ``ceil(lights / interval)``."""
        return -(-self.lights // self.interval)

    @property
    def physical_units(self):
        """The configs of the unit copies the hardware builds: ``units`` at interval 1; at a
        larger one the first :attr:`per_cycle` copies of a one-light unit, or the datapath
        with :attr:`per_cycle` lights."""
        if self.interval == 1:
            return self.units
        per = self.per_cycle
        unit = self.units[0]
        if not isinstance(unit, DatapathConfig):
            return self.units[:per]
        local = unit.local_lights
        return (unit.replace(lights=per, local_lights=local if isinstance(local, bool)
                             else tuple(local[:per])),)

    def feeds(self, group):
        """What feeds the physical copies (:attr:`physical_units`) in cycle ``group`` of a
        pixel: one ``{copy input: shader input}`` per copy.  Copy ``j`` (datapath light ``j``)
        serves light ``group·per_cycle + j``; a slot with no light left (5 lights at
        interval 2) is fed light ``j`` again and its terms are not blended."""
        per = self.per_cycle

        def light(j):
            served = group * per + j
            return served if served < self.lights else j

        units = self.physical_units
        if self.interval == 1 or not isinstance(units[0], DatapathConfig):
            return [{name: self.port_name(light(j), name) for name in sub.inputs} for j, sub in enumerate(units)]
        physical, logical = units[0], self.units[0]
        feed = {name: name for name in physical.inputs}
        for j in range(per):
            feed.update(zip(physical.light_inputs(j), logical.light_inputs(light(j))))
        return [feed]

    @property
    def physical_terms(self):
        """``(copy, diffuse port, lane, specular port)`` of each light slot of
        :attr:`physical_units`: light ``l`` is slot ``l % per_cycle`` in cycle ``l // per_cycle``."""
        return [(copy, *term) for copy, config in enumerate(self.physical_units)
                for term in unit_terms(self.unit, config)]

    @property
    def inputs(self):
        ports = {name: self.units[0].inputs[name] for name in self.shared}  # shared first
        for copy, config in enumerate(self.units):
            ports.update({self.port_name(copy, name): port for name, port in config.inputs.items()})
        if "material" in self.blend.inputs:
            ports["material"] = self.blend.inputs["material"]
        return ports

    @property
    def outputs(self):
        return self.blend.outputs

    def replace(self, **changes):
        """This config with fields ``changes``; any other setting (``vec_frac``, a unit's
        field) goes to every unit's config, and ``pipeline`` to the blend's as well (and to
        the units that have a depth: the conventional unit, pipelined by hand, has none)."""
        own = {name: changes.pop(name) for name in ("unit", "units", "blend", "share", "interval")
               if name in changes}
        depth = changes.pop("pipeline", None)
        if depth is not None:
            own["blend"] = own.get("blend", self.blend).replace(pipeline=depth)
        config = super().replace(**own) if own else self
        if changes or depth is not None:
            units = tuple(unit.replace(**changes, **({"pipeline": depth} if hasattr(unit, "pipeline")
                                                       and depth is not None else {}))
                          for unit in config.units)
            config = super(ShaderConfig, config).replace(units=units)
        return config
