"""Scaling: how checking time grows with frame size and datapath size.

Run ``python -m bench.scaling``.  For each datapath (:data:`BLOCKS`: the Figure 7 and
Figure 8 datapaths and the corrected Euler unit) and each frame size (:data:`SIZES`,
up to 1920×1080), seeded stimulus goes through the golden model and then through the
``verilator-fast`` back end cycle by cycle, back to back.  The golden model's seconds
and the check's seconds (pack + stream write + compiled simulate-and-compare; the
build is cached first and reported apart) are printed, written to
``build/bench/scaling.json`` and drawn on a log-log plot, ``build/bench/scaling.png``.
Time per pixel is flat where the lines have slope 1.
"""

import argparse
import json
import os
import time

from phongfx.core.files import atomic_write
from phongfx.core.registry import get_block
from phongfx.sim import fast_backend, fast_build

__all__ = ["BLOCKS", "SIZES", "measure", "plot", "main"]

BLOCKS = ("fig7", "fig8", "euler")
SIZES = (64 * 64, 128 * 128, 256 * 256, 512 * 512, 1024 * 1024, 1920 * 1080)


def measure(blocks=BLOCKS, sizes=SIZES, seed=0):
    """Rows ``{block, pixels, golden, check, build, mismatches}`` (seconds)."""
    rows = []
    for name in blocks:
        block = get_block(name)
        start = time.perf_counter()
        fast_build.build(block.component())  # cached after the first run
        build = time.perf_counter() - start
        stimulus = block.stimulus(count=max(sizes), seed=seed)
        for pixels in sizes:
            raw = {port: value[:pixels] for port, value in stimulus.items()}
            result, times = fast_backend.check_timed(block, raw, bubbles=0.0, seed=seed)
            rows.append({"block": name, "pixels": pixels, "golden": times["golden"],
                         "check": times["pack"] + times["write"] + times["simulate"] + times["report"],
                         "build": build, "mismatches": result.mismatch_count})
    return rows


def plot(rows, path):
    """Log-log plot of golden and check seconds against pixels, one colour per block."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 5))
    for index, name in enumerate(dict.fromkeys(row["block"] for row in rows)):
        mine = [row for row in rows if row["block"] == name]
        pixels = [row["pixels"] for row in mine]
        colour = f"C{index}"
        ax.loglog(pixels, [row["golden"] for row in mine], "o--", color=colour, label=f"{name} golden")
        ax.loglog(pixels, [row["check"] for row in mine], "s-", color=colour,
                  label=f"{name} RTL check (verilator-fast)")
    ax.set(xlabel="pixels (cycles)", ylabel="seconds",
           title="Checking time against frame size, per datapath")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    atomic_write(path, lambda p: fig.savefig(p, dpi=100, format="png"))
    plt.close(fig)
    return path


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m bench.scaling", description=__doc__.split("\n")[0])
    parser.add_argument("--out", default="build/bench", help="folder for scaling.json and scaling.png")
    parser.add_argument("--max-pixels", type=int, default=max(SIZES), help="largest frame size")
    args = parser.parse_args(argv)
    sizes = [size for size in SIZES if size <= args.max_pixels]
    if not sizes:
        parser.error(f"--max-pixels must be at least {min(SIZES)}, not {args.max_pixels}")
    rows = measure(sizes=sizes)
    print(f"{'block':<8}{'pixels':>10}{'golden s':>10}{'check s':>10}{'ns/pixel':>10}{'mismatches':>12}")
    for row in rows:
        print(f"{row['block']:<8}{row['pixels']:>10}{row['golden']:>10.3f}{row['check']:>10.3f}"
              f"{1e9 * (row['golden'] + row['check']) / row['pixels']:>10.0f}{row['mismatches']:>12}")
    text = json.dumps(rows, indent=2) + "\n"
    atomic_write(os.path.join(args.out, "scaling.json"), lambda p: open(p, "w").write(text))
    print(f"wrote {plot(rows, os.path.join(args.out, 'scaling.png'))}")
    return 0 if not any(row["mismatches"] for row in rows) else 1


if __name__ == "__main__":
    raise SystemExit(main())
