"""``phongfx compile``: the scene compiler's command, and how it reports each method.

Kept apart from :mod:`~phongfx.cli.commands` (the other subcommands) because its report
is the longest: every method's result, the chosen design against its defaults and the
Phong baseline, the shipped top, the testbench and the RTL check.
"""

import sys
from functools import partial

from phongfx.core.cache import folder
from phongfx.core.files import check_folder
from phongfx.core.words import levels

from .commands import exit_on_mismatch, target_device

__all__ = ["add_arguments", "cmd_compile"]


def add_arguments(p):
    """``phongfx compile``'s arguments, on its subparser ``p``."""
    p.add_argument("scene", help="scene file (TOML), e.g. scenes/torus.toml")
    p.add_argument("-o", "--output", required=True, help="output folder")
    p.add_argument("--synth", action="store_true",
                   help="cost by synthesis (yowasp; OpenSTA on asic) instead of the proxy")
    p.add_argument("--target", default="ecp5", choices=("ecp5", "ice40", "asic"),
                   help="what cost means: ecp5 (default) or ice40 LUT-eq, asic area in µm²")
    p.add_argument("--device", help="FPGA part (ecp5 25k/45k/85k, ice40 up5k/hx8k/hx1k)")
    p.add_argument("--library", help="standard cells for --target asic: osu018 (default) or osu035")
    p.add_argument("--liberty", metavar="FILE", help="standard cells for --target asic from any Liberty file "
                                                     "(a foundry's library): mapped and timed at its corner")
    p.add_argument("--freq", type=float, default=150,
                   help="clock given to synthesis in MHz (default 150; --clock when given)")
    p.add_argument("--throughput", type=float, metavar="MPX",
                   help="pixel rate the core must sustain, Mpixel/s, instead of the scene's "
                        "requirement.mpixels_per_second (or width × height × fps)")
    p.add_argument("--clock", type=float, metavar="MHZ",
                   help="the clock the core will run at, MHz: the design must reach it, its pixel rate is "
                        "clock / interval (default: each design at its own Fmax)")
    p.add_argument("--workers", type=int, help="with --synth: worker processes (default: all cores; 1: in-process)")
    p.add_argument("--scheduler", help="with --synth: Dask scheduler address, or 'local' for a LocalCluster")
    p.add_argument("--seed", type=int, default=1, help="nextpnr's placement seed (default 1)")
    p.add_argument("--max-error", type=float, metavar="LEVELS",
                   help="instead of the scene's requirement.max_error_levels (display levels, > 0)")
    from phongfx.core.methods import METHODS
    p.add_argument("--methods",
                   help=f"comma-separated methods to consider: {', '.join(METHODS)} (default all)")
    p.add_argument("--no-check", action="store_true", help="skip the cycle-by-cycle RTL check")
    p.add_argument("--testbench", action="store_true",
                   help="does nothing: DIR/testbench (frame 0 as a self-checking Verilog testbench for "
                        "Icarus and Verilator, the FuseSoC core's sim target) is always written; kept for scripts")
    p.add_argument("--vcd", metavar="FILE", help="waveform of the RTL check (Verilator --trace)")
    p.add_argument("--prove", action="store_true",
                   help="prove the chosen design's overflow=\"error\" claims (phongfx prove; minutes per claim "
                        "on a datapath); a design with a counterexample is not chosen")
    p.add_argument("--prove-timeout", type=float, default=600, metavar="S",
                   help="with --prove: seconds per claim before it is reported unknown (default 600)")
    p.add_argument("--samples", type=int, metavar="N",
                   help="domain points each measured design is measured on, instead of the scene's "
                        "[domain] samples (default 1,000,000)")
    p.add_argument("--final-samples", type=int, metavar="N",
                   help="fresh domain points the chosen design's witness is searched on, instead of the "
                        "scene's [domain] final_samples (default 2,000,000)")
    p.add_argument("--sampled", action="store_true",
                   help="choose by the measured error alone (the frames and a sample of the scene's domain, the "
                        "witness search): faster, and a choice for methods without a bounding method, but the "
                        "manifest says certified: false (default: certified, every width point bounded too)")
    p.add_argument("--certified", action="store_true",
                   help="does nothing: certified is the default (--sampled is the other way); kept for scripts")
    p.add_argument("--quiet", action="store_true", help="no progress bar")



