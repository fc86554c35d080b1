"""The shipped top of a block: one named port per payload field and lane, AXI-Stream handshake.

:class:`~phongfx.hdl.block.PipelinedBlock` ports are two packed payload vectors
(``i__payload``, ``o__payload``) without back-pressure: right for the harness, awkward for
a user's design, which would have to know the packing.  :class:`Top` puts the block
behind :class:`~phongfx.hdl.handshake.Handshake` and gives every field and lane its own
port, named after the config's ports: ``in_n0_x``, ``in_n0_y``, ``in_n0_z`` (a 3-lane vector
gets ``_x``, ``_y``, ``_z``; other lane counts ``_0`` .. ``_k``), ``in_a``, ..., ``out_spec0``.

The overflow flag (:data:`~phongfx.hdl.block.OVERFLOW`) is a simulation aid: the shipped
top is built under :func:`~phongfx.hdl.overflow.overflow_checks` ``(False)``, so its
netlist is what synthesis costs, and has no ``out_overflow``; ``overflow=True`` builds the
checks and adds the port, for simulation only.

:func:`port_map` is the list of ports with their formats and their place in the inner
block's packed payload; :func:`top_verilog`'s header comment is printed from it, so the
manifest and the Verilog cannot disagree.
"""

from amaranth.hdl import Module
from amaranth.lib import wiring
from amaranth.lib.wiring import In, Out

from phongfx.config import ShaderConfig

from .block import OVERFLOW, PipelinedBlock, checked_outputs, unbuilt
from .comment import wrap
from .emit import verilog
from .handshake import Handshake
from .overflow import Checked

__all__ = ["BLOCK_PATH", "CONTROL_PORTS", "POWER_UP", "TIMING_KEYS", "lane_suffix", "port_map", "Top", "timing_line",
           "header", "top_verilog", "shipped_verilog"]

#: The ports that carry no payload, in header order: ``(name, direction, meaning)``.
CONTROL_PORTS = (
    ("clk", "input", "clock; everything happens on its rising edge"),
    ("rst", "input", "synchronous reset, active high"),
    ("in_valid", "input", "the in_* ports hold a vector"),
    ("in_ready", "output", "the top takes the vector on this edge if in_valid is high"),
    ("out_valid", "output", "the out_* ports hold a result"),
    ("out_ready", "input", "the consumer takes the result on this edge if out_valid is high"),
)

#: What the top does from power-up without a reset pulse, as measured (``tests/hdl/test_top.py``
#: runs the exported testbench without its first reset under Icarus Verilog 11 ``-g2012``).
POWER_UP = ("Power-up without a reset pulse: every register starts at its reset value (Verilog "
            "initializers) and the logic between them is continuous assignments, evaluated at time 0 "
            "(no always @* block, which under Icarus -g2012 would wait for an event and gave out_valid "
            "= X for the first cycles), so out_valid is 0 and in_ready 1 from time 0 under Icarus "
            "-g2012 and Verilator.  "
            "Hardware without register initial values (an ASIC) needs an rst pulse first.")


#: The keys of :func:`top_verilog`'s ``timing``.
TIMING_KEYS = ("clock_mhz", "clock_source", "pixel_rate_mpx", "requirement_mpx", "met")


def lane_suffix(lane, lanes):
    """``"_x"`` / ``"_y"`` / ``"_z"`` for a 3-lane vector, ``"_<lane>"`` for other lane counts,
    ``""`` for a scalar (``lanes == 1``)."""
    if lanes == 1:
        return ""
    return "_" + "xyz"[lane] if lanes == 3 else f"_{lane}"


