"""The common shape of every datapath component: ``i``/``o`` with valid and payload.

A block's ports come from its configuration (:attr:`BlockConfig.inputs` and
``outputs``: name -> (format, lanes)), so the payload layouts and the golden model
agree on widths by construction.  Components are fully pipelined: one new input
every clock, no back-pressure, and ``valid`` travels with the data through exactly
``latency`` registers.
"""

from amaranth.hdl import Module
from amaranth.lib import data, wiring
from amaranth.lib.wiring import In, Out

from ..config import BlockConfig
from .fixed import FixedValue, FixedVector, delay

__all__ = ["payload_layout", "stream_signature", "PipelinedBlock"]


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

    def __init__(self, config):
        if not isinstance(config, self.config_class):
            raise TypeError(f"config must be a {self.config_class.__name__}, not {config!r}")
        self.config = config
        super().__init__({
            "i": In(stream_signature(config.inputs)),
            "o": Out(stream_signature(config.outputs)),
        })

    @property
    def latency(self):
        raise NotImplementedError

    def datapath(self, m, inputs):
        raise NotImplementedError

    def elaborate(self, platform):
        m = Module()
        inputs = {}
        for name, (fmt, lanes) in self.config.inputs.items():
            field = self.i.payload[name]
            inputs[name] = FixedValue(field, fmt) if lanes == 1 else FixedVector.from_array(field, fmt)
        outputs = self.datapath(m, inputs)
        for name, (fmt, lanes) in self.config.outputs.items():
            value = outputs[name]
            if value.fmt != fmt:
                raise ValueError(f"{type(self).__name__} output {name} has format {value.fmt}, "
                                 f"the config declares {fmt}")
            if lanes == 1:
                m.d.comb += self.o.payload[name].eq(value.value)
            else:
                for lane, item in enumerate(value):
                    m.d.comb += self.o.payload[name][lane].eq(item.value)
        m.d.comb += self.o.valid.eq(delay(m, self.i.valid, self.latency, name="valid"))
        return m
