"""``phongfx tables pipeline``: Fmax, size and latency against pipeline depth:
what each register level buys in clock speed, and what it costs in flip-flops and latency.

For each datapath of :data:`NAMES` (Lyon's Figure 7 and Figure 8) and each depth of
:data:`DEPTHS`, :func:`phongfx.explore.synth.fpga.synth` synthesizes, places and routes the block
with ``pipeline=depth`` (see :class:`phongfx.config.BlockConfig`) on an ECP5 at
:data:`FREQ` MHz, once per placement seed of :data:`SEEDS`, and reports the median Fmax (and
each seed's: placement alone moves it by about ±10%), LUT4s, flip-flops, DSP multipliers
(MULT18X18D, with the pipeline's registers inside them: :mod:`phongfx.hdl.dsp`), latency in
cycles and the critical path of the median run.  The goal is one pixel per clock at
:data:`FREQ` MHz or more; the Markdown says, per datapath, the first depth that meets
it or what limits the deepest one, and where nextpnr leaves a DSP's internal multiply
untimed, the bound that puts on the clock.  A PNG plots Fmax against depth.

Deterministic: synthesis runs with fixed placement seeds and is cached on disk.
"""

import json
import os
import sys

from phongfx.config import MAX_PIPELINE
from phongfx.core.registry import get_block

from phongfx.explore.progress import Candidates

__all__ = ["TABLES", "NAMES", "DEPTHS", "SEEDS", "FREQ", "pipeline_rows", "run_table", "markdown",
           "to_json", "plot"]

#: Tables this module knows.
TABLES = ("pipeline",)

#: Datapaths measured: Figure 7 and Figure 8, and the normalizer that limited both at depth 0.
NAMES = ("fig7", "fig8", "normalize")

#: Pipeline depths measured.
DEPTHS = tuple(range(MAX_PIPELINE + 1))

#: Target clock (MHz) given to nextpnr, and the goal.
FREQ = 150

#: nextpnr placement seeds per point; the table gives the median Fmax.
SEEDS = (1, 2, 3)

_KEYS = ("fmax_mhz", "lut4", "ff", "dsp", "latency", "critical_path")
_ASIC_KEYS = ("fmax_mhz", "area_um2", "ff", "latency", "critical_path")


def _to_stderr(text):
    print(f"pipeline: {text}", file=sys.stderr, flush=True)


