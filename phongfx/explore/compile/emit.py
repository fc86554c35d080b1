"""Write what :func:`phongfx.explore.compile.compiler.compile_scene` found, and verify it.

``DIR/manifest.json`` (:func:`manifest`), ``DIR/verilog/<module>.v`` (exactly the
chosen datapath's blocks), ``DIR/frames/frame_NNN.png`` (the fixed-point render of each
frame at its first shininess variant) and ``DIR/error/frame_NNN.png`` (its error in
levels against the reference; white = twice the requirement), and a cycle-by-cycle
check of the Verilog against the golden model on the whole first frame
(:func:`phongfx.sim.harness.check`, ``verilator-fast``; a unit with one copy per light
runs each light's stream in turn, so ``vectors`` is pixels × copies, more for units fed
every span pixel, hidden ones included).
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
from phongfx.core.files import atomic_write
from phongfx.core.format import Format
from phongfx.core.registry import get_block
from phongfx.render.mesh import write_png

from . import run as runs

__all__ = ["formats", "submodules", "manifest", "emit"]

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
        return {k: r.get(k) for k in ("feasible", "params", "max", "mean", "cost", "default")}
    return {"why_not": compiled.rejected.get(method, "not among the methods considered")}


def manifest(compiled, module=None, instances=None, check=None):
    """The manifest dict (module docstring of :mod:`phongfx.explore.compile.emit`)."""
    spec, best = compiled.spec, compiled.best
    out = {"scene": spec.name, "path": spec.path,
           "requirement": {"max_error_levels": spec.requirement.max_error_levels,
                           "against": spec.requirement.against},
           "analysis": compiled.analysis.as_dict(), "cost_model": compiled.cost_model,
           "evaluation": {"frames": len(compiled.scene.geometries), "renders": len(compiled.scene.renders),
                          "shininess_variants": compiled.scene.shininess_variants},
           "chosen": compiled.chosen,
           "rejected": dict(compiled.rejected),
           "methods": {name: {k: r.get(k) for k in ("feasible", "params", "max", "mean", "cost", "default")}
                       for name, r in compiled.results.items()},
           "conventional_baseline": _baseline(compiled, "conventional"),
           "blinn_baseline": _baseline(compiled, "blinn")}
    if best is not None:
        config = runs.build(best["method"], best["params"], compiled.analysis)
        block = get_block(runs.block_name(best["method"]), config=config)
        out.update({"block": block.name, "module": module, "widths": best["params"],
                    "blocks": instances, "block_counts": _kinds(instances or []),
                    "formats": formats(config), "config": dataclasses.asdict(config),
                    "latency": block.latency, "ports": _ports(config),
                    "error": {"max": best["max"], "mean": best["mean"],
                              "max_unrounded": best.get("max_unrounded"),
                              "measured_at": "out_r, out_g, out_b (display levels)"},
                    "cost": best["cost"],
                    "minimality_proof": best["proof"], "default_widths": best["default"],
                    "rtl_check": check})
    return _clean(out)


def _picture(geometry, values):
    """An (H, W) or (H, W, 3) picture of per-pixel ``values`` (P,) or (P, 3); black elsewhere."""
    values = np.asarray(values, dtype=np.float64)
    image = np.zeros((geometry.height, geometry.width) + values.shape[1:])
    image[geometry.row, geometry.col] = values
    return image


def _identifier(text):
    name = re.sub(r"\W", "_", text)
    return name if name[:1].isalpha() else f"m_{name}"


def emit(compiled, out_dir, *, check=True, progress=None):
    """Write the outputs of ``compiled`` under ``out_dir``; returns the manifest dict."""
    from phongfx.hdl.emit import verilog

    from .compiler import pixel_error

    best = compiled.best
    if best is None:
        data = manifest(compiled)
        atomic_write(os.path.join(out_dir, "manifest.json"),
                     lambda p: open(p, "w").write(json.dumps(data, indent=2) + "\n"))
        return data
    method, scene = best["method"], compiled.scene
    config = runs.build(method, best["params"], compiled.analysis)
    block = get_block(runs.block_name(method), config=config)
    module = _identifier(f"{compiled.spec.name}_{method}")
    text = verilog(block.component(), module)
    atomic_write(os.path.join(out_dir, "verilog", f"{module}.v"), lambda p: open(p, "w").write(text))
    done, result = set(), None
    scale = 2 * compiled.spec.requirement.max_error_levels
    for index, (g, _n) in enumerate(scene.renders):
        if g.frame in done:
            continue
        done.add(g.frame)
        codes, reference, raw, out = scene.render(method, config, best["params"], index)
        top_level = (1 << compiled.spec.output.bits) - 1
        write_png(os.path.join(out_dir, "frames", f"frame_{g.frame:03d}.png"), _picture(g, codes / top_level))
        error = pixel_error(codes, reference, compiled.spec.output.bits).max(axis=-1)
        write_png(os.path.join(out_dir, "error", f"frame_{g.frame:03d}.png"), _picture(g, error / scale))
        if check and result is None:
            if progress:
                progress(f"RTL check of frame {g.frame} ({len(next(iter(raw.values())))} pixels)")
            from phongfx.sim.harness import check as run_check
            start = time.perf_counter()
            r = run_check(block, raw, expected=out, backend="verilator-fast")
            result = {"frame": g.frame, "backend": r.backend, "pixels": len(g), "vectors": r.vectors,
                      "copies": runs.copies(method, compiled.analysis), "cycles": r.cycles,
                      "mismatches": r.mismatch_count, "ok": r.ok, "simulate_seconds": r.seconds,
                      "seconds": time.perf_counter() - start}  # with the Verilator build
    data = manifest(compiled, module, submodules(text, module), result)
    data["error_png_white_levels"] = scale
    atomic_write(os.path.join(out_dir, "manifest.json"),
                 lambda p: open(p, "w").write(json.dumps(data, indent=2) + "\n"))
    return data
