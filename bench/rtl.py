"""RTL verification throughput: the Figure 7 datapath on every back end.

Run ``python -m bench.rtl`` (``--help`` for sizes).  It measures, in one run:

* a full 1920×1080 frame (:data:`FRAME` pixels) checked cycle by cycle, back to back,
  on the fast path (``verilator-fast``, :mod:`phongfx.sim.fast_backend`), split into
  stimulus generation, golden model, build (cached), packing, stream write, and the
  compiled simulate-and-compare run; the target is ≤ 10 s for the check itself
  (pack + write + simulate), build reported separately;
* the same smaller stimulus on Amaranth's simulator, cocotb + Verilator and the fast
  path, in cycles per second, with ratios to Amaranth's;
* the cold build of each Verilator flavour (in a fresh cache directory).

The table goes to stdout and the numbers to ``build/bench/rtl.json`` (written
atomically).  Ratios, not absolute times, are what compare across machines.
"""

import argparse
import json
import platform
import tempfile
import time

from phongfx.core.files import atomic_write
from phongfx.core.registry import get_block
from phongfx.sim import fast_backend, fast_build, verilator_backend
from phongfx.sim.harness import check

__all__ = ["FRAME", "TARGET_SECONDS", "measure", "table", "main"]

FRAME = 1920 * 1080
TARGET_SECONDS = 10.0


def _stimulus(block, count, seed):
    # stimulus() adds its directed cases to the random ones: cut to exactly ``count``
    raw = block.stimulus(count=count, seed=seed)
    return {name: value[:count] for name, value in raw.items()}


def _cold_builds(block):
    """Seconds of a build from nothing (no design, no run-time objects cached)."""
    out = {}
    for name, build in (("verilator-fast", fast_build.build),
                        ("verilator", verilator_backend.build)):
        with tempfile.TemporaryDirectory() as directory:
            start = time.perf_counter()
            build(block.component(), build_dir=directory)
            out[name] = time.perf_counter() - start
    return out


def measure(pixels=FRAME, small=20000, seed=0, cold=True):
    """Run the benchmark; returns a JSON-ready dict."""
    if pixels < 1 or small < 1:
        raise ValueError(f"pixels and small must be positive integers, not {pixels}, {small}")
    block = get_block("fig7")
    start = time.perf_counter()
    raw = _stimulus(block, pixels, seed)
    generated = time.perf_counter() - start
    result, times = fast_backend.check_timed(block, raw, bubbles=0.0, seed=seed)
    times["vectors"] = generated
    check_seconds = times["pack"] + times["write"] + times["simulate"] + times["report"]
    frame = {"pixels": pixels, "cycles": result.cycles, "mismatches": result.mismatch_count,
             "seconds": {name: round(value, 4) for name, value in times.items()},
             "check_seconds": round(check_seconds, 4),
             "meets_target": check_seconds <= TARGET_SECONDS,
             "cycles_per_second_simulate": result.cycles / times["simulate"]}

    side = _stimulus(block, small, seed + 1)
    expected = block.golden(side)
    rows = []
    for backend in ("amaranth", "verilator", "verilator-fast"):
        # warm the build cache first: build time is reported on its own below
        check(block, {name: value[:2] for name, value in side.items()}, backend=backend,
              bubbles=0.0)
        run = check(block, side, expected=expected, backend=backend, bubbles=0.0, seed=seed)
        rows.append({"backend": backend, "vectors": run.vectors, "cycles": run.cycles,
                     "seconds": run.seconds, "cycles_per_second": run.cycles_per_second,
                     "mismatches": run.mismatch_count})
    base = rows[0]["cycles_per_second"]
    for row in rows:
        row["ratio_to_amaranth"] = row["cycles_per_second"] / base
    return {"block": "fig7", "machine": platform.processor() or platform.machine(),
            "target_seconds": TARGET_SECONDS, "frame": frame, "backends": rows,
            "cold_build_seconds": _cold_builds(block) if cold else None}


def table(data):
    """The benchmark as plain-text tables."""
    frame = data["frame"]
    s = frame["seconds"]
    lines = [f"Figure 7 datapath, {frame['pixels']} pixels ({frame['cycles']} cycles), "
             f"verilator-fast, {frame['mismatches']} mismatching cycle(s)",
             f"  stimulus generation {s['vectors']:7.3f} s   (block.vectors, not part of the check)",
             f"  golden model        {s['golden']:7.3f} s",
             f"  build (cached)      {s['build']:7.3f} s",
             f"  pack (numpy)        {s['pack']:7.3f} s",
             f"  write stream        {s['write']:7.3f} s",
             f"  simulate + compare  {s['simulate']:7.3f} s   "
             f"({frame['cycles_per_second_simulate']:,.0f} cycles/s)",
             f"  check total         {frame['check_seconds']:7.3f} s   "
             f"(target <= {data['target_seconds']:g} s: "
             f"{'met' if frame['meets_target'] else 'NOT met'})",
             "",
             f"{'back end':<16}{'cycles':>10}{'seconds':>10}{'cycles/s':>14}{'ratio':>10}"]
    for row in data["backends"]:
        lines.append(f"{row['backend']:<16}{row['cycles']:>10}{row['seconds']:>10.3f}"
                     f"{row['cycles_per_second']:>14,.0f}{row['ratio_to_amaranth']:>9.1f}x")
    if data["cold_build_seconds"]:
        lines.append("")
        lines.extend(f"cold build, {name:<16}{seconds:7.2f} s"
                     for name, seconds in data["cold_build_seconds"].items())
    return "\n".join(lines)


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m bench.rtl", description=__doc__.split("\n")[0])
    parser.add_argument("--pixels", type=int, default=FRAME, help="frame size for the fast path")
    parser.add_argument("--small", type=int, default=20000,
                        help="vectors for the side-by-side run of all back ends")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--no-cold-build", action="store_true", help="skip the cold builds")
    parser.add_argument("--out", default="build/bench/rtl.json")
    args = parser.parse_args(argv)
    for name in ("pixels", "small"):
        if getattr(args, name) < 1:
            parser.error(f"--{name} must be a positive integer, not {getattr(args, name)}")
    data = measure(args.pixels, args.small, args.seed, cold=not args.no_cold_build)
    print(table(data))

    def write(path):
        with open(path, "w") as file:
            json.dump(data, file, indent=2)
            file.write("\n")

    atomic_write(args.out, write)
    return 0 if not data["frame"]["mismatches"] else 1


if __name__ == "__main__":
    raise SystemExit(main())
