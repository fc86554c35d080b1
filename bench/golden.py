"""Golden model throughput: pixels per second of our numpy golden models.

Run ``python -m bench.golden`` (``--help`` for sizes).  In one run it measures the whole
Figure 7 datapath (Lyon 1993, Figures 6–7: LIRP, g2 normalizer, reflect, ``D·D``, ``2x``,
shape, and the diffuse term, two lights), the Figure 8 datapath and the Euler unit of
Hast et al. over spans, on 1, 4 and 16 Mpixel batches (10^6 pixels).  "ours" is
``Block.golden`` as every caller runs it: a stateless datapath a chunk of
:data:`~phongfx.golden.chunks.CHUNK` pixels at a time (:mod:`phongfx.golden.chunks`),
"whole" the same model on the whole batch at once.  Figure 7 is measured against

* :func:`fig7_float`: the same formula in float64 numpy with nothing quantized, run in
  the same chunks and whole (the faster counts): the speed the bit-exact model is held
  to, within 2×;
* :func:`fig7_apytypes`: the same Figure 7 computation written with ``apytypes``
  (C++ arbitrary-precision fixed point, multithreaded), bit-identical to ours;
* :func:`fig7_loop`: one pixel at a time in plain Python ints, in the style of Lyon's
  appendix code, bit-identical to ours, on a smaller batch and extrapolated.

Every comparison is a ratio of times measured side by side in the same run.  Peak
memory is measured apart, in a fresh process per model and size (a warm heap hides
reuse): the growth of its resident set over the inputs (``VmHWM``, reset through
``/proc/self/clear_refs``), so it counts apytypes' C++ allocations too.
Where ours spends its time is a cProfile of one run, by function.  The table goes to
stdout and the numbers to ``build/bench/golden.json`` (written atomically).
"""

import argparse
import cProfile
import json
import os
import platform
import pstats
import subprocess
import sys
import time

import numpy as np

from phongfx.core.files import atomic_write
from phongfx.core.registry import get_block
from phongfx.golden.chunks import CHUNK, chunked

from .golden_models import fig7_apytypes, fig7_float, fig7_loop

__all__ = ["SIZES", "inputs", "measure", "peak_memory", "run", "table", "main"]

#: Batch sizes in pixels.
SIZES = (1_000_000, 4_000_000, 16_000_000)
_BASE = 1 << 20  # generated once per block, then tiled: stimulus is not what is timed


