"""A compiled core as an Amaranth component: ``lib.stream`` in, ``lib.stream`` out.

``phongfx compile SCENE -o DIR`` ships Verilog; a user whose own design is written in
Amaranth wants the core as an Amaranth object instead, to instantiate and simulate with
Amaranth's simulator without reading the Verilog back in.  :func:`load_core` builds it from
the folder (its ``manifest.json``: :mod:`phongfx.deliver.manifest`): the same block at the
same config as the shipped ``verilog/<module>_top.v``, elaborated from the same Amaranth
source, so the two are one design.

:class:`ShadingCore` is the block behind :class:`~phongfx.hdl.handshake.Handshake` (the
handshake of the shipped top, :class:`~phongfx.hdl.top.Top`), built without the
simulation-only overflow checks as the shipped top is
(:class:`~phongfx.hdl.overflow.Checked`):

* ``i``: ``In(stream.Signature(layout))``, ``layout`` a ``StructLayout`` with one field per
  input of the top (``normal``, ``view``, ``n``, ``c0_light`` ...; the top's ports
  ``in_normal_x`` ... are its fields and lanes): a 3-lane vector is an ``ArrayLayout`` of 3,
  a code of format ``Sn.m`` a ``signed(1+n+m)``, of ``n.m`` an ``unsigned(n+m)``
  (:meth:`~phongfx.core.format.Format.shape`);
* ``o``: ``Out(stream.Signature(StructLayout r, g, b))``, the display codes.

The handshake keeps :mod:`amaranth.lib.stream`'s rules, which are AXI-Stream's: a transfer
happens on an edge where ``valid`` and ``ready`` are both high; ``o.valid`` comes from a
register and never depends on ``o.ready``; while ``o.valid & ~o.ready`` the whole pipeline
holds, so ``o.valid`` and ``o.payload`` stay stable until taken; ``i.ready`` depends
combinationally on ``o.ready`` (``o.ready | ~o.valid``) and never on ``i.valid``.  A design
whose lights take turns on shared hardware (``interval`` > 1) holds
``i.ready`` low for ``interval − 1`` moving cycles after each pixel taken.  ``rst`` (the
``sync`` domain's reset) drops what is in flight.
"""

from collections.abc import Mapping

from amaranth.hdl import Module
from amaranth.lib import stream, wiring
from amaranth.lib.wiring import In, Out

from phongfx.core.registry import get_block
from phongfx.hdl.block import OVERFLOW, checked_outputs, payload_layout, unbuilt
from phongfx.hdl.handshake import Handshake
from phongfx.hdl.overflow import Checked

from .manifest import design_of, manifest_path, read_manifest

__all__ = ["ShadingCore", "load_core"]


class ShadingCore(wiring.Component):
    """The block ``block`` (a registry name) at ``config`` with :mod:`amaranth.lib.stream`
    interfaces ``i`` and ``o`` (module docstring).

    Parameters
    ----------
    config : BlockConfig
        Usually a :class:`~phongfx.config.ShaderConfig`: the manifest's ``"config"``, or
        :func:`phongfx.explore.compile.architecture.config_of` of a compile's best result.
    name : str
        The compiled module's name (``<scene>_<method>``); the shipped top is ``<name>_top``.
    block : str
        The registry block (``"shader"`` for a compiled scene).
    overflow : bool
        Build the RTL overflow checks and add an ``overflow`` field to ``o.payload`` (1 on
        an output whose computation left a format the golden model says it fits): for
        simulation; the shipped Verilog has none.

    Attributes: ``config``, ``name``, ``latency`` (cycles in which the pipeline moves, from a
    pixel taken to its result offered), ``interval`` (clocks per pixel at least), ``block``
    (the :class:`~phongfx.core.registry.Block`: ``core.block.golden(inputs)`` gives the
    expected outputs), ``manifest`` (the dict it was loaded from, or None).
    """

    def __init__(self, config, *, name="shader", block="shader", overflow=False):
        try:
            if not isinstance(name, str) or not name.isidentifier():
                raise ValueError(f"name must be an identifier (the compiled module's), not {name!r}")
            self.block = get_block(block, config=config)
            self.handshake = unbuilt(Handshake(self.block.component()))
        except Exception:
            unbuilt(self)  # half-made: no "unused elaboratable" warning later
            raise
        self.config = config
        self.name = name
        self.overflow = bool(overflow)
        self.latency = self.handshake.latency
        self.interval = self.handshake.interval
        self.manifest = None
        outputs = checked_outputs(config) if self.overflow else dict(config.outputs)
        super().__init__({"i": In(stream.Signature(payload_layout(config.inputs))),
                          "o": Out(stream.Signature(payload_layout(outputs)))})

    @classmethod
    def from_manifest(cls, manifest, *, where="manifest", overflow=False):
        """The core of a manifest dict (``manifest.json`` read, or what
        :func:`phongfx.explore.compile.emit.emit` returns); ``where`` names it in errors."""
        block, module, config = design_of(manifest, where)
        core = cls(config, name=module, block=block, overflow=overflow)
        core.manifest = manifest
        return core

    def elaborate(self, platform):
        m = Module()
        inner = self.handshake
        m.submodules.core = Checked(inner, self.overflow)
        wiring.connect(m, wiring.flipped(self.i), inner.i)  # the same payload layout
        m.d.comb += [self.o.valid.eq(inner.o.valid), inner.o.ready.eq(self.o.ready)]
        for field in self.config.outputs:
            m.d.comb += self.o.payload[field].eq(inner.o.payload[field])
        if self.overflow:
            m.d.comb += self.o.payload[OVERFLOW].eq(inner.o.payload[OVERFLOW])
        return m


def load_core(folder, *, overflow=False):
    """The :class:`~phongfx.deliver.component.ShadingCore` of a compiled output folder (``phongfx compile ... -o folder``),
    of its ``manifest.json`` path, or of a manifest dict (what
    :func:`phongfx.explore.compile.emit.emit` returns).

    Raises :class:`~phongfx.deliver.manifest.ManifestError` (a ValueError) naming the file
    and the field for a folder without a manifest, a manifest of another version, or of a
    compile that found no design."""
    if isinstance(folder, Mapping):
        return ShadingCore.from_manifest(folder, overflow=overflow)
    path = manifest_path(folder)
    return ShadingCore.from_manifest(read_manifest(path), where=path, overflow=overflow)