def pipeline_rows(names=NAMES, depths=DEPTHS, *, target="ecp5", device=None, freq=FREQ, seeds=SEEDS,
                  workdir=None, progress=None):
    """Rows ``{name, depth, fmax_mhz, fmax_seeds, lut4, ff, dsp, latency, critical_path,
    met}`` (on ``target="asic"``: ``area_um2`` instead of ``lut4`` and ``dsp``, one run: the
    standard-cell flow has no placement seed), one per (name, depth), from
    :func:`phongfx.explore.synth.fpga.synth`: ``fmax_mhz`` is the median over ``seeds``, the
    other values those of the median run; on an FPGA, ``fmax_bound_mhz`` also caps it
    where nextpnr leaves a DSP's internal multiply untimed (``dsp_untimed`` DSPs).

    Every run takes up to minutes, so ``progress(text)`` (default: a ``pipeline:`` line on
    stderr) hears "synthesizing candidate i of N (name, pipeline=d seed=s) T s" and the
    flow's stages (:class:`~phongfx.explore.progress.Candidates`)."""
    from phongfx.explore.synth import fpga as synth_module

    rows = []
    asic = target == "asic"
    keys = _ASIC_KEYS if asic else _KEYS
    runs = (1,) if asic else tuple(seeds)
    steps = Candidates(len(names) * len(depths) * len(runs), progress or _to_stderr)
    for name in names:
        for depth in depths:
            config = get_block(name, pipeline=depth).config
            results = []
            for seed in runs:
                options = {} if asic else {"seed": seed}
                stage = steps.next(name, {"pipeline": depth, **options})
                results.append(synth_module.synth(name, config=config, target=target, device=device,
                                                  freq=freq, workdir=workdir, progress=stage, **options))
            ranked = sorted(results, key=lambda result: result["fmax_mhz"])
            median = ranked[(len(ranked) - 1) // 2]
            row = {"name": name, "depth": depth, **{key: median[key] for key in keys}}
            if not asic:
                row["fmax_seeds"] = [round(result["fmax_mhz"], 1) for result in results]
                row["dsp_untimed"] = median.get("dsp_untimed", 0)
                row["fmax_bound_mhz"] = median.get("fmax_bound_mhz", median["fmax_mhz"])
            row["met"] = bool(row["fmax_mhz"] >= freq)
            rows.append(row)
    return rows


def run_table(name, out_dir=None, target="ecp5", device=None, progress=None, names=NAMES, depths=DEPTHS,
              seeds=SEEDS):
    """The table called ``name`` (:data:`TABLES`) on ``target`` (``device``: the FPGA part or
    the standard-cell library), over ``names``, ``depths`` and ``seeds`` (a smaller run
    for a smoke test); writes ``pipeline_fmax.png`` into ``out_dir`` when given (its path
    is the result's ``plot``)."""
    if name not in TABLES:
        raise ValueError(f"unknown table {name!r}; valid tables: {', '.join(TABLES)}")
    rows = pipeline_rows(names, depths, target=target, device=device, seeds=seeds, progress=progress)
    result = {"source": "Fmax against pipeline depth: pipelining to a target frequency",
              "target": target, "device": device, "freq": FREQ,
              "seeds": [1] if target == "asic" else list(seeds), "rows": rows, "plot": None}
    if out_dir is not None:
        result["plot"] = plot(result, os.path.join(out_dir, "pipeline_fmax.png"))
    return result


def _verdict(rows, freq):
    met = [row for row in rows if row["met"]]
    deepest = rows[-1]
    path = deepest["critical_path"] or {}
    split = (f" ({path['logic_ns']:.2f} logic, {path['routing_ns']:.2f} routing)" if "logic_ns" in path else "")
    limit = (f"critical path at depth {deepest['depth']}: {path.get('from', '?')} → {path.get('to', '?')}, "
             f"{path.get('ns', 0):.2f} ns{split}")
    if met:
        return f"meets {freq} MHz from depth {met[0]['depth']} (latency {met[0]['latency']} cycles); {limit}"
    return f"**falls short of {freq} MHz**: {deepest['fmax_mhz']:.1f} MHz at depth {deepest['depth']}; {limit}"


def markdown(result):
    """One row per (datapath, depth), then a verdict per datapath and the DSP caveat."""
    freq = result["freq"]
    asic = result["target"] == "asic"
    where = result["target"] + (f" {result['device']}" if result.get("device") else "")
    seeds = result.get("seeds", [1])
    what = f"median of {len(seeds)} placement seeds" if len(seeds) > 1 else f"seed {seeds[0]}"
    lines = [f"# Fmax against pipeline depth ({where}, {freq} MHz target, {what})", ""]
    if asic:
        lines += ["| datapath | depth | Fmax MHz | area µm² | FF | latency | critical path (ns, pre-layout) |",
                  "|---|---:|---:|---:|---:|---:|---|"]
    else:
        lines += ["| datapath | depth | Fmax MHz | seeds | LUT4 | FF | DSP | latency | "
                  "critical path (ns: logic + routing) |",
                  "|---|---:|---:|---|---:|---:|---:|---:|---|"]
    for row in result["rows"]:
        path = row["critical_path"] or {}
        ends = f"{path.get('from', '?')} → {path.get('to', '?')}"
        fmax = f"{row['fmax_mhz']:.1f}{'' if row['met'] else ' ✗'}"
        if asic:
            lines.append(f"| {row['name']} | {row['depth']} | {fmax} | {row['area_um2']:,.0f} | {row['ff']} | "
                         f"{row['latency']} | {ends} ({path.get('ns', 0):.2f}) |")
        else:
            spread = " / ".join(f"{f:.1f}" for f in row.get("fmax_seeds", [row["fmax_mhz"]]))
            lines.append(f"| {row['name']} | {row['depth']} | {fmax} | {spread} | {row['lut4']} | {row['ff']} | "
                         f"{row['dsp']} | {row['latency']} | {ends} ({path.get('logic_ns', 0):.2f} + "
                         f"{path.get('routing_ns', 0):.2f}) |")
    lines.append("")
    for name in dict.fromkeys(row["name"] for row in result["rows"]):
        rows = [row for row in result["rows"] if row["name"] == name]
        lines.append(f"* {name}: {_verdict(rows, freq)}.")
    untimed = [row for row in result["rows"] if row.get("dsp_untimed")]
    if untimed:
        from phongfx.hdl.dsp import DSP_INTERNAL_NS

        lines += ["", f"Caveat: where a MULT18X18D has its input and output registers on ({untimed[0]['dsp_untimed']} "
                      f"of {untimed[0]['dsp']} DSPs at depth {untimed[0]['depth']} of {untimed[0]['name']}), nextpnr "
                      f"does not time the multiply between them; its timing data puts that at up to "
                      f"{DSP_INTERNAL_NS} ns, so the DSPs themselves bound the clock at "
                      f"{1000 / DSP_INTERNAL_NS:.0f} MHz, above every Fmax here."
                  if all(row["fmax_mhz"] <= 1000 / DSP_INTERNAL_NS for row in untimed) else
                  f"Caveat: nextpnr does not time the multiply inside a MULT18X18D whose input and output "
                  f"registers are on (up to {DSP_INTERNAL_NS} ns): Fmax above {1000 / DSP_INTERNAL_NS:.0f} MHz "
                  f"is a routing bound, not a clock the DSPs are known to meet."]
    if result.get("plot"):
        lines += ["", f"![Fmax against depth]({os.path.basename(result['plot'])})"]
    return "\n".join(lines) + "\n"


def to_json(result):
    return json.dumps(result, indent=2, ensure_ascii=False)


def plot(result, path):
    """PNG of Fmax against depth, one line per datapath, the target dashed; returns ``path``."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from phongfx.core.files import atomic_write

    fig, ax = plt.subplots(figsize=(6, 4))
    for name in dict.fromkeys(row["name"] for row in result["rows"]):
        rows = [row for row in result["rows"] if row["name"] == name]
        ax.plot([r["depth"] for r in rows], [r["fmax_mhz"] for r in rows], "o-", label=name)
    ax.axhline(result["freq"], color="gray", linestyle="--", label=f"target {result['freq']} MHz")
    ax.set_xlabel("pipeline depth")
    ax.set_ylabel("Fmax (MHz, nextpnr)")
    ax.set_xticks(sorted({row["depth"] for row in result["rows"]}))
    ax.set_title(f"Fmax against pipeline depth ({result['target']})")
    ax.legend()
    fig.tight_layout()
    atomic_write(path, lambda tmp: fig.savefig(tmp, format="png", dpi=100))
    plt.close(fig)
    return path
