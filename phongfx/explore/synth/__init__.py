"""What a block costs in hardware: synthesis, timing and the tool-free estimates.

* :mod:`.fpga`: synthesis, place and route on the FPGAs (yowasp Yosys + nextpnr, ECP5
  and iCE40), cached;
* :mod:`.asic`: standard-cell synthesis (Yosys onto the OSU Liberty cells) and static
  timing (OpenSTA);
* :mod:`.lutmap`: Yosys' LUT mapping, and its fallbacks where ABC9 fails or gives nets
  two drivers;
* :mod:`.toolrun`: what both flows share (the synthesis harness, the RTLIL of a
  design, the cache of finished runs);
* :mod:`.parallel`: many syntheses at once on Dask, with progress per candidate;
* :mod:`.netlist`: the synthesized FPGA netlist simulated against the golden model;
* :mod:`.proxy`: tool-free cost estimates from the elaborated RTLIL (LUT-eq, and µm²
  fitted to the standard-cell flow by ``phongfx tables proxy``).
"""

from phongfx.explore.synth.asic import DEFAULT_LIBRARY, LIBRARIES, Library, asic_synth
from phongfx.explore.synth.fpga import ALL_TARGETS, TARGETS, SynthError, Target, markdown, synth
from phongfx.explore.synth.netlist import NETLIST_TARGETS, check_netlist, synth_netlist
from phongfx.explore.synth.parallel import synth_all
from phongfx.explore.synth.proxy import proxy_area, proxy_cost, proxy_estimate

__all__ = ["SynthError", "Target", "TARGETS", "ALL_TARGETS", "synth", "markdown",
           "Library", "LIBRARIES", "DEFAULT_LIBRARY", "asic_synth",
           "NETLIST_TARGETS", "synth_netlist", "check_netlist",
           "proxy_cost", "proxy_area", "proxy_estimate", "synth_all"]