def port_map(config, *, overflow=False):
    """The ports of :class:`Top` for ``config``: a list of dicts, control ports first.

    Each dict has ``name``, ``direction`` (``"input"`` / ``"output"``), ``field`` and
    ``lane`` (the config port and lane, ``lane`` None for a scalar; both None for the
    control ports), ``width`` (bits), ``format`` (Lyon's ``Sn.m`` / ``n.m``, None for control
    ports), ``signed`` and ``offset``: the field's first bit in the inner block's packed
    ``i.payload`` / ``o.payload`` (:func:`phongfx.sim.vectors.payload_fields` order; None for
    control ports).  ``overflow=True`` adds the 1-bit ``out_overflow``.
    """
    ports = [{"name": name, "direction": direction, "field": None, "lane": None, "width": 1,
              "format": None, "signed": False, "offset": None} for name, direction, _ in CONTROL_PORTS]
    outputs = checked_outputs(config)
    if not overflow:
        del outputs[OVERFLOW]
    for prefix, direction, fields in (("in", "input", config.inputs), ("out", "output", outputs)):
        offset = 0
        for field, (fmt, lanes) in fields.items():
            for lane in range(lanes):
                ports.append({"name": f"{prefix}_{field}{lane_suffix(lane, lanes)}", "direction": direction,
                              "field": field, "lane": lane if lanes > 1 else None, "width": fmt.width,
                              "format": str(fmt), "signed": fmt.signed, "offset": offset})
                offset += fmt.width
    names = [port["name"] for port in ports]
    clash = sorted({name for name in names if names.count(name) > 1})
    if clash:
        raise ValueError(f"ports of {type(config).__name__} clash with the top's: {', '.join(clash)}")
    return ports


class Top(wiring.Component):
    """``block`` behind :class:`~phongfx.hdl.handshake.Handshake`, one port per field and lane.

    Parameters
    ----------
    block : PipelinedBlock
        Latency at least 1 (the handshake's condition).
    name : str
        The Verilog module is ``<name>_top`` (:func:`top_verilog`).
    overflow : bool
        Build the RTL overflow checks and add ``out_overflow`` (simulation only).

    ``ports`` is :func:`port_map` of the block's config.
    """

    def __init__(self, block, name, *, overflow=False):
        try:
            if not isinstance(block, PipelinedBlock):
                raise TypeError(f"block must be a PipelinedBlock, not {block!r}")
            if not isinstance(name, str) or not name.isidentifier():
                raise ValueError(f"top name must be a Verilog identifier, not {name!r}")
            # the handshake's own checks (latency >= 1) run now, not at elaboration
            self.handshake = unbuilt(Handshake(block))
            self.ports = port_map(block.config, overflow=overflow)
        except Exception:
            unbuilt(self)  # half-made: no "unused elaboratable" warning later
            raise
        self.block = block
        self.name = name
        self.overflow = bool(overflow)
        self.latency = block.latency
        self.interval = block.interval
        members = {}
        for port in self.ports:
            shape = self._shape(port)
            members[port["name"]] = In(shape) if port["direction"] == "input" else Out(shape)
        del members["clk"], members["rst"]  # the sync domain's, added by Amaranth
        super().__init__(members)

    def _shape(self, port):
        if port["field"] is None:
            return 1
        config = self.block.config
        fields = config.inputs if port["direction"] == "input" else checked_outputs(config)
        return fields[port["field"]][0].shape()

    def elaborate(self, platform):
        m = Module()
        handshake = self.handshake
        m.submodules.handshake = Checked(handshake, self.overflow)
        m.d.comb += [
            handshake.i.valid.eq(self.in_valid),
            self.in_ready.eq(handshake.i.ready),
            self.out_valid.eq(handshake.o.valid),
            handshake.o.ready.eq(self.out_ready),
        ]
        for port in self.ports:
            if port["field"] is None:
                continue
            payload = handshake.i.payload if port["direction"] == "input" else handshake.o.payload
            target = payload[port["field"]]
            if port["lane"] is not None:
                target = target[port["lane"]]
            signal = getattr(self, port["name"])
            m.d.comb += target.eq(signal) if port["direction"] == "input" else signal.eq(target)
        return m


