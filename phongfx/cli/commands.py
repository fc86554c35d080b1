"""The ``phongfx`` subcommands: one ``cmd_NAME(args)`` per command, returning its exit code.

Each takes the parsed arguments of :func:`phongfx.cli.parser.build_parser` and prints
its results on stdout.  Bad input raises ``ValueError`` (or ``OSError`` ...), which
:func:`phongfx.cli.main` turns into one ``phongfx: error:`` line; a mismatch between
golden and RTL is exit code 1 with a line on stderr.  The heavy modules are imported
inside each command, so that ``phongfx --help`` or a usage error stays fast.
"""

import json
import os
import sys

from phongfx.core.files import check_folder
from phongfx.core.registry import block_names, get_block
from phongfx.explore.tables import TABLES, table_module

from .settings import apply_settings, configured_block

__all__ = ["MAX_SIZE", "MAX_TESTBENCH_COUNT", "cmd_verilog", "cmd_testbench", "cmd_sim",
           "cmd_render", "cmd_synth", "cmd_sweep", "cmd_report", "cmd_figure9", "cmd_tables",
           "exit_on_mismatch", "target_device"]

#: Largest ``--size`` of ``render mesh`` / ``render frames`` (an 8K frame).
MAX_SIZE = 8192


def cmd_verilog(args):
    from phongfx.hdl.emit import write_verilog
    block = configured_block(args.name, args.set)
    if args.top:
        from pathlib import Path

        from phongfx.core.files import atomic_write
        from phongfx.hdl.top import top_verilog

        text = top_verilog(block.component(), args.name)
        atomic_write(args.output, lambda temp: Path(temp).write_text(text))
    else:
        write_verilog(block.component(), args.name, args.output)
    print(f"wrote {args.output}", file=sys.stderr)
    return 0


#: Largest ``--count`` of ``testbench``: the testbench holds every vector in simulator memory.
MAX_TESTBENCH_COUNT = 1_000_000


def cmd_testbench(args):
    from tqdm import tqdm

    from phongfx.sim.testbench import (MAX_PROBABILITY, SIMULATORS, require_simulator, run_simulator,
                                       write_testbench)
    if not 0 <= args.count <= MAX_TESTBENCH_COUNT:
        raise ValueError(f"--count must be an integer in 0..{MAX_TESTBENCH_COUNT}, not {args.count}")
    if args.seed < 0:
        raise ValueError(f"--seed must be a non-negative integer, not {args.seed}")
    for option in ("stall", "bubbles"):
        value = getattr(args, option)
        if not 0 <= value <= MAX_PROBABILITY:  # also refuses nan
            raise ValueError(f"--{option} must be a probability in 0..{MAX_PROBABILITY}, not {value}")
    block = configured_block(args.name, args.set)
    simulators = SIMULATORS if args.simulate == "both" else (args.simulate,) if args.simulate else ()
    for simulator in simulators:
        require_simulator(simulator)  # refused before anything is written
    steps = 3 + len(simulators)
    with tqdm(total=steps, desc=f"testbench {args.name}", disable=args.quiet, file=sys.stderr,
              bar_format="{desc}: {n}/{total} steps {elapsed}") as bar:
        def stage(step):
            bar.set_description(f"testbench {args.name}: {step}")
        stage("vectors")
        inputs = block.stimulus(count=args.count, seed=args.seed)
        bar.update(1)
        stage("golden")
        expected = block.golden(inputs)
        bar.update(1)
        stage("writing")
        bench = write_testbench(block, inputs, expected, args.output, args.name, seed=args.seed,
                                stall=args.stall, bubbles=args.bubbles, vcd=args.vcd)
        bar.update(1)
        results = {}
        for simulator in simulators:
            stage(simulator)
            results[simulator] = run_simulator(simulator, args.output, args.name)
            bar.update(1)
    print(f"wrote {args.output}: {', '.join(bench.files)} ({bench.vectors} vectors; mid-stream reset "
          f"after {bench.reset_at} results)")
    failed = []
    for simulator, (ok, text, seconds) in results.items():
        verdict = [line for line in text.splitlines() if line.startswith(("PASS", "FAIL"))]
        print(f"{simulator} ({seconds:.1f} s):")
        print("\n".join(f"  {line}" for line in (verdict or text.splitlines()[-20:])))
        if not ok:
            failed.append(simulator)
    if failed:
        print(f"phongfx: testbench of {args.name} FAILED under {', '.join(failed)}", file=sys.stderr)
        return 1
    return 0


