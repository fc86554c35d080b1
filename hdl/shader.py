"""A whole shader as one pipelined component: the shading unit's copies and the blend."""

from amaranth.hdl import Signal
from amaranth.lib import data

from phongfx.config import ShaderConfig
from phongfx.core.registry import REGISTRY

from .blend import Blend
from .block import OVERFLOW, PipelinedBlock, unbuilt
from .fixed import FixedValue, FixedVector, delay
from .overflow import collecting_overflow, report_overflow

__all__ = ["Shader"]


class Shader(PipelinedBlock):
    """The shading unit (one copy, or one per light) feeding :class:`~phongfx.hdl.blend.Blend`.

    The copies run side by side on their own inputs and the shared ones, one wire fanned
    out to every copy (:attr:`~phongfx.config.ShaderConfig.shared`); every light's diffuse
    and specular outputs and the pixel's ``material`` (delayed by the cycle tags to meet the
    slowest copy's) go to the blend, whose ``r``, ``g``, ``b`` are the shader's outputs.

    **Light sharing** (``interval`` ``I`` > 1, :class:`~phongfx.config.ShaderConfig`): the
    physical copies (:attr:`~phongfx.config.ShaderConfig.physical_units`) take turns.  A
    pixel is accepted when no turn is running; its inputs go to the copies at once (turn 0)
    and into a holding register that feeds turns ``1 .. I−1``, one per clock, each turn's
    light group chosen by a multiplexer on the turn counter
    (:meth:`~phongfx.config.ShaderConfig.feeds`).  Each turn's terms leave the copies on
    consecutive clocks; those of the first ``I−1`` turns are held in registers, and with
    the last turn's the blend takes every light at once: its constants are different per
    light, so an adder tree accumulating per turn would need every light's products
    anyway, while holding the terms costs registers only, and the sum is exact and rounded
    once (the codes are interval 1's, :func:`phongfx.golden.shader.shader_terms`).  A copy's
    overflow flag is ORed over the turns.  The cycle tags count from the last turn, the one
    the output waits for.

    Latency: ``max(copy latencies) + blend + interval − 1``, each at its own pipeline
    depth; one pixel every ``interval`` clocks (:attr:`interval`).
    """

    config_class = ShaderConfig

    def __init__(self, config):
        super().__init__(config)
        component = REGISTRY[config.unit].load("component")
        self._units = [unbuilt(component(sub)) for sub in config.physical_units]
        self._blend = unbuilt(Blend(config.blend))

    @property
    def _slowest(self):
        """The copy whose outputs come last: the others' wait for it (a point light's copy of
        the conventional unit normalizes its L, three cycles more than a directional one's)."""
        return max(self._units, key=lambda unit: unit.latency)

    @property
    def interval(self):
        return self.config.interval

    @property
    def latency(self):
        return self._slowest.latency + self._blend.latency + self.interval - 1

    def datapath(self, m, i):
        c = self.config
        if c.interval == 1:
            inputs, valid = [{name: i[port] for name, port in feed.items()} for feed in c.feeds(0)], self.i.valid
        else:
            inputs, valid, turn = self._turns(m)
        for copy, (unit, values) in enumerate(zip(self._units, inputs)):
            m.submodules[f"unit{copy}"] = unit
            unit.feed(m, valid, values)
        m.submodules.blend = self._blend
        results = [unit.results() for unit in self._units]
        last = max(value.cycle for result in results for value in result.values())
        terms, done = {}, self._slowest.o.valid
        if c.interval > 1:
            turn = delay(m, turn, self._slowest.latency, name="turn_out")
            self._held_overflow(m, results, last, done, turn)
        per = c.per_cycle
        for slot, (copy, diff, lane, spec) in enumerate(c.physical_terms):
            for group in range(c.interval):
                light = group * per + slot
                if light >= c.lights:
                    continue
                for name, port in ((f"diff{light}", diff), (f"spec{light}", spec)):
                    if port is None:
                        continue
                    value = results[copy][port]
                    value = (value if lane is None or name.startswith("spec") else value[lane]).at(last)
                    terms[name] = value if group == c.interval - 1 else self._hold(m, value, done & (turn == group), name)
        if "material" in c.inputs:
            terms["material"] = i["material"]
        if c.interval > 1:
            done = done & (turn == c.interval - 1)
        self._blend.feed(m, done, terms)  # feed delays the faster copies' terms
        return {**self._blend.results(), "valid": self._blend.o.valid}

    def _turns(self, m):
        """The holding register and turn counter of light sharing: each copy's inputs
        (cycle ``interval − 1``), the valid of every turn, and the turn number."""
        c = self.config
        last = c.interval - 1
        turn = Signal(range(c.interval), name="turn")
        busy = Signal(name="busy")  # turns 1 .. interval − 1 of a pixel are running
        accept = self.i.valid & ~busy
        feeds = [c.feeds(group) for group in range(c.interval)]
        later = {port for feed in feeds[1:] for names in feed for port in names.values()}
        current = {}
        for port, (fmt, lanes) in c.inputs.items():
            if port not in later:  # read in turn 0 only: from the input as it is taken
                current[port] = self.i.payload[port]
                continue
            shape = fmt.shape() if lanes == 1 else data.ArrayLayout(fmt.shape(), lanes)
            held, now = Signal(shape, name=f"{port}_held"), Signal(shape, name=f"{port}_now")
            with m.If(accept):
                m.d.sync += held.eq(self.i.payload[port])
            m.d.comb += now.eq(self.i.payload[port])
            with m.If(busy):
                m.d.comb += now.eq(held)
            current[port] = now
        with m.If(accept):
            m.d.sync += [turn.eq(1), busy.eq(1)]
        with m.Elif(busy):
            m.d.sync += turn.eq(turn + 1)
            with m.If(turn == last):
                m.d.sync += [turn.eq(0), busy.eq(0)]
        inputs = []
        for copy, sub in enumerate(c.physical_units):
            values = {}
            for name, (fmt, lanes) in sub.inputs.items():
                ports = [feed[copy][name] for feed in feeds]
                shape = fmt.shape() if lanes == 1 else data.ArrayLayout(fmt.shape(), lanes)
                label = f"u{copy}_{name}"
                chosen = Signal(shape, name=label)
                m.d.comb += chosen.eq(current[ports[0]])
                for group, port in enumerate(ports[1:], 1):
                    if port != ports[0]:
                        with m.If(turn == group):
                            m.d.comb += chosen.eq(current[port])
                values[name] = (FixedValue(chosen, fmt, last, m, label) if lanes == 1 else
                                FixedVector.from_array(chosen, fmt, last, m, label))
            inputs.append(values)
        return inputs, accept | busy, turn

    def _hold(self, m, value, load, name):
        """``value`` of an early turn in a register loaded at ``load``, read with the last turn."""
        held = Signal(value.fmt.shape(), name=f"{name}_turn")
        with m.If(load):
            m.d.sync += held.eq(value.value)
        return FixedValue(held, value.fmt, value.cycle, m, f"{name}_turn")

    def _held_overflow(self, m, results, last, done, turn):
        """The copies' overflow flags ORed over the early turns, reported with the last turn's."""
        if not collecting_overflow():
            return
        flag = 0
        for unit, result in zip(self._units, results):
            cycle = next(iter(result.values())).cycle
            flag = flag | FixedValue(unit.o.payload[OVERFLOW], "1.0", cycle, m, "unit_overflow").at(last).value
        seen = Signal(name="overflow_turns")
        with m.If(done & (turn == 0)):
            m.d.sync += seen.eq(flag)
        with m.Elif(done & (turn < self.config.interval - 1)):
            m.d.sync += seen.eq(seen | flag)
        report_overflow(FixedValue(seen, "1.0", last, m, "overflow_turns"))