def timing_line(timing, interval=1, noun="vector"):
    """The header's sentence on the clock and the rate of ``timing`` (:func:`top_verilog`),
    None when there is nothing to say."""
    timing = {key: value for key, value in (timing or {}).items() if value is not None}
    unknown = sorted(set(timing) - set(TIMING_KEYS))
    if unknown:
        raise ValueError(f"timing keys must be among {', '.join(TIMING_KEYS)}, not {', '.join(unknown)}")
    if not timing:
        return None
    parts = []
    clock = timing.get("clock_mhz")
    if clock is not None:
        source = timing.get("clock_source")
        parts.append(f"clock {clock:.1f} MHz" + (f" ({source})" if source else ""))
    rate = timing.get("pixel_rate_mpx", None if clock is None else clock / interval)
    if rate is not None:
        parts.append(f"{rate:.1f} M{noun}/s" + (f" (one {noun} every {interval} clocks)" if interval > 1 else ""))
    want = timing.get("requirement_mpx")
    if want is not None:
        verdict = {True: "met", False: "MISSED"}.get(timing.get("met"), "not known whether met")
        if timing.get("met") is False and rate is not None:
            verdict += f" by {want - rate:.1f} M{noun}/s ({100 * (want - rate) / want:.0f} %)"
        parts.append(f"requirement {want:.1f} M{noun}/s: {verdict}")
    return "Timing: " + "; ".join(parts) + "."


def header(ports, name, latency, interval=1, timing=None, noun="vector", contract=()):
    """The comment that opens :func:`top_verilog`: what the module is, its latency and
    initiation interval (``interval`` clocks per ``noun``), its clock and rate (``timing``,
    :func:`timing_line`), handshake, reset, one line per port of ``ports`` (:func:`port_map`)
    and, last, the paragraphs of ``contract`` (what the inputs and outputs mean: text made by
    :func:`phongfx.deliver.contract.contract_lines`, each paragraph wrapped)."""
    if interval == 1:
        rate = f"Initiation interval: 1 clock: one {noun} every clock while out_ready is high."
    else:
        rate = (f"Initiation interval: {interval} clocks: one {noun} every {interval} clocks while "
                f"out_ready is high; in_ready is low for the {interval - 1} clock(s) after a {noun} is "
                f"taken (counting clocks in which the pipeline moves), while the work takes its turns.")
    text = [
        f"{name}_top: the phongfx block {name} behind an AXI-Stream valid/ready handshake.",
        f"Latency: {latency} cycle(s) from the edge that takes a vector (in_valid & in_ready) to its "
        f"result on out_*, counting only cycles in which the pipeline moves (out_ready high or "
        f"out_valid low).",
        rate,
        *filter(None, [timing_line(timing, interval, noun)]),
        "Handshake (AXI-Stream): a transfer happens on a rising clk edge where valid and ready are "
        "both high.  While out_valid is high and out_ready low the whole pipeline holds: out_valid "
        "and out_* stay stable and no input is taken.  Nothing is lost or repeated.  in_ready = "
        "out_ready | ~out_valid" + ("" if interval == 1 else ", and'ed with the end of the turns,") +
        " depends combinationally on out_ready (never on in_valid); out_valid comes from a register.",
        "Reset: rst is synchronous and active high, and not held off by out_ready: it clears "
        "everything in flight (vectors accepted and not yet delivered are dropped, and so is one "
        "offered on an edge where rst is high, whatever in_ready says); out_valid is 0 after the "
        "first edge that samples rst high.",
        POWER_UP,
        "Ports: bits [w-1:0], MSB first.  A payload port holds a code c of format Sn.m or n.m "
        "(Lyon's notation), value c * 2^-m: Sn.m is signed two's complement, 1 sign bit + n integer "
        "bits + m fraction bits (1+n+m bits); n.m is unsigned, n integer + m fraction bits (n+m "
        "bits).  'offset' is the port's first bit in the block's packed payload.",
    ]
    lines = [line for paragraph in text for line in _wrap(paragraph)]
    width = max(len(port["name"]) for port in ports)
    lines.append(f"  {'dir':6s} {'port':{width}s} {'bits':>4s}  {'format':7s} meaning")
    meanings = {name: meaning for name, _, meaning in CONTROL_PORTS}
    for port in ports:
        if port["field"] is None:
            meaning = meanings.get(port["name"], "")
        elif port["field"] == OVERFLOW:
            meaning = (f"simulation only: an overflow the golden model did not predict, offset "
                       f"{port['offset']}")
        else:
            lane = "" if port["lane"] is None else f"[{port['lane']}]"
            meaning = (f"{'signed' if port['signed'] else 'unsigned'}, {port['field']}{lane}, "
                       f"offset {port['offset']}")
        lines.append(f"  {port['direction']:6s} {port['name']:{width}s} {port['width']:4d}  "
                     f"{port['format'] or '-':7s} {meaning}")
    for paragraph in contract or ():
        lines.extend(_wrap(paragraph))
    return "".join(f"// {line}".rstrip() + "\n" for line in lines)


