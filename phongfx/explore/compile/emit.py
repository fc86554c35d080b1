"""Write what :func:`phongfx.compiler.compile.compile_scene` found, and verify it.

``DIR/manifest.json`` (:func:`manifest`, with the top's input contract as ``"contract"``:
:mod:`phongfx.deliver.contract`; ``"certified"`` and ``"certificate"``, the design's sound
bound, or false and null for a compile by measurement alone; ``"path"``, the scene file
relative to ``DIR``), ``DIR/verilog/<module>_top.v`` (the shipped
design: the named-port top of :mod:`phongfx.hdl.top` around exactly the chosen shader's
blocks, without the simulation-only overflow checks, what the cost is of; its header says
whether the error is certified and the bound: :func:`~phongfx.deliver.contract.error_paragraph`),
``DIR/frames/frame_NNN.png`` (the shader's r, g, b codes of each frame at its first
shininess variant, titled and enlarged) and ``DIR/error/frame_NNN.png`` (its error in
display levels against the reference, the worst channel, with a colour bar; white = twice
the requirement), each also as one contact sheet ``sheet.png``, and a cycle-by-cycle check
of the shader against the golden model on the whole first frame
(:func:`phongfx.sim.harness.check`, ``verilator-fast``, with random ``out_ready`` stalls
and a reset in the middle of the stream; ``vectors`` is the frame's pixels, every span
pixel for units fed per span, hidden ones included).  ``DIR/testbench/`` holds the same
frame as a self-checking Verilog testbench for Icarus Verilog and Verilator
(:func:`phongfx.sim.testbench.write_testbench`), and the rest of a flow comes with it:
``DIR/constraints/`` the clock the core was compiled for as SDC, ECP5 LPF and an iCE40
nextpnr script (:mod:`phongfx.deliver.constraints`), ``DIR/<module>.core`` a FuseSoC core
of the RTL, the testbench and the constraints (:mod:`phongfx.deliver.fusesoc`).
``DIR/report.html``, written last (also when nothing is chosen, beside the manifest alone),
is one self-contained page of all of it: the requirement, the chosen design and why, every
candidate on a cost/error chart, the pixel rates, the certificate and witness, the error
maps and frames embedded, the RTL check, the ports and the input contract
(:mod:`phongfx.deliver.page`).
"""

import dataclasses
import json
import math
import os
import re
import time
from collections import Counter

import numpy as np

from phongfx.config import BlockConfig, DatapathConfig, ShaderConfig
from phongfx.core.files import atomic_write, staged_folder
from phongfx.core.methods import BASELINE
from phongfx.core.format import Format
from phongfx.core.words import levels, plural
from phongfx.deliver.constraints import clock_of
from phongfx.deliver.contract import contract_lines, error_paragraph, input_contract
from phongfx.deliver.fusesoc import write_flow
from phongfx.deliver.manifest import MANIFEST_VERSION
from phongfx.deliver.page import REPORT_NAME, write_report
from phongfx.render.figure import contact_sheet, error_figure, frame_figure

from . import run as runs
from .architecture import design_block, timing_of

__all__ = ["CHECK_STALLS", "CHECK_OPTIMIZE", "formats", "submodules", "scene_path", "manifest", "module_name",
           "prepare_outputs", "emit"]

#: The sub-configs of each Lyon datapath that its hardware uses (the others are idle defaults).
def formats(config, prefix=""):
    """``{"path.field": "Sn.m"}`` of every format field of ``config`` (used sub-configs only)."""
    out = {}
    if isinstance(config, ShaderConfig):  # its units (one, or one per light) and the blend
        for copy, unit in enumerate(config.units):
            out.update(formats(unit, f"{prefix}unit{copy if config.copies > 1 else ''}."))
        return {**out, **formats(config.blend, f"{prefix}blend.")}
    names = [f.name for f in dataclasses.fields(config)]
    if isinstance(config, DatapathConfig):
        names = list(config.used)
    for name in names:
        value = getattr(config, name)
        if isinstance(value, BlockConfig):
            out.update(formats(value, f"{prefix}{name}."))
        elif isinstance(value, str):
            try:
                out[f"{prefix}{name}"] = str(Format.parse(value))
            except ValueError:
                pass  # a name (rounding, variant), not a format
    return out