def _cost(cost, synth=False):
    """``LUT-eq 1234`` or ``area 56,789 µm²`` of a compile cost dict; why it is missing."""
    value = cost.get("cost")
    if value is None:
        log = f"; log {cost['log']}" if cost.get("log") else ""
        return f"cost unknown ({cost.get('why', 'not costed')}{log})"
    # under --synth an infeasible method's defaults keep the proxy's cost: say which it is
    model = " by the proxy" if synth and str(cost.get("model")).endswith("-proxy") else ""
    if cost.get("unit") == "µm²":
        return f"area {value:,.0f} µm²{model}"
    return f"LUT-eq {value:.0f}{model}"


def _speed(cost, asked):
    """`` [depth 2, interval 2: 50 Mpixel/s]`` of a method's cost when a speed was asked, or
    why none of its architectures meets it."""
    if not asked or "pixel_rate_mpx" not in cost:
        return ""
    a = cost["architecture"]
    verdict = (", over the part" if cost.get("why_not") == "fit"
               else "" if cost.get("met", True) else ", the fastest, too slow")
    return f" [depth {a['pipeline']}, interval {a['interval']}: {cost['pixel_rate_mpx']:g} Mpixel/s{verdict}]"


def _saving(cost, other):
    if cost.get("cost") is None or not other.get("cost"):
        return ""
    return f" (chosen saves {1 - cost['cost'] / other['cost']:.1%})"


def _levels(value):
    """A max error in display levels (whole numbers at the outputs; "inf" when unbuildable)."""
    if isinstance(value, float) and value.is_integer():
        value = int(value)
    return levels(value, ".3f" if isinstance(value, float) else "")


def _where(result):
    """``frames 1, domain 1`` of a method's result: where its max error was measured."""
    domain = result.get("domain_max")
    if domain is None:
        return f"frames {_levels(result.get('frames_max', result['max'])).split()[0]}, domain not measured"
    return (f"frames {_levels(result['frames_max']).split()[0]}, domain {_levels(domain).split()[0]} "
            f"on {result['domain_points']:,} points")


def _certified(certificate):
    """``, certified ≤ 1.4 (interval)`` or why the design is not certified."""
    if not certificate:
        return ", not certified (--sampled)"
    bound, method = certificate["bound_levels"], certificate["method"]
    if certificate["certified"]:
        return f", certified ≤ {bound:.3g} ({method})"
    if bound is None:
        return f", not certified ({certificate['why']})"
    return f", not certified: bound {bound:.3g} ({method})"


def certificate_line(data, folder):
    """The report's line on the shipped design's certificate: its bound and parts, or why it has none."""
    certificate = data["certificate"]
    if not certificate:
        return (f"  not certified: --sampled chose by the measured error alone; "
                f"phongfx certify {folder} bounds it")
    if not certificate["certified"]:
        return f"  not certified: {certificate['why']}"
    parts = certificate["parts"]
    named = " + ".join(f"{name} {parts[name]:.3g}" for name in ("rounding", "approximation", "output")
                       if isinstance(parts.get(name), (int, float)))
    return (f"  certified: no input of the domain is more than {levels(data['requirement']['max_error_levels'])} "
            f"off: bound {certificate['bound_levels']:.3f} levels ({certificate['method']}"
            + (f": {named}" if named else "") + f"; {certificate['seconds']:.1f} s)")