def cmd_sim(args):
    from phongfx.sim.harness import check
    # every range checked here, before a Verilator build of up to a minute
    if args.vectors < 0:
        raise ValueError(f"--vectors must be a non-negative integer, not {args.vectors}")
    if args.seed < 0:
        raise ValueError(f"--seed must be a non-negative integer, not {args.seed}")
    for option in ("stalls", "bubbles"):
        value = getattr(args, option)
        if not 0 <= value < 1:  # NaN fails too
            raise ValueError(f"--{option} must be a probability in [0, 1) (at 1 nothing would move), not {value:g}")
    if args.reset_at is not None and args.reset_at < 0:
        raise ValueError(f"--reset-at must be a cycle number, 0 or more, not {args.reset_at}")
    block = configured_block(args.name, args.set)
    options = {"vcd": args.vcd} if args.vcd else {}
    stream = args.stalls or args.reset_at is not None
    if stream and args.netlist:
        raise ValueError("--stalls and --reset-at run the RTL inside Handshake; a --netlist has no ready")
    if stream:
        options.update(stalls=args.stalls, reset_at=args.reset_at)
    if args.device and not args.netlist:
        raise ValueError("--device chooses the synthesis of --netlist; add --netlist ecp5|ice40")
    if args.netlist and args.dsp:
        raise ValueError("--netlist already maps the products as synthesis does; drop --dsp")
    if args.netlist and args.backend != "verilator-fast":
        raise ValueError(f"--netlist is simulated by the verilator-fast back end, not {args.backend}")
    if args.dsp and args.backend == "amaranth":
        raise ValueError("--dsp instantiates DSP primitives, which only the Verilator back ends simulate")
    if args.netlist:
        from phongfx.explore.synth.netlist import check_netlist

        print(f"synthesizing {args.name} for {args.netlist} ...", file=sys.stderr, flush=True)
        result = check_netlist(block, args.netlist, args.device, count=args.vectors, seed=args.seed,
                               bubbles=args.bubbles)
    else:
        from phongfx.hdl.dsp import dsp_mapping

        with dsp_mapping(args.dsp):
            result = check(block, backend=args.backend, count=args.vectors, seed=args.seed,
                           bubbles=args.bubbles, **options)
    print(result.describe())
    print(f"{result.cycles_per_second:.0f} cycles/s")
    return 0 if result.ok else 1


def exit_on_mismatch(count, where=""):
    """Exit code 1 (and a line on stderr) if golden and RTL differed on ``count`` pixels."""
    if count:
        print(f"MISMATCH between golden and RTL: {count} pixel(s){where}", file=sys.stderr)
        return 1
    return 0


#: Defaults of ``render``'s own options, which are None when not given so that a target
#: (``mesh``, ``frames``) can tell an option it takes from one it would silently ignore.
RENDER_DEFAULTS = {"backend": "verilator-fast", "radius": 64, "span": 8, "out": "build/sim", "speed_sample": 0}
#: ``render``'s options that mean nothing to a target, and what they do apply to.
_LYON_ONLY = ("radius", "span", "set", "speed_sample")
_SCENE_ONLY = {**dict.fromkeys(_LYON_ONLY, "Lyon's scene"), "backend": "Lyon's scene and frames (mesh runs no RTL)"}


def _target_option(args, name, own, default):
    """A target's option ``own`` (``mesh_out`` ...): its own value, else ``render``'s ``name``,
    else ``default``; given both ways and different, an error naming both."""
    mine, outer = getattr(args, own), getattr(args, name)
    if mine is not None and outer is not None and mine != outer:
        raise ValueError(f"render --{name} {outer} and render {args.target} --{name} {mine} disagree; give one")
    return next((value for value in (mine, outer) if value is not None), default)


def _refuse_scene_options(args, also=()):
    """Refuse ``render --radius/--span/--set`` (and ``also``) before a target that would
    ignore them: an option silently dropped looks like one that worked."""
    for name in (*_LYON_ONLY, *also):
        if getattr(args, name) is not None:
            raise ValueError(f"render --{name.replace('_', '-')} applies to {_SCENE_ONLY[name]}, "
                             f"not to render {args.target}; drop it")


