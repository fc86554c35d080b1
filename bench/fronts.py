"""Area against pixel rate: every architecture of each example scene's chosen design, synthesized.

Run ``python -m bench.fronts`` (``--help``).  For each scene of :data:`DESIGNS` (the design
``phongfx compile`` chooses for it, or ``--manifest`` of a compiled folder) and each
architecture the compiler may give it (:func:`phongfx.explore.compile.run.architectures`:
pipeline depth × cycles per pixel; and, for a shader of one-light copies, the inputs that do
not depend on the light taken once or per copy), the whole shader is synthesized on ECP5
(LUT-eq = LUT4 + 958·DSP, Fmax after nextpnr) and on OSU 0.18 µm standard cells (µm², Fmax
by OpenSTA), and priced by the proxies the compiler uses without ``--synth`` (area and clock).
A design's pixel rate is its Fmax over its cycles per pixel.

Written to ``build/bench/fronts.json`` and ``fronts.md``: every row, the area–pixel-rate
front per scene and target (the rows no cheaper row beats on rate), the cheapest design
meeting each rate of :data:`RATES` (Mpixel/s), and the saving of shared inputs against a
copy of them per light.  Synthesis is cached (the per-user cache), so a rerun only reads.
"""

import argparse
import json
import os
import sys
import time

from phongfx.core.files import atomic_write
from phongfx.core.registry import get_block
from phongfx.explore.compile import run as runs
from phongfx.explore.compile.analysis import analyse
from phongfx.scene.file import load_scene
from phongfx.scene.geometry import frames

__all__ = ["DESIGNS", "RATES", "TARGETS", "variants", "measure", "fronts", "choices", "markdown", "main"]

ROOT = os.path.join(os.path.dirname(__file__), "..")
#: The design ``phongfx compile`` chooses for each scene (certified, on its domain; main 0db86fe).
DESIGNS = {
    "torus": ("conventional", {"vec_frac": 11, "rsqrt_addr": 8, "table_addr": 5, "coef": 0}),
    "local-mesh": ("conventional", {"vec_frac": 14, "rsqrt_addr": 9, "table_addr": 5, "coef": 1}),
    "lyon-balls": ("halfway", {"vec_frac": 15, "x2_frac": 5, "shape_t_frac": 13, "coef": 2, "order": 2}),
    "two-lights": ("conventional", {"vec_frac": 10, "rsqrt_addr": 7, "table_addr": 6, "coef": 5}),
}
#: The pixel rates (Mpixel/s) the compiler's choice is shown at.
RATES = (30, 60, 150, 250)
#: (target, device, cost key, unit) of each synthesized target.
TARGETS = (("ecp5", "45k", "lut_eq", "LUT-eq"), ("asic", "osu018", "area_um2", "µm²"))


def _log(text):
    print(f"fronts: {text}", file=sys.stderr, flush=True)


def variants(method, analysis):
    """The architectures measured for ``method`` on a scene: every one the compiler may choose,
    and, when the shader holds several copies of a one-light unit, the same without shared
    inputs (what the shader was before they were shared)."""
    out = [dict(a) for a in runs.architectures(method, analysis)]
    if runs.copies(method, analysis) > 1:
        out += [{**a, "share": False} for a in out if a.get("interval", 1) == 1 and a.get("share", True)]
    return out


def _synthesize(config, target, device, log):
    from phongfx.explore.synth.fpga import synth

    result = synth("shader", config=config, target=target, device=device, freq=150,
                   progress=lambda stage: log(stage))
    if target == "asic":
        return {"cost": result["area_um2"], "fmax_mhz": result["fmax_mhz"], "ff": result["ff"],
                "cells": result["cell_count"]}
    return {"cost": result["lut4"] + 958 * result["dsp"], "fmax_mhz": result["fmax_mhz"], "ff": result["ff"],
            "lut4": result["lut4"], "dsp": result["dsp"], "bram_bits": result["bram_bits"]}


def _proxy(block, target, device):
    from phongfx.explore.synth.clock import proxy_clock
    from phongfx.explore.synth.proxy import proxy_estimate

    area = proxy_estimate(block, target, device)
    clock = proxy_clock(block, target, device)
    return {"cost": area["area_um2"] if target == "asic" else area["lut_eq"], "fmax_mhz": clock["fmax_mhz"]}


