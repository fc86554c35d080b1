"""The common shape of every datapath component: ``i``/``o`` with valid and payload.

A block's ports come from its configuration (:attr:`BlockConfig.inputs` and
``outputs``: name -> (format, lanes)), so the payload layouts and the golden model
agree on widths by construction.  Components are fully pipelined: one new input
every clock, no back-pressure, and ``valid`` travels with the data through exactly
``latency`` registers.

Inputs enter :meth:`PipelinedBlock.datapath` at cycle 0 (see the cycle tags of
:mod:`phongfx.hdl.fixed`); every output should come back at cycle ``latency``.
Elaboration records the cycle of each output in ``output_cycles``, so a test can
check a ``latency`` formula against the registers a pipeline depth adds (the
harness catches a mismatch as well, by timing).  A sub-block's :meth:`results` carry
the cycle of what was fed to it plus its latency.

No silent overflow, so that a wrong answer never passes for a right one: ``o.payload``
carries one more field than the config's outputs, ``overflow`` (:data:`OVERFLOW`): high
on a valid output whose computation met an ``overflow="error"`` quantize out of range,
in this block or a sub-block it fed.  The golden model raises on such a value, so the
harness expects 0 on every valid output: a 1 is an overflow in the RTL that the golden
model did not predict.  Synthesis builds under
:func:`~phongfx.hdl.overflow.overflow_checks` ``(False)``, where the field is 0.
"""

from amaranth.hdl import Const, Module, Signal
from amaranth.lib import data, wiring
from amaranth.lib.wiring import In, Out

from phongfx.config import BlockConfig
from phongfx.core.format import Format

from .fixed import FixedValue, FixedVector, align, delay
from .overflow import add_probe, overflow_flags, probing, report_overflow

__all__ = ["OVERFLOW", "checked_outputs", "payload_layout", "stream_signature", "unbuilt", "PipelinedBlock"]

#: The output field that flags an undeclared overflow in the RTL (see the module docstring).
OVERFLOW = "overflow"


def checked_outputs(config):
    """The ports of ``o.payload``: ``config.outputs`` and the 1-bit :data:`OVERFLOW` last."""
    if OVERFLOW in config.outputs:
        raise ValueError(f"an output may not be named {OVERFLOW!r}: the overflow flag uses it")
    return {**config.outputs, OVERFLOW: (Format(1, 0), 1)}


def unbuilt(elaboratable):
    """``elaboratable``, marked as not meant to be elaborated by its creator, and returned.

    Amaranth warns about every elaboratable that is created but never elaborated, to
    catch a design that forgot to add a submodule.  Some are made on purpose without
    being built: to be asked a number (a latency, a cache key), as a sub-block owned by a
    composite block that builds its own (only the composite, if it is itself left
    unused, should warn), or half-made by a constructor that raises.  Amaranth 0.5 has
    no public switch for this: the flag below is its private one, set here only, so an
    Amaranth upgrade that renames it is one line to change.
    """
    elaboratable._MustUse__silence = True
    return elaboratable


def payload_layout(ports):
    """``StructLayout`` for ports ``{name: (Format, lanes)}``; 3 lanes become an ``ArrayLayout``."""
    members = {}
    for name, (fmt, lanes) in ports.items():
        shape = fmt.shape()
        members[name] = shape if lanes == 1 else data.ArrayLayout(shape, lanes)
    return data.StructLayout(members)


def stream_signature(ports):
    """A valid bit and a payload (no ready: the datapath never stalls)."""
    return wiring.Signature({"valid": Out(1), "payload": Out(payload_layout(ports))})