def cmd_render(args):
    if args.target == "mesh":
        _refuse_scene_options(args, also=("backend",))
        args.mesh_out = _target_option(args, "out", "mesh_out", "build/mesh")
        return cmd_render_mesh(args)
    if args.target == "frames":
        _refuse_scene_options(args)
        args.frames_out = _target_option(args, "out", "frames_out", "build/frames")
        args.frames_backend = _target_option(args, "backend", "frames_backend", RENDER_DEFAULTS["backend"])
        args.quiet = args.quiet or args.frames_quiet
        return cmd_render_frames(args)
    from phongfx.config import fig7_config
    from phongfx.render.lyon import run
    for name, value in RENDER_DEFAULTS.items():
        if getattr(args, name) is None:
            setattr(args, name, value)
    config = apply_settings(fig7_config(), args.set or [])
    check_folder(args.out)
    summary = run(config, radius=args.radius, span=args.span, backend=args.backend,
                  out_dir=args.out, sample=args.speed_sample, quiet=args.quiet)
    print(f"pixels checked {summary['pixels_checked']}, mismatches {summary['mismatches']}, "
          f"cycles {summary['cycles']}")
    for name, speed in summary["cycles_per_second"].items():
        print(f"  {name}: {speed['cycles_per_second']:.0f} cycles/s")
    for mode, errors in summary["error_8bit"].items():
        for what, value in errors.items():
            if isinstance(value, dict):
                print(f"  {mode:6s} {what:22s} max {value['max']:7.2f}  mean {value['mean']:7.3f} levels")
    print(f"wrote {args.out}/fig7.png, {args.out}/fig7_error.png, {args.out}/summary.json")
    return exit_on_mismatch(summary["mismatches"], "; see summary.json")


def _check_size(size):
    # the frame buffers are size² int64 arrays per quantity: bound them before allocating
    if size > MAX_SIZE:
        raise ValueError(f"--size must be an integer in 1..{MAX_SIZE}, not {size}")


def cmd_render_mesh(args):
    from phongfx.render import mesh as mesh_render
    _check_size(args.size)
    if args.method in mesh_render.RENAMED:
        new = mesh_render.RENAMED[args.method]
        print(f"phongfx: note: --method {args.method} is now called {new} (the fixed-point unit, named "
              f"as in compile; the float {new} is {new}-float)", file=sys.stderr)
        args.method = new
    check_folder(args.mesh_out)
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


def cmd_render_frames(args):
    from phongfx.render.frames import markdown, run_all
    _check_size(args.size)
    check_folder(args.frames_out)
    result = run_all(out_dir=args.frames_out, units=args.units, quiet=args.quiet,
                     backend=args.frames_backend, polygons=args.polygons, width=args.size,
                     height=args.size, frame=args.frame)
    print(markdown(result))
    print(f"wrote {args.frames_out}/frames.json and {', '.join(os.path.basename(row['png']) for row in result['frames'])}")
    return exit_on_mismatch(result["mismatches"])


def target_device(target, device, library, liberty=None):
    """The device of ``synth``: for ``asic`` the library (``--library``, ``--device`` as its
    synonym, or ``--liberty FILE``: any Liberty file), for an FPGA the part; a library or a
    Liberty file given for an FPGA is an error, and so is a Liberty file that cannot be used."""
    if target != "asic":
        for option, value in (("--library", library), ("--liberty", liberty)):
            if value is not None:
                raise ValueError(f"{option} applies to --target asic only, not to {target!r} "
                                 f"(use --device for an FPGA part)")
        return device
    if liberty is not None:
        from phongfx.explore.synth.liberty import read_liberty

        if device is not None or library is not None:
            raise ValueError(f"--liberty {liberty!r} and --{'library' if library else 'device'} "
                             f"{library or device!r} both name the cells; give one")
        return read_liberty(liberty).path  # a missing or bad file fails here, before any work
    if device is not None and library is not None and device != library:
        raise ValueError(f"--device {device!r} and --library {library!r} disagree; give one")
    return library or device