def timing_line(timing):
    """``  architecture: depth 2, interval 1, shared inputs; 120 MHz by the clock proxy, ...``"""
    from phongfx.explore.compile.architecture import describe

    if timing.get("fmax_mhz") is None:
        return (f"  architecture: {describe(timing['architecture'])}; clock not estimated (no clock proxy for this "
                f"target: --synth measures it); latency {timing['latency']} cycles")
    source = "synthesized" if timing["clock_source"] == "synthesis" else "promised by the clock proxy"
    error = ""
    if timing["clock_source"] != "synthesis" and timing.get("clock_error") is not None:
        margin = timing.get("clock_margin") or 0
        error = (f" (its estimate {timing['clock_estimate_mhz']:g} less a {margin:.0%} margin, " if margin else " (") + (
            f"never above synthesis on its calibration, at most {timing['clock_error']:.0%} below)")
    asked = timing.get("requirement_mpx")
    verdict = (f" against {asked:g} Mpixel/s asked" if asked else "") + (
        "" if timing.get("clock_required_mhz") is None else ": met" if timing["met"] else ": NOT MET")
    return (f"  architecture: {describe(timing['architecture'])}; clock {timing['clock_mhz']:g} MHz {source}{error}, "
            f"{timing['pixel_rate_mpx']:g} Mpixel/s{verdict}; latency {timing['latency']} cycles "
            f"({timing['latency_ns']:g} ns)")


def timing_missed(timing, method):
    """The stderr line of a chosen design whose clock misses what was asked, or None."""
    if timing.get("met") is not False:
        return None
    return (f"phongfx: TIMING NOT MET: {method} reaches {timing['fmax_mhz']:g} MHz "
            f"({'synthesized' if timing['clock_source'] == 'synthesis' else 'by the clock proxy'}), "
            f"{timing['pixel_rate_mpx']:g} Mpixel/s; it needs {timing['clock_required_mhz']:g} MHz: missed by "
            f"{timing['missed_by_mhz']:g} MHz ({timing['missed_by_percent']:g}%)")


def fit_lines(fit):
    """How the chosen design fits its FPGA part: one line, and a warning within the proxy's margin."""
    if not fit:
        return []
    names = {"lut4": "LUT4", "dsp": "DSP", "bram_bits": "block RAM bits"}
    used = ", ".join(f"{names[k]} {r['need']:,} of {r['available']:,}" for k, r in fit["resources"].items()
                     if r["need"] or k != "bram_bits")
    lines = [f"  fits the {fit['part']} ({fit['source']}): {used}"]
    if fit["status"] == "margin":
        near = ", ".join(f"{names[k]} {fit['resources'][k]['need']:,} ±{fit['resources'][k]['margin']:.0%} of "
                         f"{fit['resources'][k]['available']:,}" for k in fit["over"])
        lines = [f"  within the proxy's margin of the {fit['part']}: {near}; synthesize to be sure (--synth)"
                 + (f", or --device {fit['smallest_device']}" if fit.get("smallest_device") else "")]
    return lines


def _warm(_):
    """Build the RTL check's simulator run-time objects into the cache (10 processor-seconds of
    C++ when not there yet), so that the check of the chosen design compiles only its own; a
    failure is the check's to report."""
    from phongfx.core.registry import get_block
    from phongfx.explore.compile.workers import step_aside
    from phongfx.sim.fast_build import warm

    step_aside()  # wanted only when the search has ended: the searches go first
    try:
        warm(get_block("lirp").component(), optimize=False)
    except Exception:  # no Verilator, or its build fails: the RTL check says so itself
        pass


