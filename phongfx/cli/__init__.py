"""The ``phongfx`` command line.

``phongfx blocks`` lists the datapath blocks; ``phongfx verilog NAME -o FILE`` emits
one as Verilog; ``phongfx sim NAME`` checks it cycle by cycle against its golden
model; ``phongfx compile SCENE.toml -o DIR`` compiles a scene to its cheapest datapath;
``phongfx render`` is ``make sim``: Lyon's scene through Figure 7, golden and
RTL.  ``--set field=value`` (repeatable; ``shape.k=1`` inside a composite) changes
the block's configuration.  Errors go to stderr with exit code 2 (bad input) or 1
(a mismatch).
"""

import argparse
import dataclasses
import json
import os
import sys

from phongfx.core.registry import block_names, get_block
from phongfx.explore.synth import SynthError
from phongfx.sim.harness import BACKENDS
from phongfx.explore.tables import TABLES, table_module

__all__ = ["main", "apply_settings", "MAX_SIZE"]

#: Largest ``--size`` of ``render mesh`` / ``render frames`` (an 8K frame).
MAX_SIZE = 8192


class _Parser(argparse.ArgumentParser):
    """argparse, but a usage error is one ``phongfx: error:`` line like every other bad input."""

    def error(self, message):
        self.print_usage(sys.stderr)
        where = self.prog.partition(" ")[2]
        self.exit(2, f"phongfx: error: {where + ': ' if where else ''}{message}\n")


def apply_settings(config, settings):
    """``config`` with ``["field=value", "sub.field=value"]`` applied (types follow the field)."""
    for setting in settings:
        if "=" not in setting:
            raise ValueError(f"--set wants field=value, not {setting!r}")
        path, text = setting.split("=", 1)
        config = _set(config, path.split("."), text, path)
    return config


def _set(config, parts, text, path):
    names = [f.name for f in dataclasses.fields(config)]
    if parts[0] not in names:
        raise ValueError(f"--set {path}: {type(config).__name__} has no field {parts[0]!r}; "
                         f"fields: {', '.join(names)}")
    current = getattr(config, parts[0])
    if len(parts) == 1 and dataclasses.is_dataclass(current):
        # a whole sub-config cannot be parsed from one string; point at its fields instead
        fields = ", ".join(f"{parts[0]}.{f.name}" for f in dataclasses.fields(current))
        raise ValueError(f"--set {path}: {parts[0]} is a {type(current).__name__}; set one of its "
                         f"fields instead: {fields}")
    if len(parts) > 1:
        if not dataclasses.is_dataclass(current):
            raise ValueError(f"--set {path}: {parts[0]} has no sub-fields")
        value = _set(current, parts[1:], text, path)
    elif isinstance(current, bool) or not isinstance(current, int):
        value = text
    else:
        try:
            value = int(text)
        except ValueError:
            raise ValueError(f"--set {path}: {parts[0]} must be an integer, not {text!r}") from None
    return dataclasses.replace(config, **{parts[0]: value})


def _block(args):
    block = get_block(args.name)
    if args.set:
        block = get_block(args.name, config=apply_settings(block.config, args.set))
        _dry_run(block, args.set)
    return block


def _dry_run(block, settings):
    """Run the golden model once on the block's directed vectors, so that a setting which
    makes an intermediate format too wide for int64, or a declared-safe quantize overflow,
    is reported against the ``--set`` that caused it rather than the intermediate's name."""
    try:
        block.golden(block.stimulus(count=0, seed=0))
    except ValueError as error:
        raise ValueError(f"--set {' '.join(settings)}: {error}") from None
    except OverflowError as error:
        raise ValueError(f"--set {' '.join(settings)}: {error}; widen that format") from None


def _cmd_blocks(args):
    for name in block_names():
        block = get_block(name)
        print(f"{name:16s} latency {block.latency:3d}  {block.config}")
    return 0


def _cmd_verilog(args):
    from phongfx.hdl.emit import write_verilog
    block = _block(args)
    write_verilog(block.component(), args.name, args.output)
    print(f"wrote {args.output}", file=sys.stderr)
    return 0


def _cmd_sim(args):
    from phongfx.sim.harness import check
    if args.seed < 0:
        raise ValueError(f"--seed must be a non-negative integer, not {args.seed}")
    block = _block(args)
    options = {"vcd": args.vcd} if args.vcd else {}
    if args.vcd and args.backend != "amaranth":
        raise ValueError("--vcd is written by the amaranth back end; add --backend amaranth")
    result = check(block, backend=args.backend, count=args.vectors, seed=args.seed,
                   bubbles=args.bubbles, **options)
    print(result.describe())
    print(f"{result.cycles_per_second:.0f} cycles/s")
    return 0 if result.ok else 1