def cmd_synth(args):
    from tqdm import tqdm

    from phongfx.explore.synth.fpga import markdown, synth
    block = configured_block(args.name, args.set)
    device = target_device(args.target, args.device, args.library, args.liberty)
    if args.corner and args.target != "asic":
        raise ValueError(f"--corner applies to --target asic only, not to {args.target!r}")
    for corner in args.corner or ():
        target_device("asic", None, None, corner)  # a missing or bad file fails before the synthesis
    with tqdm(total=3, desc=f"synth {args.name}", disable=args.quiet or args.json,
              bar_format="{desc}: {n}/{total} steps {elapsed}") as bar:
        def progress(step):
            bar.set_description(f"synth {args.name}: {step}")
            bar.update(1)
        result = synth(args.name, config=block.config, target=args.target, device=device,
                       freq=args.freq, seed=args.seed, workdir=args.workdir, progress=progress)
    if args.corner:
        from phongfx.explore.synth.asic import time_at

        result["corners"] = [time_at(result, corner) for corner in args.corner]
    print(json.dumps(result, indent=2, default=str) if args.json else markdown([result]), end="")
    for timed in result.get("corners", ()) if not args.json else ():
        path = timed["critical_path"]
        print(f"* the same netlist at {timed['library']} ({timed['corner']}): Fmax {timed['fmax_mhz']:.1f} MHz, "
              f"worst path {path['from']} → {path['to']}, {path['ns']:.2f} ns")
    return 0


def cmd_sweep(args):
    from phongfx.core.files import atomic_write
    from phongfx.explore.report import pareto_plot, summary_markdown
    from phongfx.explore.sweep.run import load_records, run_sweep
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


def cmd_report(args):
    from phongfx.explore.report import build_report
    tables = tuple(args.tables) if args.tables is not None else tuple(TABLES)
    for name in tables:
        table_module(name)  # refuses an unknown name before any work
    from phongfx.core.words import plural

    failed = []
    index = build_report(out_dir=args.out, sweep_dir=args.sweep, tables=tables, quick=args.quick, failed=failed)
    print(f"wrote {index}")
    if failed:
        print(f"phongfx: {plural(len(failed), 'table')} failed ({', '.join(failed)}); see {index}", file=sys.stderr)
        return 1
    return 0


def cmd_figure9(args):
    from tqdm import tqdm

    from phongfx.papers.lyon.figure9 import FIXED_ROWS, markdown, run
    from phongfx.scene.lyon import Scene, pixels
    total = len(pixels(Scene(radius=args.radius))) * sum(len(rows) for rows in FIXED_ROWS.values())
    with tqdm(total=total, unit="px", desc=f"RTL ({args.backend})", disable=args.quiet) as bar:
        table = run(out_dir=args.out, backend=args.backend, radius=args.radius, progress=bar.update)
    print(markdown(table))
    print(f"wrote {args.out}/figure9.png, figure9_diff.png, figure9.md, figure9.json")
    return exit_on_mismatch(table["rtl_mismatches"])


#: The options of ``phongfx tables`` that only some tables take, and which.
_TABLE_OPTIONS = {"target": ("cost", "pipeline"), "library": ("cost", "pipeline", "proxy"),
                  "liberty": ("cost", "pipeline", "proxy", "clock"), "refit": ("proxy", "clock")}


def _table_options(args):
    options = {}
    for option, tables in _TABLE_OPTIONS.items():
        value = getattr(args, option)
        if value in (None, False):
            continue
        if args.table not in tables:
            raise ValueError(f"--{option} applies to tables {', '.join(tables)} only, not to {args.table!r}")
        options[option] = value
    if "liberty" in options:
        if "library" in options:
            raise ValueError(f"--liberty {options['liberty']!r} and --library {options['library']!r} both name "
                             f"the cells; give one")
        options["library"] = target_device("asic", None, None, options.pop("liberty"))
        if args.table in ("cost", "pipeline"):
            options.setdefault("target", "asic")
    if "library" in options and args.table == "clock":
        options["device"] = options.pop("library")
    elif "library" in options and args.table != "proxy":
        if options.get("target", "ecp5") != "asic":
            raise ValueError("--library and --liberty apply to --target asic only")
        options["device"] = options.pop("library")
    if options.get("target") not in (None, "ecp5", "asic"):
        raise ValueError(f"--target must be 'ecp5' or 'asic' for tables, not {options['target']!r}")
    return options


def cmd_tables(args):
    module = table_module(args.table)
    options = _table_options(args)
    result = module.run_table(args.table, out_dir=args.out or f"build/{args.table}", **options)
    print(module.to_json(result) if args.json else module.markdown(result))
    return 0
