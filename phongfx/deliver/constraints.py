"""The clock constraint of a compiled core, in the formats the usual flows read.

A compiled core has one clock, port ``clk`` (:mod:`phongfx.hdl.top`), and is meant to be
run at the clock it was compiled for: the ``--clock`` asked (the manifest's
``"requirement"``), else the design's own clock as the compiler estimated or measured it
(its ``"timing"``).  :func:`clock_of` picks it and says where it comes from;
:func:`write_constraints` writes it as

* ``constraints/<module>.sdc``: SDC (Tcl), for OpenSTA and the ASIC flows around it
  (OpenROAD, OpenLane) and for FPGA tools that read SDC;
* ``constraints/<module>.lpf``: a Lattice preference file for ECP5 (nextpnr-ecp5 ``--lpf``,
  Diamond), the clock only;
* ``constraints/<module>_ice40_clock.py``: for iCE40, whose PCF holds pins but no clock,
  a script for nextpnr-ice40 ``--pre-pack`` that calls ``ctx.addClock``;
* ``constraints/<module>_nextpnr.sdc``: the clock alone, for nextpnr's own ``--sdc`` (any
  architecture), which takes ``create_clock`` and refuses the port delays of the full SDC;
  it serves where nextpnr has no Python (the WebAssembly build phongfx runs has none, so no
  ``--pre-pack``).

No file places pins: the core is usually instantiated inside a larger design, and where it
is a top on its own, its pins are the user's board's.  All are written for every
core whatever target it was priced for: the Verilog is the same on every target (no vendor
primitive), so the user may take it anywhere; the comment names the target the clock was
estimated for.
"""

import math
import os
from dataclasses import dataclass

from phongfx.core.files import atomic_write

__all__ = ["PLACEHOLDER_MHZ", "Clock", "clock_of", "sdc_text", "nextpnr_sdc_text", "lpf_text", "ice40_clock_text",
           "constraint_files", "write_constraints"]

#: The clock written when none was asked and none estimated (a target without a clock
#: estimate, compiled without ``--clock``); the files say it is a placeholder.
PLACEHOLDER_MHZ = 100.0
#: Width of the wrapped comment and port-list lines.
_WIDTH = 96


@dataclass(frozen=True)
class Clock:
    """The clock a core is constrained to: ``mhz`` and ``source``, the sentence saying
    where that figure comes from (written as a comment beside it)."""

    mhz: float
    source: str

    def __post_init__(self):
        if isinstance(self.mhz, bool) or not isinstance(self.mhz, (int, float)) or not math.isfinite(self.mhz) \
                or self.mhz <= 0:
            raise ValueError(f"clock mhz must be a positive finite number of MHz, not {self.mhz!r}")

    @property
    def period_ns(self):
        """The period in ns, to the picosecond."""
        return round(1000.0 / self.mhz, 3)


def clock_of(manifest):
    """The :class:`Clock` of a compiled core from its manifest dict: ``"requirement"``'s
    ``clock_mhz`` when one was asked, else ``"timing"``'s ``clock_mhz`` (the design's
    Fmax by the clock proxy or by synthesis), else :data:`PLACEHOLDER_MHZ`."""
    asked = (manifest.get("requirement") or {}).get("clock_mhz")
    timing = manifest.get("timing") or {}
    target = str(manifest.get("cost_model") or "the target").partition("-")[0]
    fmax, how = timing.get("fmax_mhz"), timing.get("clock_source")
    model = (f" ({timing['clock_model']}: its estimate less a {timing.get('clock_margin') or 0:.0%} margin, never above "
             f"synthesis on its calibration, at most {timing['clock_error']:.0%} below)") \
        if timing.get("clock_model") and timing.get("clock_error") is not None else ""
    estimate = f"{target} Fmax {fmax:g} MHz {'promised by the clock proxy' if how == 'proxy' else 'by ' + how}{model}" \
        if fmax else None
    if asked:
        note = f"; the design's {estimate}" if estimate else "; no Fmax estimate for this target"
        if fmax and fmax < asked:
            note += ": timing will not close at the clock asked (manifest timing.met is false)"
        return Clock(float(asked), f"the clock asked for (phongfx compile --clock, manifest "
                                   f"requirement.clock_mhz){note}")
    if timing.get("clock_mhz"):
        return Clock(float(timing["clock_mhz"]), f"no clock was asked: the design's own clock, its {estimate} "
                                                 f"(manifest timing.clock_mhz)")
    return Clock(PLACEHOLDER_MHZ, f"a PLACEHOLDER: no clock was asked and {target} has no clock estimate without "
                                  f"synthesis; replace it by the clock the core will run at, or compile with --clock")


def _wrap(text, prefix="# "):
    """``text`` as comment lines of at most :data:`_WIDTH` characters."""
    lines, line = [], ""
    for word in text.split():
        if line and len(prefix) + len(line) + 1 + len(word) > _WIDTH:
            lines.append(prefix + line)
            line = word
        else:
            line = f"{line} {word}" if line else word
    return "\n".join(lines + [prefix + line]) + "\n"