def _exit_on_mismatch(count, where=""):
    """Exit code 1 (and a line on stderr) if golden and RTL differed on ``count`` pixels."""
    if count:
        print(f"MISMATCH between golden and RTL: {count} pixel(s){where}", file=sys.stderr)
        return 1
    return 0


def _cmd_render(args):
    if args.target == "mesh":
        return _cmd_render_mesh(args)
    if args.target == "frames":
        return _cmd_render_frames(args)
    from phongfx.config import fig7_config
    from phongfx.render.lyon import run
    config = apply_settings(fig7_config(), args.set or [])
    summary = run(config, radius=args.radius, span=args.span, backend=args.backend,
                  out_dir=args.out, quiet=args.quiet)
    print(f"pixels checked {summary['pixels_checked']}, mismatches {summary['mismatches']}, "
          f"cycles {summary['cycles']}")
    for name, speed in summary["cycles_per_second"].items():
        print(f"  {name}: {speed['cycles_per_second']:.0f} cycles/s")
    for mode, errors in summary["error_8bit"].items():
        for what, value in errors.items():
            if isinstance(value, dict):
                print(f"  {mode:6s} {what:22s} max {value['max']:7.2f}  mean {value['mean']:7.3f} levels")
    print(f"wrote {args.out}/fig7.png, {args.out}/fig7_error.png, {args.out}/summary.json")
    return _exit_on_mismatch(summary["mismatches"], "; see summary.json")


def _check_size(size):
    # the frame buffers are size² int64 arrays per quantity: bound them before allocating
    if size > MAX_SIZE:
        raise ValueError(f"--size must be an integer in 1..{MAX_SIZE}, not {size}")


def _cmd_render_mesh(args):
    from phongfx.render import mesh as mesh_render
    _check_size(args.size)
    if args.figure:
        figure = {"14": mesh_render.figure14, "15": mesh_render.figure15}[args.figure]
        summary = figure(out_dir=args.mesh_out)
    else:
        summary = mesh_render.run(args.method, mesh=args.mesh, polygons=args.polygons,
                                  stacks=args.stacks, slices=args.slices, n=args.n,
                                  addr_bits=args.addr_bits, rom_bits=args.rom_bits,
                                  width=args.size, height=args.size, frame=args.frame,
                                  out_dir=args.mesh_out)
    print(json.dumps(summary, indent=2, default=str))
    return 0


def _cmd_render_frames(args):
    from phongfx.render.frames import UNITS, markdown, run_all
    _check_size(args.size)
    result = run_all(out_dir=args.frames_out, units=args.units or UNITS, quiet=args.quiet,
                     backend=args.frames_backend, polygons=args.polygons, width=args.size,
                     height=args.size, frame=args.frame)
    print(markdown(result))
    print(f"wrote {args.frames_out}/frames.json")
    return _exit_on_mismatch(result["mismatches"])


def _cmd_synth(args):
    from tqdm import tqdm

    from phongfx.explore.synth import markdown, synth
    block = _block(args)
    with tqdm(total=3, desc=f"synth {args.name}", disable=args.quiet or args.json,
              bar_format="{desc}: {n}/{total} steps {elapsed}") as bar:
        def progress(step):
            bar.set_description(f"synth {args.name}: {step}")
            bar.update(1)
        result = synth(args.name, config=block.config, target=args.target, device=args.device,
                       freq=args.freq, seed=args.seed, workdir=args.workdir, progress=progress)
    print(json.dumps(result, indent=2, default=str) if args.json else markdown([result]), end="")
    return 0