def cmd_compile(args):
    from tqdm import tqdm

    from phongfx.compiler.compile import compile_scene
    from phongfx.compiler.request import CompileRequest, check_methods
    from phongfx.core.methods import BASELINE
    from phongfx.explore.compile.emit import emit, prepare_outputs
    from phongfx.explore.compile.architecture import Speed
    from phongfx.explore.compile.workers import Pending
    from phongfx.scene.file import load_scene, with_requirement, with_throughput
    methods = check_methods([m.strip() for m in args.methods.split(",")]) if args.methods else None
    device = target_device(args.target, args.device, args.library, args.liberty)
    spec = load_scene(args.scene)
    if args.sampled and args.certified:
        raise ValueError("--sampled and --certified contradict each other: certified is the default, "
                         "--sampled chooses by the measured error alone")
    if args.max_error is not None:
        spec = with_requirement(spec, args.max_error)
    if args.throughput is not None:
        spec = with_throughput(spec, args.throughput)
    Speed(spec.requirement.mpixels_per_second, args.clock)  # a bad --clock fails before the search
    check_folder(args.output)
    # the RTL check's simulator run time, built while the width search runs
    warming = None if args.no_check else Pending(_warm, None)
    with tqdm(desc=f"compile {spec.name}", unit="step", disable=args.quiet, file=sys.stderr,
              bar_format="{desc}: {n} steps {elapsed}") as bar:
        def progress(step):
            bar.set_description(f"compile {spec.name}: {step}")
            bar.update(1)
        try:
            compiled = compile_scene(CompileRequest(
                spec, methods=methods, synth=args.synth, target=args.target, device=device, freq=args.freq,
                seed=args.seed, clock=args.clock, scheduler=args.scheduler, workers=args.workers,
                samples=args.samples, final_samples=args.final_samples, journal=folder("compile"),
                prove=args.prove, prove_timeout=args.prove_timeout,
                certify="none" if args.sampled else "search",
                certificates=None if args.sampled else folder("compile") / "certificates",
                progress=progress,
                prepare=partial(prepare_outputs, scene=spec.name, check=not args.no_check, vcd=args.vcd)))
            if warming is not None:
                warming.result()
        finally:  # interrupted, or the compile failed: the build need not finish
            if warming is not None:
                warming.cancel()
        try:
            if compiled.refused and compiled.refused["why"] in ("fit", "certificate"):
                for line in compiled.refused["text"]:
                    print(f"phongfx: refused: {line}", file=sys.stderr)
                print(f"phongfx: nothing written to {args.output}", file=sys.stderr)
                return 1
            data = emit(compiled, args.output, check=not args.no_check, progress=progress,
                        testbench=args.testbench, vcd=args.vcd)
        finally:  # the outputs prepared beside, when emit did not take them
            compiled.close()
    for name, reason in data["rejected"].items():
        print(f"  {name:12s} rejected: {reason}")
    asked = data["requirement"].get("mpixels_per_second") or data["requirement"].get("clock_mhz")
    for name, r in data["methods"].items():
        default = f"defaults: max {_levels(r['default']['max'])}, {_cost(r['default']['cost'], args.synth)}"
        if r["feasible"]:
            bound = f", bound {r['certificate']['bound_levels']:.3g}" if r.get("certificate") else ""
            print(f"  {name:12s} max {_levels(r['max'])}{bound} {_cost(r['cost'])}{_speed(r['cost'], asked)} at "
                  f"{r['params']} ({_where(r)}; {default})")
            if r.get("why_not_chosen"):
                print(f"  {'':12s}   not chosen: {r['why_not_chosen']}")
        else:
            print(f"  {name:12s} infeasible: best max {_levels(r['max'])} at {r['params']} ({default})")
            for why in r.get("why", []):
                print(f"  {'':12s}   {why}")
    print(f"cost model: {data['cost_model']}; wrote {args.output}/manifest.json")
    if data["chosen"] is None and data.get("refused"):
        for line in data["refused"]["text"]:
            print(f"phongfx: {line}; see {args.output}/manifest.json", file=sys.stderr)
        return 1
    if data["chosen"] is None:
        print(f"phongfx: no method meets max_error_levels = {spec.requirement.max_error_levels} "
              f"against {spec.requirement.against} on {spec.name}; see {args.output}/manifest.json",
              file=sys.stderr)
        for line in (data["hint"] or {}).get("text", []):
            print(f"phongfx: hint: {line}", file=sys.stderr)
        return 1
    error, witness = data["error"], data["witness"]
    print(f"chosen {data['chosen']} ({data['module']}): max {_levels(float(witness['error_levels']))} over the "
          f"domain (witness; frames {_levels(error['frames_max']).split()[0]}){_certified(data['certificate'])} "
          f"at out_r/g/b, "
          f"mean {error['mean']:.4f} ({witness['unrounded']:.3f} against the unrounded reference), "
          f"{_cost(data['cost'])}, latency {data['latency']}")
    if data["timing"].get("architecture"):  # not when every synthesis of the design failed
        print(timing_line(data["timing"]))
    for line in fit_lines(data.get("fit")):
        print(line)
    for step in data["witness_rounds"]:
        print(f"  {step['method']} at {step['params']}: witness {levels(step['witness_levels'])}, "
              + (f"searched again with {step['hard_points']} hard points" if step["action"] == "searched again"
                 else "not chosen"))
    print(f"  witness: {witness['found_by']}; replay: {witness['replay']}")
    print(certificate_line(data, args.output))
    tie = data["tie"]
    if tie:
        runner = _cost({"cost": tie["runner_up_cost"], "unit": data["cost"].get("unit")})
        print(f"  tie: {tie['runner_up']} is within {tie['within']:.0%} ({runner}, max "
              f"{_levels(tie['runner_up_max'])}); decided by {tie['decided_by']}")
    where = data["cost"]
    if where.get("utilisation"):
        used = ", ".join(f"{name} {u['percent']:g}%" for name, u in where["utilisation"].items()
                         if u["percent"] is not None)
        print(f"  on {where.get('part') or where['device']} at {where['freq']:g} MHz, seed {where['seed']}: "
              f"{used} of the device (the synthesis harness included)")
    default = data["default_widths"]
    misses = default["max"] > spec.requirement.max_error_levels
    print(f"  against its default widths: max {_levels(default['max'])}, {_cost(default['cost'])}"
          + (" (the defaults miss the requirement)" if misses else _saving(data['cost'], default['cost'])))
    baseline = data["conventional_baseline"]
    if data["chosen"] == BASELINE:
        print("  the chosen design is conventional Phong itself")
    elif "why_not" in baseline:
        print(f"  against conventional Phong: {baseline['why_not']}")
    elif baseline["feasible"]:
        print(f"  against conventional Phong meeting the same requirement: max {_levels(baseline['max'])}, "
              f"{_cost(baseline['cost'])} at {baseline['params']}{_saving(data['cost'], baseline['cost'])}")
    else:
        print(f"  conventional Phong misses the requirement: max {_levels(baseline['max'])} even at "
              f"{baseline['params']}")
    proof = data["overflow_proof"]
    if "claims" in proof:
        print(f"  overflow claims: {len(proof['claims'])}; proven {proof['proven']}, by width {proof['static']}, "
              f"counterexample {proof['counterexample']}, unknown {proof['unknown']} ({proof['seconds']:.0f} s; "
              f"assuming {'; '.join(proof['assumptions'])})")
    top = data["top"]
    print(f"shipped top: {args.output}/{top['file']} ({top['module']}, {len(top['ports'])} ports, "
          f"latency {top['latency']}"
          + (f", one pixel every {top['interval']} clocks)" if top.get("interval", 1) > 1 else ")"))
    print(f"report: {args.output}/report.html")
    if "testbench" in data:
        print(f"testbench: {args.output}/testbench ({data['testbench']['vectors']} vectors of frame "
              f"{data['testbench']['frame']}; run: sh {args.output}/testbench/run.sh)")
    if "flow" in data:
        flow = data["flow"]
        print(f"constraints: {args.output}/constraints (clk {flow['clock_mhz']:g} MHz: .sdc, .lpf for ECP5, "
              f"_ice40_clock.py for nextpnr-ice40 --pre-pack, _nextpnr.sdc for nextpnr --sdc)")
        print(f"FuseSoC core: {args.output}/{flow['fusesoc_core']} (run: fusesoc --cores-root {args.output} run "
              f"--target sim {flow['fusesoc_name']})")
    missed = timing_missed(data["timing"], data["chosen"])
    if missed:
        print(missed, file=sys.stderr)
    check = data["rtl_check"]
    if check is None:
        return 1 if missed else 0
    print(f"RTL check frame {check['frame']}: {check['pixels']} pixels, {check['cycles']} cycles "
          f"({check['stalls']:.0%} out_ready stalls, a reset at cycle {check['reset_at_cycle']}), "
          f"{check['mismatches']} mismatches, {check['seconds']:.2f} s")
    return exit_on_mismatch(check["mismatches"], f"; see {args.output}/manifest.json") or (1 if missed else 0)