def _head(module, what, clock, comment="# "):
    return (_wrap(f"{module}_top: {what}, written by phongfx compile with the core.", comment)
            + _wrap(f"Clock clk: {clock.mhz:g} MHz (period {clock.period_ns:g} ns), {clock.source}.", comment))


def _port_list(names, command):
    """``command [get_ports {names}]`` wrapped with Tcl line continuations."""
    lines, line = [], f"{command} [get_ports {{"
    for name in names:
        if len(line) + len(name) + 3 > _WIDTH:
            lines.append(line + " \\")
            line = "    " + name
        else:
            line += name if line.endswith("{") else f" {name}"
    return "\n".join(lines + [line + "}]"]) + "\n"


def sdc_text(module, clock, ports):
    """SDC of ``<module>_top`` at ``clock``; ``ports``: :func:`phongfx.hdl.top.port_map`'s
    list (every port but ``clk`` gets a 0 ns input or output delay, see the text)."""
    inputs = [p["name"] for p in ports if p["direction"] == "input" and p["name"] != "clk"]
    outputs = [p["name"] for p in ports if p["direction"] == "output"]
    return (_head(module, "timing constraints in SDC (OpenSTA read_sdc, ASIC flows, FPGA tools that read SDC)",
                  clock)
            + f"create_clock -name clk -period {clock.period_ns:g} [get_ports clk]\n\n"
            + _wrap("Input and output delays: 0 ns, an assumption. The core is meant to sit in a synchronous "
                    "design on the same clock, its ports driven by and feeding that design's registers "
                    "directly: then the whole period belongs to the core's paths, the paths phongfx's clock "
                    "figures measure. Where logic lies between those registers and a port, give it its "
                    "share, e.g. 0.3 times the period for 30 %. in_ready follows out_ready through logic "
                    "alone (no register between), so that path gets the period less both delays. The drive "
                    "and load of the ports are left to the flow (its library's defaults).")
            + _port_list(inputs, "set_input_delay 0 -clock clk") + _port_list(outputs, "set_output_delay 0 -clock clk"))


def nextpnr_sdc_text(module, clock):
    """The clock of ``<module>_top`` for nextpnr ``--sdc``: ``create_clock`` alone (nextpnr's
    SDC reader stops at ``set_input_delay``)."""
    return (_head(module, "clock constraint for nextpnr --sdc (iCE40, ECP5), no PCF or LPF needed", clock)
            + _wrap("nextpnr reads create_clock only (the full SDC beside this file has the port delays). "
                    "Inside a larger design, name the clock port of that design instead of clk.")
            + f"create_clock -name clk -period {clock.period_ns:g} [get_ports clk]\n")


def lpf_text(module, clock):
    """The ECP5 preference file of ``<module>_top``: the clock's frequency only."""
    return (_head(module, "clock constraint for Lattice ECP5 (nextpnr-ecp5 --lpf, Diamond)", clock)
            + _wrap("No LOCATE or IOBUF line: the pins and their IO standard are the board's, and the user's to "
                    "add (or run nextpnr-ecp5 with --lpf-allow-unconstrained). Inside a larger design, the "
                    "clock's port is that design's: rename clk below.")
            + f'FREQUENCY PORT "clk" {clock.mhz:g} MHz;\n')


def ice40_clock_text(module, clock):
    """A nextpnr-ice40 ``--pre-pack`` script constraining ``clk`` (iCE40's PCF has pins only)."""
    return (_head(module, "clock constraint for iCE40, a script for nextpnr-ice40 --pre-pack FILE", clock)
            + _wrap("nextpnr runs it with its context as ctx before packing; a PCF (pins only) stays the "
                    "user's. Inside a larger design, name the clock net of that design instead of clk.")
            + f'ctx.addClock("clk", {clock.mhz:g})\n')


def constraint_files(module):
    """``{kind: path}`` of the files :func:`write_constraints` writes, relative to the
    core's folder (``kind``: ``"sdc"``, ``"lpf"``, ``"ice40"``, ``"nextpnr"``)."""
    return {"sdc": f"constraints/{module}.sdc", "lpf": f"constraints/{module}.lpf",
            "ice40": f"constraints/{module}_ice40_clock.py", "nextpnr": f"constraints/{module}_nextpnr.sdc"}


def write_constraints(out_dir, module, clock, ports):
    """Write the files of :func:`constraint_files` into ``out_dir``; returns that dict."""
    files = constraint_files(module)
    texts = {"sdc": sdc_text(module, clock, ports), "lpf": lpf_text(module, clock),
             "ice40": ice40_clock_text(module, clock), "nextpnr": nextpnr_sdc_text(module, clock)}
    for kind, path in files.items():
        atomic_write(os.path.join(out_dir, path), lambda p, text=texts[kind]: _save(p, text))
    return files


def _save(path, text):
    with open(path, "w") as handle:
        handle.write(text)
