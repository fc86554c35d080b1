"""Domain points per second: what the compiler's search on a scene's input domain costs.

Run ``python -m bench.domain`` (``--help`` for sizes).  For each example scene
(``scenes/torus.toml``, ``scenes/local-mesh.toml``) at the design the compiler chooses for
it (:data:`DESIGNS`, or ``--manifest`` of a compiled folder), it times, on the same points,
each stage of one domain measurement (:mod:`phongfx.explore.compile.points`):

* **sample**: drawing the points (:meth:`phongfx.scene.domain.Domain.chunks`);
* **encode**: the shader's raw input codes (:func:`phongfx.explore.compile.run.frame_inputs`);
* **golden**: the bit-exact golden model of the whole shader (unit and blend);
* **reference**: true Phong's specular terms (:func:`phongfx.explore.compile.measure.phong_terms`);
* **error**: the reference shaded and the display-level error (``shade``, ``pixel_error``);

and reports points per second of each and of all of them together.  The width search pays
encode, golden and error per measured design (sample and reference once per compile); the
witness search pays all five.  The numbers go to ``build/bench/domain.json`` (atomically).
"""

import argparse
import json
import os
import platform
import time

import numpy as np

from phongfx.compiler.compile import scene_domain
from phongfx.core.files import atomic_write
from phongfx.deliver.manifest import read_manifest
from phongfx.explore.compile import run as runs
from phongfx.explore.compile.measure import SceneEval, cosines, phong_terms, point_errors
from phongfx.golden.blend import blend
from phongfx.golden.fixed import Fixed
from phongfx.golden.shader import shader_terms
from phongfx.scene.file import load_scene
from phongfx.scene.geometry import shade, terminator_lit

__all__ = ["DESIGNS", "STAGES", "measure", "run", "table", "main"]

ROOT = os.path.join(os.path.dirname(__file__), "..")
#: The design ``phongfx compile`` chooses for each example scene (searched on its domain).
DESIGNS = {
    "torus": ("fig7", {"vec_frac": 11, "x2_frac": 7, "shape_t_frac": 12, "coef": 0, "order": 2, "k": 4}),
    "local-mesh": ("conventional", {"vec_frac": 13, "rsqrt_addr": 8, "table_addr": 5, "coef": 1}),
}
STAGES = ("sample", "encode", "golden", "reference", "error")


def measure(scene_name, method, params, points, seed=1):
    """``{stage: seconds}`` and the totals of ``points`` domain points of ``scenes/<scene_name>.toml``
    at ``method``/``params`` (module docstring)."""
    spec = load_scene(os.path.join(ROOT, "scenes", f"{scene_name}.toml"))
    scene = SceneEval(spec)
    domain = scene_domain(spec, scene.geometries)
    config = runs.build(method, params, scene.analysis)
    seconds = dict.fromkeys(STAGES, 0.0)
    worst, count = 0, 0
    chunks = domain.chunks(points, seed)
    while True:
        start = time.perf_counter()
        g = next(chunks, None)
        seconds["sample"] += time.perf_counter() - start
        if g is None:
            break
        n = np.round(g.n).astype(np.int64)
        start = time.perf_counter()
        raw = runs.frame_inputs(method, config, g, n)
        seconds["encode"] += time.perf_counter() - start
        start = time.perf_counter()
        terms = shader_terms(config, **{name: Fixed(np.asarray(raw[name], dtype=np.int64), fmt)
                                        for name, (fmt, _) in config.inputs.items()})
        out = {name: value.raw for name, value in blend(config.blend, **terms).items()}
        seconds["golden"] += time.perf_counter() - start
        start = time.perf_counter()
        spec_terms = phong_terms(g, n)
        seconds["reference"] += time.perf_counter() - start
        start = time.perf_counter()
        codes = runs.frame_codes(method, out, g)
        lit = (np.stack([terms[f"diff{i}"].raw > 0 for i in range(config.blend.lights)])
               if config.blend.diff else None)
        cosine = cosines(g)
        reference = shade(g, np.maximum(cosine, 0.0), spec_terms, lit=terminator_lit(cosine, lit, g.bits))
        levels, _ = point_errors(codes, reference, g.bits)
        seconds["error"] += time.perf_counter() - start
        worst, count = max(worst, int(levels.max(initial=0))), count + len(g)
    total = sum(seconds.values())
    search = seconds["encode"] + seconds["golden"] + seconds["error"]
    return {"scene": scene_name, "method": method, "params": params, "points": count, "seconds": seconds,
            "points_per_second": {stage: count / s for stage, s in seconds.items() if s > 0},
            "all_points_per_second": count / total, "search_points_per_second": count / search,
            "max_error_levels": worst}


def run(points=1_000_000, designs=None, out_dir="build/bench"):
    """Measure every design; returns the result dict (also written to ``out_dir/domain.json``)."""
    rows = [measure(name, method, params, points) for name, (method, params) in (designs or DESIGNS).items()]
    result = {"rows": rows, "numpy": np.__version__, "python": platform.python_version(),
              "machine": platform.machine()}
    path = f"{out_dir}/domain.json"
    atomic_write(path, lambda tmp: open(tmp, "w").write(json.dumps(result, indent=2)))
    result["path"] = path
    return result


def table(result):
    """Markdown table of :func:`run`'s result (thousands of points per second)."""
    lines = ["| scene | design | points | " + " | ".join(f"{s} kpt/s" for s in STAGES)
             + " | search kpt/s | all kpt/s |", "|---" * (5 + len(STAGES)) + "|"]
    for row in result["rows"]:
        rates = [f"{row['points_per_second'].get(s, 0) / 1e3:,.0f}" for s in STAGES]
        lines.append(f"| {row['scene']} | {row['method']} | {row['points']:,} | " + " | ".join(rates)
                     + f" | {row['search_points_per_second'] / 1e3:,.0f} | {row['all_points_per_second'] / 1e3:,.0f} |")
    lines.append("search: what each measured design costs (encode + golden + error); all: with sampling and the "
                 "reference (the witness search).")
    return "\n".join(lines)


def _designs(manifests):
    """:data:`DESIGNS` with the chosen design of each compiled folder's ``manifest.json``."""
    out = dict(DESIGNS)
    for folder in manifests or ():
        data = read_manifest(folder)  # its version checked: a manifest of another layout is refused
        out[os.path.splitext(os.path.basename(data["path"]))[0]] = (data["chosen"], data["widths"])
    return out


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m bench.domain", description=__doc__.split("\n\n")[0])
    parser.add_argument("--points", type=int, default=1_000_000, help="domain points per scene (default 10^6)")
    parser.add_argument("--manifest", nargs="*", metavar="DIR",
                        help="compiled folders whose chosen design replaces the built-in one for its scene")
    parser.add_argument("--out", default="build/bench", help="folder for domain.json")
    args = parser.parse_args(argv)
    if args.points < 1:
        parser.error(f"--points must be a positive integer, not {args.points}")
    result = run(args.points, _designs(args.manifest), args.out)
    print(table(result))
    print(f"wrote {result['path']}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