def _cmd_sweep(args):
    from phongfx.core.files import atomic_write
    from phongfx.explore.report import pareto_plot, summary_markdown
    from phongfx.explore.sweep import load_records, run_sweep
    try:
        summary = run_sweep(args.spec, out=args.out, workers=args.workers, scheduler=args.scheduler,
                            progress=not args.quiet)
    except KeyboardInterrupt:
        print(f"phongfx: interrupted; finished points are kept in {args.out}/points.jsonl "
              f"- run again to resume", file=sys.stderr)
        return 130
    records = load_records(summary["jsonl"])
    scene = next((r["scenes"][0] for r in records if r.get("scenes")), "torus")
    plot = pareto_plot(records, os.path.join(args.out, "pareto.png"), f"{scene}.phong.max")
    text = "\n".join(summary_markdown(records, f"{scene}.{ref}.max") for ref in ("phong", "self"))
    atomic_write(os.path.join(args.out, "summary.md"), lambda p: open(p, "w").write(text))
    print(text)
    print(f"{summary['ran']} point(s) run ({summary['ok']} ok, {summary['failed']} failed), "
          f"{summary['skipped']} already done, of {summary['total']}; wrote {summary['csv']}, "
          f"{args.out}/pareto.png ({plot['plotted']} points with cost), {args.out}/summary.md")
    if summary["failed"]:
        print(f"phongfx: {summary['failed']} point(s) failed; see the error column", file=sys.stderr)
    return 0


def _cmd_report(args):
    from phongfx.explore.report import build_report
    tables = tuple(args.tables) if args.tables is not None else tuple(TABLES)
    for name in tables:
        table_module(name)  # refuses an unknown name before any work
    print(f"wrote {build_report(out_dir=args.out, sweep_dir=args.sweep, tables=tables, quick=args.quick)}")
    return 0


def _cmd_figure9(args):
    from tqdm import tqdm

    from phongfx.papers.lyon.figure9 import FIXED_ROWS, markdown, run
    from phongfx.scene.lyon import Scene, pixels
    total = len(pixels(Scene(radius=args.radius))) * sum(len(rows) for rows in FIXED_ROWS.values())
    with tqdm(total=total, unit="px", desc=f"RTL ({args.backend})", disable=args.quiet) as bar:
        table = run(out_dir=args.out, backend=args.backend, radius=args.radius, progress=bar.update)
    print(markdown(table))
    print(f"wrote {args.out}/figure9.png, figure9_diff.png, figure9.md, figure9.json")
    return _exit_on_mismatch(table["rtl_mismatches"])




def _levels(value):
    return f"{value:.3f} levels" if isinstance(value, float) else f"{value} levels"


def _cmd_compile(args):
    from tqdm import tqdm

    from phongfx.explore.compile.compiler import check_methods, compile_scene
    from phongfx.explore.compile.emit import emit
    from phongfx.scene.file import load_scene
    methods = check_methods([m.strip() for m in args.methods.split(",")]) if args.methods else None
    spec = load_scene(args.scene)
    with tqdm(desc=f"compile {spec.name}", unit="step", disable=args.quiet, file=sys.stderr,
              bar_format="{desc}: {n} steps {elapsed}") as bar:
        def progress(step):
            bar.set_description(f"compile {spec.name}: {step}")
            bar.update(1)
        compiled = compile_scene(spec, methods=methods, synth=args.synth, progress=progress)
        data = emit(compiled, args.output, check=not args.no_check, progress=progress)
    for name, reason in data["rejected"].items():
        print(f"  {name:12s} rejected: {reason}")
    for name, r in data["methods"].items():
        default = f"defaults: max {_levels(r['default']['max'])}, LUT-eq {r['default']['cost'].get('lut_eq')}"
        if r["feasible"]:
            print(f"  {name:12s} max {_levels(r['max'])} LUT-eq {r['cost']['lut_eq']} at {r['params']} "
                  f"({default})")
        else:
            print(f"  {name:12s} infeasible: max {_levels(r['max'])} even at {r['params']} ({default})")
    print(f"cost model: {data['cost_model']}; wrote {args.output}/manifest.json")
    if data["chosen"] is None:
        print(f"phongfx: no method meets max_error_levels = {spec.requirement.max_error_levels} "
              f"against {spec.requirement.against} on {spec.name}; see {args.output}/manifest.json",
              file=sys.stderr)
        return 1
    check = data["rtl_check"]
    print(f"chosen {data['chosen']} ({data['module']}): max {data['error']['max']:.3f} levels, "
          f"mean {data['error']['mean']:.4f}, LUT-eq {data['cost']['lut_eq']}, latency {data['latency']}")
    if check is None:
        return 0
    print(f"RTL check frame {check['frame']}: {check['pixels']} pixels, {check['cycles']} cycles, "
          f"{check['mismatches']} mismatches, {check['seconds']:.2f} s")
    return _exit_on_mismatch(check["mismatches"], f"; see {args.output}/manifest.json")