def inputs(name, pixels, seed=1):
    """Raw input codes of block ``name`` for ``pixels`` pixels (its seeded vectors, tiled).

    The Euler unit's vectors are whole spans (``init`` starts each), so a tiled batch is
    a longer run of spans; cutting it at ``pixels`` only shortens the last one.
    """
    block = get_block(name)
    base = block.stimulus(count=min(pixels, _BASE if name != "euler" else _BASE // 4), seed=seed)
    count = len(next(iter(base.values())))
    reps = -(-pixels // count)
    return {key: np.tile(np.asarray(value), (reps,) + (1,) * (np.ndim(value) - 1))[:pixels]
            for key, value in base.items()}


def _status(field):
    with open("/proc/self/status") as file:
        for line in file:
            if line.startswith(field + ":"):
                return int(line.split()[1]) * 1024
    return 0


def measure(*functions, repeats=1):
    """Best seconds of each function over ``repeats`` rounds, the functions taking turns
    within a round so that a noisy neighbour slows all of them alike."""
    best = [float("inf")] * len(functions)
    for _ in range(repeats):
        for index, function in enumerate(functions):
            start = time.perf_counter()
            function()
            best[index] = min(best[index], time.perf_counter() - start)
    return best


def _float(config, raw):
    """:func:`fig7_float` in the chunks ours runs in."""
    return chunked(lambda part: fig7_float(config, part), raw)


_MODELS = {"ours": lambda block, raw: block.golden(raw),
           "whole": lambda block, raw: block.golden(raw, whole=True),
           "float64": lambda block, raw: _float(block.config, raw),
           "float64_whole": lambda block, raw: fig7_float(block.config, raw),
           "apytypes": lambda block, raw: fig7_apytypes(block.config, raw),
           "loop": lambda block, raw: fig7_loop(block.config, raw)}


def _probe(name, model, pixels):
    """In this (fresh) process: resident-set growth in bytes of one run of ``model``."""
    block, raw = get_block(name), inputs(name, pixels)
    try:  # hand the stimulus generator's freed heap back, or the run reuses it unseen
        import ctypes
        ctypes.CDLL("libc.so.6").malloc_trim(0)
    except (OSError, AttributeError):
        pass
    base = _status("VmRSS")
    with open("/proc/self/clear_refs", "w") as file:
        file.write("5")  # VmHWM := the current resident set
    _MODELS[model](block, raw)
    return _status("VmHWM") - base


def peak_memory(name, model, pixels):
    """Peak memory of ``model`` on ``pixels`` pixels of ``name``, measured in a fresh process."""
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    proc = subprocess.run([sys.executable, "-m", "bench.golden", "--probe", name, model, str(pixels)],
                          capture_output=True, text=True, cwd=root, check=True)
    return int(proc.stdout.split()[-1])


def _profile(block, raw, top=8):
    profile = cProfile.Profile()
    profile.runcall(block.golden, raw)
    stats = pstats.Stats(profile)
    total = stats.total_tt
    rows = sorted(stats.stats.items(), key=lambda item: -item[1][2])[:top]
    return [{"function": f"{func[0].split('/')[-1]}:{func[1]} {func[2]}", "share": tt / total}
            for func, (_, _, tt, _, _) in rows]


def _same(ours, theirs, what):
    for key, value in ours.items():
        if not np.array_equal(value, theirs[key]):
            bad = int(np.count_nonzero(value != theirs[key]))
            raise AssertionError(f"{what} differs from the golden model on {key}: {bad} pixel(s)")


def run(sizes=SIZES, loop_pixels=20_000, check_pixels=200_000, out_dir="build/bench", quiet=False):
    """Measure everything; returns the result dict (also written to ``out_dir/golden.json``)."""
    import apytypes

    say = (lambda *a: None) if quiet else (lambda *a: print(*a, flush=True))
    fig7 = get_block("fig7")
    # correctness first: both rivals bit-identical to our golden model (directed cases first)
    sample = inputs("fig7", check_pixels)
    ours = fig7.golden(sample)
    _same(ours, fig7_apytypes(fig7.config, sample), "apytypes Figure 7")
    _same(ours, fig7.golden(sample, whole=True), "whole-batch golden Figure 7")
    loop_sample = {key: value[:loop_pixels] for key, value in sample.items()}
    looped = fig7_loop(fig7.config, loop_sample)
    (loop_seconds,) = measure(lambda: fig7_loop(fig7.config, loop_sample), repeats=2)
    loop_peak = peak_memory("fig7", "loop", loop_pixels)
    _same({k: v[:loop_pixels] for k, v in ours.items()}, looped, "per-pixel loop Figure 7")
    say(f"bit-identical on {check_pixels} pixels (apytypes, whole batch) and {loop_pixels} (loop)")
    rows = []
    for name in ("fig7", "fig8", "euler"):
        block = get_block(name)
        for pixels in sizes:
            raw = inputs(name, pixels)
            repeats = 3 if pixels <= 4_000_000 else 1
            # the Euler unit carries state from pixel to pixel: never cut, so no "whole" apart
            names = ["ours"] + (["whole"] if name != "euler" else [])
            if name == "fig7":  # the loop takes its turn too (on its small batch), under the same load
                names += ["float64", "float64_whole", "apytypes", "loop"]
            runs = [(lambda m, r: lambda: _MODELS[m](block, r))(m, loop_sample if m == "loop" else raw)
                    for m in names]
            times = dict(zip(names, measure(*runs, repeats=repeats)))
            loop_seconds = min(loop_seconds, times.pop("loop", loop_seconds))
            row = {"datapath": name, "pixels": pixels}
            for model, seconds in times.items():
                row.update({f"{model}_seconds": seconds, f"{model}_pixels_per_second": pixels / seconds})
                if model != "float64_whole":
                    row[f"{model}_peak_bytes"] = peak_memory(name, model, pixels)
            if name == "fig7":
                row["loop_pixels_per_second"] = loop_pixels / loop_seconds  # best so far
                row["ratio_float64"] = times["ours"] / min(times["float64"], times["float64_whole"])
                row["ratio_apytypes"] = times["apytypes"] / times["ours"]
                row["ratio_loop"] = row["ours_pixels_per_second"] / row["loop_pixels_per_second"]
            rows.append(row)
            say(_line(row))
            del raw
    profile = _profile(fig7, inputs("fig7", min(sizes)))
    result = {"rows": rows, "loop": {"pixels": loop_pixels, "seconds": loop_seconds, "peak_bytes": loop_peak},
              "check_pixels": check_pixels, "chunk": CHUNK, "profile_fig7": profile,
              "apytypes": {"version": apytypes.__version__, "threads": apytypes.n_threads()},
              "numpy": np.__version__, "python": platform.python_version(), "machine": platform.machine(),
              "targets": {"ratio_float64": 2.0, "ratio_apytypes": 10.0, "ratio_loop": 100.0}}
    path = f"{out_dir}/golden.json"
    atomic_write(path, lambda tmp: open(tmp, "w").write(json.dumps(result, indent=2)))
    result["path"] = path
    return result


def _mpx(row, model):
    return f"{row[model + '_pixels_per_second'] / 1e6:.2f}" if model + "_seconds" in row else "-"


def _mib(row, model):
    return f" ({row[model + '_peak_bytes'] / 2**20:.0f})" if model + "_peak_bytes" in row else ""


def _line(row):
    return (f"{row['datapath']:6s} {row['pixels'] / 1e6:5.1f} Mpx  Mpx/s: ours {_mpx(row, 'ours')}, "
            f"whole {_mpx(row, 'whole')}, float64 {_mpx(row, 'float64')} (whole {_mpx(row, 'float64_whole')}), "
            f"apytypes {_mpx(row, 'apytypes')}")


def table(result):
    """Markdown table of :func:`run`'s result."""
    models = ("ours", "whole", "float64", "float64_whole", "apytypes")
    lines = ["| datapath | Mpixels | ours Mpx/s (MiB) | ours whole batch | float64 chunked | float64 whole | "
             "apytypes | ours time ÷ float64 | ours ÷ apytypes | ours ÷ loop |", "|---" * 10 + "|"]
    for row in result["rows"]:
        ratios = ["-"] * 3
        if "apytypes_seconds" in row:
            ratios = [f"{row['ratio_float64']:.2f}", f"{row['ratio_apytypes']:.1f}", f"{row['ratio_loop']:.0f}"]
        cells = [_mpx(row, m) + _mib(row, m) for m in models]
        lines.append(f"| {row['datapath']} | {row['pixels'] / 1e6:g} | " + " | ".join(cells + ratios) + " |")
    loop, targets = result["loop"], result["targets"]
    lines += ["", f"Per-pixel loop: {loop['pixels'] / loop['seconds']:.0f} px/s on {loop['pixels']} pixels "
              f"({loop['peak_bytes'] / 2**20:.0f} MiB).  apytypes {result['apytypes']['version']} on "
              f"{result['apytypes']['threads']} threads; ours and float64 single-threaded numpy, chunks of "
              f"{result['chunk']} pixels.  Targets: ours within {targets['ratio_float64']:g}× the time of float64 "
              f"(the faster of its two runs), ≥ {targets['ratio_apytypes']:g}× apytypes, "
              f"≥ {targets['ratio_loop']:g}× the loop.",
              f"Where ours spends its time (Figure 7, {min(r['pixels'] for r in result['rows']) / 1e6:g} Mpx, "
              f"one call):"]
    lines += [f"- {p['share']:5.1%} {p['function']}" for p in result["profile_fig7"]]
    return "\n".join(lines)


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m bench.golden", description=__doc__.split("\n\n")[0])
    parser.add_argument("--sizes", type=float, nargs="+", default=[s / 1e6 for s in SIZES],
                        help="batch sizes in Mpixels (default 1 4 16)")
    parser.add_argument("--loop-pixels", type=int, default=20_000, help="pixels for the per-pixel loop")
    parser.add_argument("--out", default="build/bench", help="folder for golden.json")
    parser.add_argument("--probe", nargs=3, metavar=("BLOCK", "MODEL", "PIXELS"), help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.probe:
        print(_probe(args.probe[0], args.probe[1], int(args.probe[2])))
        return 0
    result = run(sizes=[int(s * 1e6) for s in args.sizes], loop_pixels=args.loop_pixels, out_dir=args.out)
    print(table(result))
    print(f"wrote {result['path']}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