def measure(scenes=None, designs=None, targets=TARGETS, depths=None, log=_log):
    """One row per (scene, architecture, target): synthesized and proxy cost and Fmax, the
    cycles per pixel and the pixel rates (module docstring); ``depths``: only those pipeline
    depths (default every one)."""
    rows = []
    for scene in scenes or list(designs or DESIGNS):
        method, params = (designs or DESIGNS)[scene]
        spec = load_scene(os.path.join(ROOT, "scenes", f"{scene}.toml"))
        analysis = analyse(spec, frames(spec))
        for arch in variants(method, analysis):
            if depths is not None and arch.get("pipeline", 0) not in depths:
                continue
            config = runs.build(method, params, analysis, arch)
            block = get_block("shader", config=config)
            for target, device, _, unit in targets:
                label = f"{scene} {method} {arch} on {target}"
                start = time.perf_counter()
                synthesized = _synthesize(config, target, device, lambda stage: log(f"{label}: {stage}"))
                proxy = _proxy(block, target, device)
                interval = config.interval
                rows.append({"scene": scene, "method": method, "params": params, "architecture": arch,
                             "target": target, "device": device, "unit": unit, "interval": interval,
                             "latency": block.latency, **synthesized,
                             "pixel_rate_mpx": synthesized["fmax_mhz"] / interval,
                             "proxy_cost": proxy["cost"], "proxy_fmax_mhz": proxy["fmax_mhz"],
                             "proxy_pixel_rate_mpx": proxy["fmax_mhz"] / interval,
                             "seconds": time.perf_counter() - start})
                log(f"{label}: {synthesized['cost']:,.0f} {unit}, {synthesized['fmax_mhz']:.1f} MHz, "
                    f"{rows[-1]['pixel_rate_mpx']:.1f} Mpixel/s")
    return rows


def _groups(rows):
    groups = {}
    for row in rows:
        groups.setdefault((row["scene"], row["target"]), []).append(row)
    return groups


def fronts(rows):
    """``{(scene, target): [rows]}``: the shared-input rows no cheaper row beats on pixel rate,
    cheapest first."""
    out = {}
    for key, group in _groups(rows).items():
        front, best = [], 0.0
        for row in sorted((r for r in group if r["architecture"].get("share", True)), key=lambda r: r["cost"]):
            if row["pixel_rate_mpx"] > best:
                front.append(row)
                best = row["pixel_rate_mpx"]
        out[key] = front
    return out


def choices(rows, rates=RATES):
    """``{(scene, target): {rate: row or None}}``: the cheapest synthesized design meeting each rate."""
    out = {}
    for key, group in _groups(rows).items():
        shared = [r for r in group if r["architecture"].get("share", True)]
        out[key] = {rate: min((r for r in shared if r["pixel_rate_mpx"] >= rate), key=lambda r: r["cost"],
                              default=None) for rate in rates}
    return out


def _arch(row):
    a = row["architecture"]
    return f"depth {a.get('pipeline', 0)}, {row['interval']} clk/pixel" + ("" if a.get("share", True) else ", unshared")


def markdown(rows, rates=RATES):
    """The fronts, the choices at each rate and the saving of shared inputs, as Markdown."""
    lines = ["| scene | target | architecture | cost | Fmax MHz | Mpixel/s | proxy cost | proxy MHz | front |",
             "|---|---|---|---:|---:|---:|---:|---:|---|"]
    front = {id(r) for group in fronts(rows).values() for r in group}
    for r in rows:
        lines.append(f"| {r['scene']} ({r['method']}) | {r['target']} | {_arch(r)} | {r['cost']:,.0f} {r['unit']} | "
                     f"{r['fmax_mhz']:.1f} | {r['pixel_rate_mpx']:.1f} | {r['proxy_cost']:,.0f} | "
                     f"{r['proxy_fmax_mhz']:.1f} | {'yes' if id(r) in front else ''} |")
    lines += ["", "| scene | target | " + " | ".join(f"{rate} Mpixel/s" for rate in rates) + " |",
              "|---|---|" + "---|" * len(rates)]
    for (scene, target), chosen in choices(rows, rates).items():
        cells = [f"{_arch(r)}, {r['cost']:,.0f}" if r else "none reaches it" for r in chosen.values()]
        lines.append(f"| {scene} | {target} | " + " | ".join(cells) + " |")
    saving = []
    for (scene, target), group in _groups(rows).items():
        for r in group:
            if not r["architecture"].get("share", True):
                twin = next((s for s in group if s["architecture"] == {**r["architecture"], "share": True}), None)
                if twin:
                    saving.append(f"| {scene} | {target} | {_arch(twin)} | {r['cost']:,.0f} | {twin['cost']:,.0f} | "
                                  f"{1 - twin['cost'] / r['cost']:.1%} |")
    if saving:
        lines += ["", "| scene | target | architecture | a copy per light | shared | saving |",
                  "|---|---|---|---:|---:|---:|", *saving]
    return "\n".join(lines)


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m bench.fronts", description=__doc__.split("\n\n")[0])
    parser.add_argument("--scene", nargs="*", choices=list(DESIGNS), help="scenes (default all)")
    parser.add_argument("--target", nargs="*", choices=[t[0] for t in TARGETS], help="targets (default both)")
    parser.add_argument("--depth", nargs="*", type=int, help="pipeline depths (default every one)")
    parser.add_argument("--out", default="build/bench", help="folder for fronts.json and fronts.md")
    args = parser.parse_args(argv)
    targets = [t for t in TARGETS if not args.target or t[0] in args.target]
    rows = measure(args.scene, targets=targets, depths=args.depth)
    text = markdown(rows)
    atomic_write(os.path.join(args.out, "fronts.json"), lambda p: open(p, "w").write(json.dumps(rows, indent=2)))
    atomic_write(os.path.join(args.out, "fronts.md"), lambda p: open(p, "w").write(text + "\n"))
    print(text)
    print(f"wrote {args.out}/fronts.json, {args.out}/fronts.md")
    return 0


if __name__ == "__main__":
    sys.exit(main())