def submodules(verilog_text, module):
    """Instance names of the sub-blocks of ``module`` in emitted Verilog (``lirp0`` ...)."""
    names = re.findall(r"^module \\?(\S+?)\s*\(", verilog_text, re.M)
    return [n[len(module) + 1:] for n in names if n.startswith(module + ".")]


def _kinds(instances):
    """Instances per kind of block, whatever shader copy holds them (``unit0.lirp0``: lirp)."""
    return dict(sorted(Counter(re.sub(r"\d+$", "", n.rpartition(".")[2]) for n in instances).items()))


def _clean(value):
    """JSON-safe: infinities as the string "inf", numpy scalars as numbers."""
    if isinstance(value, dict):
        return {str(k): _clean(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_clean(v) for v in value]
    if isinstance(value, (np.integer,)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        return "inf" if math.isinf(value) else float(value)
    return value


def _ports(config):
    return [{"name": name, "format": str(fmt), "lanes": lanes, "direction": direction}
            for direction, ports in (("in", config.inputs), ("out", config.outputs))
            for name, (fmt, lanes) in ports.items()]


def _baseline(compiled, method):
    if method in compiled.results:
        r = compiled.results[method]
        return {k: r.get(k) for k in ("feasible", "params", "max", "mean", "frames_max", "domain_max", "cost",
                                      "default")}
    return {"why_not": compiled.rejected.get(method, "not among the methods considered")}


#: What the manifest keeps of each method's search result (an infeasible one adds its
#: best point's reasons: :func:`phongfx.explore.compile.infeasible.summary`).
_METHOD_KEYS = ("feasible", "params", "max", "mean", "frames_max", "domain_max", "domain_points", "cost", "default",
                "widest", "why", "k_scan", "overflow_proof", "witness", "why_not_chosen", "superseded", "certificate")


def _domain_evaluation(compiled):
    """How the width search measured the domain (the manifest's ``"evaluation"``)."""
    points = compiled.scene.points
    if points is None:
        return {}
    per_span = [name for name in compiled.results if not runs.per_pixel(name)]
    return {"domain_samples": points.count, "domain_seed": points.seed, "hard_points": points.hard_points,
            "domain_measured": "only where the frames meet the requirement (elsewhere the point fails "
                               "whatever the domain holds; domain_max null)",
            "fed_per_span": {name: "measured on the visible pixels of rasterized random poses of the domain "
                                   "(its stream is per span: a domain point cannot be fed alone)"
                             for name in per_span}}


def scene_path(spec, out_dir):
    """The scene file of ``spec`` relative to the output folder ``out_dir`` (what the manifest's
    ``"path"`` holds, so that the folder can be read from anywhere), None for a scene without a file."""
    if not spec.path:
        return None
    return os.path.relpath(os.path.abspath(spec.path), os.path.abspath(out_dir))


def manifest(compiled, module=None, instances=None, check=None, out_dir="."):
    """The manifest dict (module docstring of :mod:`phongfx.explore.compile.emit`) of the
    output folder ``out_dir``."""
    spec, best = compiled.spec, compiled.best
    certificate = compiled.certificate and compiled.certificate.as_dict()
    out = {"manifest_version": MANIFEST_VERSION, "scene": spec.name, "path": scene_path(spec, out_dir),
           "requirement": {**spec.requirement.as_dict(), "clock_mhz": compiled.speed.clock_mhz},
           "analysis": compiled.analysis.as_dict(), "cost_model": compiled.cost_model,
           "evaluation": {"frames": len(compiled.scene.geometries), "renders": len(compiled.scene.renders),
                          "shininess_variants": compiled.scene.shininess_variants,
                          "points_measured": compiled.scene.points_measured,
                          "points_resumed": compiled.scene.resumed,
                          "journal": compiled.scene.journal and compiled.scene.journal.path,
                          **_domain_evaluation(compiled)},
           "domain": compiled.domain and compiled.domain.as_dict(), "witness": compiled.witness,
           "certified": bool(certificate and certificate["certified"]),
           "search": "certified" if compiled.certified else "sampled",
           "certificate": certificate,
           "witness_rounds": compiled.rounds,
           "chosen": compiled.chosen, "tie": compiled.tie, "hint": compiled.hint, "refused": compiled.refused,
           "rejected": dict(compiled.rejected),
           "methods": {name: {k: r[k] for k in _METHOD_KEYS if k in r} for name, r in compiled.results.items()},
           "conventional_baseline": _baseline(compiled, BASELINE),
           "blinn_baseline": _baseline(compiled, "blinn")}
    if best is not None:
        block = design_block(best, compiled.analysis)
        config = block.config
        out.update({"block": block.name, "module": module, "widths": best["params"],
                    "architecture": best["cost"].get("architecture"), "timing": timing_of(best["cost"]),
                    "fit": best["cost"].get("fit"),
                    "blocks": instances, "block_counts": _kinds(instances or []),
                    "formats": formats(config), "config": dataclasses.asdict(config),
                    "latency": block.latency, "ports": _ports(config),
                    "error": {"max": best["max"], "mean": best["mean"],
                              "max_unrounded": best.get("max_unrounded"),
                              "frames_max": best.get("frames_max"), "domain_max": best.get("domain_max"),
                              "domain_points": best.get("domain_points"),
                              "witness": compiled.witness and compiled.witness["error_levels"],
                              "measured_at": "out_r, out_g, out_b (display levels)"},
                    "cost": best["cost"],
                    "minimality_proof": best["proof"], "default_widths": best["default"],
                    "overflow_proof": best.get("overflow_proof") or {"status": "not run",
                                                                     "how": "phongfx compile --prove"},
                    "rtl_check": check})
    return _clean(out)


def _picture(geometry, values, fill=0.0):
    """An (H, W) or (H, W, 3) picture of per-pixel ``values`` (P,) or (P, 3); ``fill``
    (black, or NaN: "no surface" in an error picture) elsewhere."""
    values = np.asarray(values, dtype=np.float64)
    image = np.full((geometry.height, geometry.width) + values.shape[1:], fill)
    image[geometry.row, geometry.col] = values
    return image


def module_name(scene, method):
    """The shipped module's name (``<module>_top``) of ``method`` on the scene named ``scene``."""
    name = re.sub(r"\W", "_", f"{scene}_{method}")
    return name if name[:1].isalpha() else f"m_{name}"


#: The RTL check's share of cycles with ``out_ready`` low (the harness's stream mode).
CHECK_STALLS = 0.2
#: The RTL check's simulator is built unoptimized: for one frame a build unoptimized is seconds
#: sooner than the run it would speed up.
CHECK_OPTIMIZE = False


def prepare_outputs(result, analysis, scene, check=True, vcd=None):
    """What :func:`emit` needs of ``result`` (a search result on the scene named ``scene``) that
    takes seconds and depends on the design alone, made ahead (the ``prepare`` of
    :func:`~phongfx.compiler.compile.compile_scene`, beside the witness search): with ``check``,
    the RTL check's simulator built into the cache as the check builds it, so that the check
    finds it built; and the shipped top's module (:func:`~phongfx.hdl.top.shipped_verilog`),
    returned as ``{"module": name, "shipped": text}``, which emit then writes (the compiled
    design's ``prepared``).  A failure is left for emit to meet and report."""
    from phongfx.hdl.top import Top, shipped_verilog
    from phongfx.sim.fast_backend import checked_build
    from phongfx.sim.stream import stream_mode

    block, made = design_block(result, analysis), {}
    module = module_name(scene, result["method"])
    # the module first, while the witness takes the other core: the build's last steps (Verilator,
    # then the C++ compiler on two jobs) then have the core the witness leaves
    try:
        made = {"module": module, "shipped": shipped_verilog(Top(block.component(), module), module)}
    except Exception:  # emit writes it again, and meets the error itself
        pass
    if check:
        try:
            checked_build(block, stream_mode(CHECK_STALLS, None), vcd=vcd, optimize=CHECK_OPTIMIZE)
        except Exception:  # no Verilator, or its build fails: the check says so itself
            pass
    return made


def emit(compiled, out_dir, *, check=True, progress=None, testbench=False, vcd=None):
    """Write the outputs of ``compiled`` as the folder ``out_dir``; returns the manifest dict.

    The folder is built beside its place and renamed into it when complete
    (:func:`~phongfx.core.files.staged_folder`): it holds this run's result whole, or, after a
    failure or an interrupt, the previous run's.  ``testbench/`` (frame 0's vectors and
    expected outputs) is always written, the FuseSoC core's ``sim`` target runs it;
    ``testbench`` is kept for callers that still pass it and changes nothing; ``vcd``: a
    waveform file of the RTL check."""
    with staged_folder(out_dir) as work:
        return _write(compiled, work, check, progress, vcd, out_dir)


def _flow(out_dir, module, data):
    """Write the constraints and the FuseSoC core of the shipped top; the manifest's ``"flow"``."""
    clock = clock_of(data)
    description = (f"{data['scene']}: the {data['chosen']} shader of phongfx, {clock.mhz:g} MHz, "
                   f"latency {data['top']['latency']} cycles, interval {data['top']['interval']}")
    return write_flow(out_dir, module, clock, data["top"]["ports"], description)


def _write(compiled, out_dir, check, progress, vcd, final):
    from phongfx.hdl.top import BLOCK_PATH, port_map, top_verilog
    from phongfx.scene.geometry import pixel_error

    best = compiled.best
    if best is None:
        data = manifest(compiled, out_dir=final)
        atomic_write(os.path.join(out_dir, "manifest.json"),
                     lambda p: open(p, "w").write(json.dumps(data, indent=2) + "\n"))
        write_report(os.path.join(out_dir, REPORT_NAME), data, out_dir)
        return data
    method, scene = best["method"], compiled.scene
    block = design_block(best, compiled.analysis)
    config = block.config
    module = module_name(compiled.spec.name, method)
    done, first, sheets = set(), None, ([], [], [])
    scale = 2 * compiled.spec.requirement.max_error_levels
    against = "true Phong" if compiled.spec.requirement.against == "phong" else f"{method}'s float form"
    # the pictures first: they need nothing prepared, which may still be made beside (the two-light
    # scene's took 2.3 s to draw, the witness search ended 4 s before its prepared outputs)
    for index, (g, _n) in enumerate(scene.renders):
        if g.frame in done:
            continue
        done.add(g.frame)
        codes, reference, raw, out = scene.render(method, config, best["params"], index)
        top_level = (1 << compiled.spec.output.bits) - 1
        name = f"frame_{g.frame:03d}.png"
        picture = _picture(g, codes / top_level)
        frame_figure(os.path.join(out_dir, "frames", name), picture,
                     f"{compiled.spec.name}: {method}, frame {g.frame} ({g.width}×{g.height})")
        error = _picture(g, pixel_error(codes, reference, compiled.spec.output.bits).max(axis=-1), np.nan)
        error_figure(os.path.join(out_dir, "error", name), error,
                     f"{compiled.spec.name}: {method}, frame {g.frame}: error against {against}, worst "
                     f"channel, max {levels(np.nanmax(error, initial=0))}", scale)
        for sheet, value in zip(sheets, (picture, error, f"frame {g.frame}")):
            sheet.append(value)
        if first is None:
            first = (g, raw, out)
    title = f"{compiled.spec.name}: {method}, {plural(len(done), 'frame')}"
    contact_sheet(os.path.join(out_dir, "frames", "sheet.png"), sheets[0], sheets[2], title=title)
    contact_sheet(os.path.join(out_dir, "error", "sheet.png"), sheets[1], sheets[2], white_levels=scale,
                  title=f"{title}: error against {against} (display levels)")
    prepared = compiled.take_prepared() or {}
    timing = timing_of(best["cost"])
    header = {k: timing.get(k) for k in ("clock_mhz", "clock_source", "pixel_rate_mpx", "met")}
    contract = input_contract(config, compiled.spec, method, n_scale=runs.hooks(method).n_scale)
    shipped = top_verilog(block.component(), module, timing={**header, "requirement_mpx": compiled.speed.mpx},
                          contract=contract_lines(contract)
                          + [error_paragraph(compiled.certificate and compiled.certificate.as_dict(),
                                             compiled.spec.requirement.as_dict())],
                          module=prepared.get("shipped") if prepared.get("module") == module else None)
    atomic_write(os.path.join(out_dir, "verilog", f"{module}_top.v"), lambda p: open(p, "w").write(shipped))
    instances = submodules(shipped, f"{module}_top.{BLOCK_PATH}")
    g, raw, out = first
    count = len(next(iter(raw.values())))
    result = None
    if check:
        if progress:
            progress(f"RTL check of frame {g.frame} ({count} pixels)")
        from phongfx.sim.harness import check as run_check
        start = time.perf_counter()
        r = run_check(block, raw, expected=out, backend="verilator-fast", stalls=CHECK_STALLS,
                      reset_at=count // 2, seed=1, optimize=CHECK_OPTIMIZE, **({"vcd": vcd} if vcd else {}))
        result = {"frame": g.frame, "backend": r.backend, "pixels": len(g), "vectors": r.vectors,
                  "copies": runs.copies(method, compiled.analysis), "cycles": r.cycles,
                  "mismatches": r.mismatch_count, "ok": r.ok, "simulate_seconds": r.seconds,
                  "stalls": CHECK_STALLS, "reset_at_cycle": count // 2, "vcd": vcd,
                  "seconds": time.perf_counter() - start}  # with the Verilator build
    from phongfx.sim.testbench import write_testbench
    if progress:
        progress(f"testbench of frame {g.frame}")
    write_testbench(block, raw, out, os.path.join(out_dir, "testbench"), module, top=shipped)
    data = manifest(compiled, module, instances, result, final)
    data["error_png_white_levels"] = scale
    data["pictures"] = {"frames": "frames/frame_NNN.png, frames/sheet.png (all frames)",
                        "error": "error/frame_NNN.png, error/sheet.png: worst channel's error in display "
                                 f"levels against {against}, white = {scale:g} levels or more, "
                                 "the colour bar beside"}
    data["top"] = {"module": f"{module}_top", "file": f"verilog/{module}_top.v", "latency": block.latency,
                   "interval": getattr(config, "interval", 1),
                   "ports": port_map(block.config)}
    data["contract"] = contract
    data["testbench"] = {"folder": "testbench", "frame": g.frame, "vectors": count,
                         "run": "sh testbench/run.sh (Icarus Verilog and Verilator)"}
    data["flow"] = _flow(out_dir, module, data)
    atomic_write(os.path.join(out_dir, "manifest.json"),
                 lambda p: open(p, "w").write(json.dumps(data, indent=2) + "\n"))
    # after the manifest is final: the page shows the RTL check's result and every field above
    write_report(os.path.join(out_dir, REPORT_NAME), data, out_dir)
    return data