def _cmd_tables(args):
    module = table_module(args.table)
    result = module.run_table(args.table, out_dir=args.out or f"build/{args.table}")
    print(module.to_json(result) if args.json else module.markdown(result))
    return 0


def _mesh_parser(p):
    p.add_argument("--method", default="phong",
                   help="phong, gouraud, euler, corrected-euler, cosn, spherical (default phong)")
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
    p.add_argument("--out", dest="mesh_out", default="build/mesh", help="output folder")


def _frames_parser(p):
    p.add_argument("--units", nargs="+", metavar="UNIT", help="euler gouraud spherical schlick (default all)")
    p.add_argument("--backend", dest="frames_backend", choices=BACKENDS, default="verilator-fast")
    p.add_argument("--polygons", type=int, default=800, help="torus polygons")
    p.add_argument("--size", type=int, default=256, help="frame width and height in pixels")
    p.add_argument("--frame", type=int, default=0, help="frame of the 200-frame rotation")
    p.add_argument("--out", dest="frames_out", default="build/frames", help="output folder")
    p.add_argument("--quiet", action="store_true", help="no progress bar")


def _parser():
    parser = _Parser(prog="phongfx", description=__doc__.split("\n\n")[0])
    sub = parser.add_subparsers(dest="command", required=True)

    sub.add_parser("blocks", help="list the datapath blocks").set_defaults(run=_cmd_blocks)

    def with_block(p):
        p.add_argument("name", choices=block_names(), help="block name")
        p.add_argument("--set", action="append", metavar="FIELD=VALUE", help="change a config field")

    p = sub.add_parser("verilog", help="emit a block as Verilog")
    with_block(p)
    p.add_argument("-o", "--output", required=True, help="Verilog file to write")
    p.set_defaults(run=_cmd_verilog)

    p = sub.add_parser("sim", help="check a block against its golden model, cycle by cycle")
    with_block(p)
    p.add_argument("--backend", choices=BACKENDS, default="verilator-fast")
    p.add_argument("--vectors", type=int, default=1000, help="random vectors beyond the directed ones")
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--bubbles", type=float, default=0.25, help="probability of an idle cycle")
    p.add_argument("--vcd", help="write a waveform (amaranth back end)")
    p.set_defaults(run=_cmd_sim)

    p = sub.add_parser("synth", help="synthesize, place and route a block: LUTs, FFs, DSPs, Fmax (yowasp tools)")
    with_block(p)
    p.add_argument("--target", default="ecp5", help="ecp5 (default) or ice40")
    p.add_argument("--device", help="part size: ecp5 25k/45k/85k (default 45k), ice40 up5k/hx8k/hx1k")
    p.add_argument("--freq", type=float, default=150, help="target clock in MHz (default 150)")
    p.add_argument("--seed", type=int, default=1, help="placer seed")
    p.add_argument("--workdir", default="build/synth", help="cache and run folder")
    p.add_argument("--json", action="store_true", help="print the whole result as JSON")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(run=_cmd_synth)

    p = sub.add_parser("sweep", help="error against cost over methods and bit widths (TOML spec)")
    p.add_argument("spec", help="sweep spec, e.g. sweeps/default.toml (see sweeps/README.md)")
    p.add_argument("--workers", type=int, help="worker processes (default: all cores; 1: in-process)")
    p.add_argument("--scheduler", help="Dask scheduler address, or 'local' for a LocalCluster")
    p.add_argument("--out", default="build/sweep", help="output folder")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(run=_cmd_sweep)

    p = sub.add_parser("report", help="build/report/index.md: the papers' tables beside our measurements, "
                                      "the sweep's Pareto plots and cheapest invisible-error datapaths")
    p.add_argument("--out", default="build/report", help="output folder")
    p.add_argument("--sweep", default="build/sweep", help="sweep folder holding points.jsonl")
    p.add_argument("--tables", nargs="*", metavar="TABLE", help="tables to include (default all)")
    p.add_argument("--quick", action="store_true", help="fewer frames and blocks (a smoke run)")
    p.set_defaults(run=_cmd_report)

    p = sub.add_parser("render", help="shade Lyon's scene through Figure 7 (what `make sim` runs)")
    p.add_argument("--backend", choices=BACKENDS, default="verilator-fast")
    p.add_argument("--radius", type=int, default=64, help="sphere radius in pixels")
    p.add_argument("--span", type=int, default=8, help="span length for interpolated normals")
    p.add_argument("--out", default="build/sim", help="output folder")
    p.add_argument("--set", action="append", metavar="FIELD=VALUE", help="change a DatapathConfig field")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(run=_cmd_render, target=None)
    targets = p.add_subparsers(dest="target", metavar="{mesh,frames}",
                               help="instead of Lyon's scene: a triangle mesh, or RTL full frames")
    _mesh_parser(targets.add_parser("mesh", help="shade a tessellated sphere or torus by method (PNG)"))
    _frames_parser(targets.add_parser(
        "frames", help="one full torus frame through the RTL of the euler, gouraud, spherical and schlick units"))

    p = sub.add_parser("figure9", help="Lyon's Figure 9: float rows and fixed-point rows, RTL-checked")
    p.add_argument("--out", default="build/figure9", help="output folder")
    p.add_argument("--backend", choices=BACKENDS, default="verilator-fast")
    p.add_argument("--radius", type=int, default=64, help="sphere radius in pixels (Lyon: 64)")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(run=_cmd_figure9)
    p = sub.add_parser("tables", help="paper claims measured: `tables lyon` (Apple TR #43), "
                                         "`tables szirmay` (Szirmay-Kalos et al. 2000), `tables schlick` (Figure 1), "
                                         "`tables hast` (Hast et al. Tables 1–2), `tables cost` (synthesis: Figure 7 "
                                         "vs Figure 8 vs the conventional baseline), `tables pipeline` (Fmax against pipeline depth)")
    p.add_argument("table", help="which table (lyon, szirmay, schlick, hast, cost, pipeline)")
    p.add_argument("--json", action="store_true", help="print JSON instead of Markdown")
    p.add_argument("--out", help="folder for the plots (default build/TABLE)")
    p.set_defaults(run=_cmd_tables)
    p = sub.add_parser("compile", help="the cheapest datapath meeting a scene's pixel error "
                                       "requirement: Verilog, manifest, frames, RTL check (issue 7)")
    p.add_argument("scene", help="scene file (TOML), e.g. scenes/torus.toml")
    p.add_argument("-o", "--output", required=True, help="output folder")
    p.add_argument("--synth", action="store_true", help="cost by ECP5 synthesis (yowasp) instead of the proxy")
    p.add_argument("--methods", help="comma-separated methods to consider (default all)")
    p.add_argument("--no-check", action="store_true", help="skip the cycle-by-cycle RTL check")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(run=_cmd_compile)
    return parser