class PipelinedBlock(wiring.Component):
    """Base for datapath components.

    Subclasses set ``config_class`` and ``latency`` and implement
    :meth:`datapath`, which receives the inputs as :class:`FixedValue` /
    :class:`FixedVector` and returns the outputs (registered inside as the block
    needs; the valid pipeline is handled here and must match ``latency``).
    """

    config_class = BlockConfig
    #: inputs tagged with cycle 0, outputs' cycles recorded (False: untagged values)
    cycle_tags = True
    #: ``{output: cycle}`` after elaboration (None where untagged)
    output_cycles = None

    def __init__(self, config):
        if not isinstance(config, self.config_class):
            unbuilt(self)  # never built: no "unused elaboratable" warning later
            raise TypeError(f"config must be a {self.config_class.__name__}, not {config!r}")
        self.config = config
        self._fed = None  # (module, cycle) of the values fed by a composite block
        super().__init__({
            "i": In(stream_signature(config.inputs)),
            "o": Out(stream_signature(checked_outputs(config))),
        })

    @property
    def latency(self):
        raise NotImplementedError

    @property
    def interval(self):
        """The initiation interval: clock cycles from one input taken to the next, at least
        (1: an input every clock).  A block that takes turns over its work (a shader sharing
        one unit between lights) takes an input at most once per ``interval`` cycles, counted
        in cycles where it moves; one offered sooner is ignored."""
        return 1

    def datapath(self, m, inputs):
        """Build the datapath; return ``{output: FixedValue | FixedVector}``.

        A composite block whose sub-blocks carry ``valid`` may also return
        ``"valid"``; otherwise ``i.valid`` is delayed by ``latency`` here.
        """
        raise NotImplementedError

    def feed(self, m, valid, values):
        """Drive this block's ``i`` from ``valid`` and ``{input: FixedValue | FixedVector}``
        (used by composite blocks; formats must match the config's).  The values are
        first aligned to the latest one's cycle; ``valid`` must be of that cycle."""
        names = list(values)
        aligned = dict(zip(names, align(*(values[name] for name in names))))
        self._fed = (m, max((value.cycle for value in aligned.values() if value.cycle is not None),
                            default=None))
        m.d.comb += self.i.valid.eq(valid)
        _drive(m, self.i.payload, self.config.inputs, aligned, f"{type(self).__name__} input")
        cycle = self._fed[1]
        report_overflow(FixedValue(self.o.payload[OVERFLOW], "1.0",
                                   None if cycle is None else cycle + self.latency, m))

    def results(self):
        """This block's outputs as ``{output: FixedValue | FixedVector}``, at the cycle fed plus ``latency``."""
        m, cycle = self._fed if self._fed is not None else (None, None)
        cycle = None if cycle is None else cycle + self.latency
        return _wrap(self.o.payload, self.config.outputs, cycle, m)

    def elaborate(self, platform):
        m = Module()
        cycle = 0 if self.cycle_tags else None
        with overflow_flags() as flags:
            outputs = self.datapath(m, _wrap(self.i.payload, self.config.inputs, cycle, m, names=True))
        valid = outputs.pop("valid", None)
        if valid is None:
            valid = delay(m, self.i.valid, self.latency, name="valid")
        self.output_cycles = {name: value.cycle for name, value in outputs.items()}
        _drive(m, self.o.payload, self.config.outputs, outputs, f"{type(self).__name__} output")
        m.d.comb += self.o.valid.eq(valid)
        m.d.comb += self.o.payload[OVERFLOW].eq(self._overflow(flags) & valid if flags else Const(0))
        if flags is not None and probing():
            for claim in flags.static:
                add_probe(type(self).__name__, claim, None)
            for index, flag in enumerate(f for f in flags if f.claim is not None):
                probe = Signal(name=f"overflow_probe{index}")
                m.d.comb += probe.eq(flag.at(self.latency).value & valid)
                add_probe(type(self).__name__, flag.claim, probe)
        return m

    def _overflow(self, flags):
        """The OR of ``flags``, each delayed to the output cycle (``latency``)."""
        untagged = [flag for flag in flags if flag.cycle is None]
        if untagged:
            # a block without cycle tags must tag the values it quantizes with "error"
            raise ValueError(f"{type(self).__name__}: an overflow=\"error\" quantize has no cycle "
                             f"tag, so its flag cannot be aligned with valid")
        late = [flag.cycle for flag in flags if flag.cycle > self.latency]
        if late:
            raise ValueError(f"{type(self).__name__}: an overflow flag at cycle {late[0]} is later "
                             f"than the latency {self.latency}")
        any_ = Const(0)
        for flag in flags:
            any_ = any_ | flag.at(self.latency).value
        return any_


def _drive(m, payload, ports, values, what):
    for name, (fmt, lanes) in ports.items():
        value = values[name]
        if value.fmt != fmt:
            raise ValueError(f"{what} {name} has format {value.fmt}, the config declares {fmt}")
        items = [value] if lanes == 1 else list(value)
        targets = [payload[name]] if lanes == 1 else [payload[name][lane] for lane in range(lanes)]
        for target, item in zip(targets, items):
            m.d.comb += target.eq(item.value)


def _wrap(payload, ports, cycle, module, names=False):
    return {name: FixedValue(payload[name], fmt, cycle, module, name if names else None) if lanes == 1
            else FixedVector.from_array(payload[name], fmt, cycle, module, name if names else None)
            for name, (fmt, lanes) in ports.items()}