def _wrap(text, width=96):
    """``text`` in lines of at most ``width`` characters, the later ones indented, none of
    which a tool reads as its pragma once behind ``// `` (:func:`~phongfx.hdl.comment.wrap`)."""
    return wrap(text, width)


#: Where the block sits in :class:`Top` (its handshake's ``block``): in the emitted Verilog the
#: block's sub-blocks are the modules ``<name>_top.handshake.block.<instance>``.
BLOCK_PATH = "handshake.block"


def top_verilog(block_component, name, *, overflow=False, timing=None, contract=(), module=None):
    """Verilog of the shipped top of ``block_component``: module ``<name>_top``, header first.

    Parameters
    ----------
    block_component : PipelinedBlock
    name : str
        Usually the block's registry name; a Verilog identifier.
    overflow : bool
        ``False`` (shipped): built under ``overflow_checks(False)``, no ``out_overflow``.
        ``True``: checks built and ``out_overflow`` added, for simulation only.
    timing : dict, optional
        What the header says of the clock beside the latency and the initiation interval
        (:func:`timing_line`): ``clock_mhz``, ``clock_source`` (how it is known, e.g.
        ``"proxied: ecp5-clock-proxy"`` or ``"synthesized: nextpnr-ecp5"``),
        ``pixel_rate_mpx`` (default ``clock_mhz / interval``), ``requirement_mpx``, ``met``;
        any may be missing.  A shader's rates are in pixels, another block's in vectors.
    contract : sequence of str, optional
        The header's closing "Contract" paragraphs: what each input and output means
        (:func:`phongfx.deliver.contract.contract_lines`); none for a bare block.
    module : str, optional
        :func:`shipped_verilog` of the same top, when the caller made it ahead (seconds of
        Amaranth and Yosys: the compiler makes it beside its witness search).

    Returns
    -------
    str
        The header (:func:`header` of :func:`port_map`) and the module, with source
        locations relative to the repository (:func:`phongfx.hdl.emit.verilog`).
    """
    top = Top(block_component, name, overflow=overflow)
    noun = "pixel" if isinstance(block_component.config, ShaderConfig) else "vector"
    return (header(top.ports, name, top.latency, top.interval, timing, noun, contract)
            + (shipped_verilog(top, name) if module is None else module))


def shipped_verilog(top, name):
    """The module of the shipped top ``top`` (a :class:`Top`), ``<name>_top``, as
    :func:`top_verilog` writes it after its header: lint-clean, its processes as multiplexers
    (:func:`phongfx.hdl.emit.verilog`'s ``lint`` and ``assigns``)."""
    return verilog(top, f"{name}_top", lint=True, assigns=True)