def _os_error(error):
    """``path: reason`` of a failed read or write (the target, not the temporary, of a rename)."""
    where = error.filename2 if error.filename2 is not None else error.filename
    return f"{where}: {error.strerror}" if where is not None and error.strerror else str(error)


def main(argv=None):
    """Run the command line; returns the exit code (0 ok, 1 mismatch, 2 bad input, 130 interrupted).

    Bad input of any kind (usage, ``ValueError`` from a config, a config whose formats
    overflow in the golden model, a file that cannot be read or written, a frame too
    large for memory) is one ``phongfx: error:`` line on stderr and exit code 2,
    never a traceback (``tests/cli/test_bad_input.py`` fuzzes this).
    """
    try:
        args = _parser().parse_args(argv)
    except SystemExit as stop:  # --help (0) or a usage error (2, already printed)
        return 0 if stop.code is None else stop.code
    if getattr(args, "vectors", 1) < 0:
        print("phongfx: error: --vectors must be a non-negative integer", file=sys.stderr)
        return 2
    try:
        return args.run(args)
    except BrokenPipeError:  # output piped into `head` and the like: not an error
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0
    except ValueError as error:
        print(f"phongfx: error: {error}", file=sys.stderr)
        return 2
    except OverflowError as error:
        # golden.fixed.FixedOverflowError: formats a config accepted that cannot hold a value
        # the block computes (e.g. an output without the integer bit 1.0 needs)
        print(f"phongfx: error: overflow: {error}; widen that format", file=sys.stderr)
        return 2
    except OSError as error:  # missing input, unwritable or non-directory output folder
        print(f"phongfx: error: {_os_error(error)}", file=sys.stderr)
        return 2
    except MemoryError as error:
        print(f"phongfx: error: out of memory ({error}); ask for a smaller problem", file=sys.stderr)
        return 2
    except SynthError as error:  # the tools failed (or the design does not fit): not bad input
        first, _, tail = str(error).partition("\n")
        print(f"phongfx: error: synthesis failed: {first}", file=sys.stderr)
        if tail:
            print(tail, file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
