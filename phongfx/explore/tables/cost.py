"""``phongfx tables cost``: Lyon's Figure 8 against Figure 7c in LUTs, DSPs and MHz.

Lyon (Apple TR #43, 1993, "Hardware Rearrangements for Bit Reductions") says of the
root-shininess unit (``m = √n``) of Figure 8: "the six 7×11 and 9×9 multipliers are likely
to be smaller and faster than the three 12×12 and one 14×22 required for similar accuracy
in the arrangement of Figure 7".  This table synthesizes, places and routes
(:func:`phongfx.explore.synth.fpga.synth`, ECP5, 150 MHz constraint) the parts and the wholes:

* ``difference`` — Figure 7c (``D = R - L``, ``D·D``, ``2x = n·D·D``), the part the claim is about;
* ``shape`` — Figure 7d (``f_k``, ``k = 2``), which Figure 7 needs after 7c;
* ``root`` — Figure 8 (``|D|·m``, fraction-only dot product, augmented comparator and
  its own shape ``f_1``), so it compares with ``difference`` + ``shape`` (a derived row);
* ``fig7``, ``fig8`` — the whole datapaths (two lights), and the ``blinn`` (Blinn–Phong) baseline.

Cost in LUT-equivalents uses :data:`phongfx.explore.report.DSP_LUT_WEIGHT` per DSP.  The
multiplier sizes of our formats are derived from the configs (:func:`multipliers`);
accuracy at equal ``n`` (:data:`N`) comes from :func:`phongfx.explore.evaluate.evaluate` on the
torus scene (max error in 8-bit levels against Phong and against the method's own float form).
"""

import json
import sys

from phongfx.config import DifferenceConfig, RootConfig

from phongfx.explore.progress import Candidates
from phongfx.explore.sweep.front import DSP_LUT_WEIGHT, lut_equivalent
from phongfx.explore.synth.fpga import SynthError, synth

__all__ = ["TABLES", "BLOCKS", "CLAIM", "N", "WHAT", "multipliers", "cost_of", "cost_table", "run_table", "markdown",
           "to_json"]

TABLES = ("cost",)
BLOCKS = ("difference", "shape", "root", "fig7", "fig8", "blinn", "conventional")
#: Lyon's words, from the end of "Hardware Rearrangements for Bit Reductions".
CLAIM = ("Figure 8: \"the six 7×11 and 9×9 multipliers are likely to be smaller and faster than "
         "the three 12×12 and one 14×22 required for similar accuracy in the arrangement of Figure 7\" "
         "(Figure 7c).")
#: Shininess at which Figure 7 (n) and Figure 8 (m = √n = 4) are compared for accuracy.
N = 16
#: What each compared block is, as its row says it.
WHAT = {"difference": "Figure 7c: D, D·D, n·D·D", "shape": "Figure 7d: f_2",
        "root": "Figure 8: m·abs(D), Σu², comparator, f_1", "fig7": "Figure 7 datapath, 2 lights",
        "fig8": "Figure 8 datapath, 2 lights", "blinn": "Blinn–Phong (rsqrt, log/exp tables)",
        "conventional": "Phong (R·V)^n per pixel (rsqrt, log/exp tables)"}
_KEYS = ("lut4", "ff", "carry", "dsp", "bram_bits", "fmax_mhz", "latency", "met", "cached")
_ASIC_KEYS = ("area_um2", "cell_count", "ff", "fmax_mhz", "area_delay", "latency", "met", "cached")
_SUMMED = {"ecp5": ("lut4", "ff", "carry", "dsp", "bram_bits", "latency"), "asic": ("area_um2", "cell_count", "ff",
                                                                                    "latency")}


def multipliers(difference=None, root=None):
    """Multiplier sizes (a × b bits) of Figure 7c and Figure 8 in our formats.

    Figure 7c: three ``d × d`` squares and ``dd × n``; Figure 8: three ``m × |d|``
    (``|d|`` is ``d`` without its sign bit) and three ``frac × frac`` squares.
    """
    difference = difference or DifferenceConfig()
    root = root or RootConfig()
    d, dd, n = (difference.fmt(k).width for k in ("d", "dd", "n"))
    m, rd, frac = root.fmt("m").width, root.fmt("d").width - 1, root.fmt("frac").width
    return {"fig7c": [(d, d)] * 3 + [(n, dd)], "fig8": [(m, rd)] * 3 + [(frac, frac)] * 3}


def cost_of(row):
    """The cost a row is compared by: µm² on standard cells, LUT-eq on an FPGA."""
    return row["area_um2"] if "area_um2" in row else row["lut_eq"]


def _to_stderr(text):
    print(f"cost: {text}", file=sys.stderr, flush=True)


def _synthesize(block, target, device, freq, workdir, steps):
    try:
        result = synth(block, target=target, device=device, freq=freq, workdir=workdir, progress=steps.next(block))
    except SynthError as error:
        steps.failed(error)
        return {"block": block, "what": WHAT.get(block, block), "error": str(error).splitlines()[0]}
    keys = _ASIC_KEYS if target == "asic" else _KEYS
    row = {"block": block, "what": WHAT.get(block, block), **{k: result[k] for k in keys}}
    row["mpixels_per_s"] = result["pixels_per_second"] / 1e6
    if target != "asic":
        row["lut_eq"] = lut_equivalent(row)
    return row


def _combined(a, b, name, what):
    """Two blocks in series: resources add, latency adds, the slower clock rules."""
    row = {"block": name, "what": what, "met": a["met"] and b["met"], "cached": a["cached"] and b["cached"]}
    row.update({k: a[k] + b[k] for k in _SUMMED["asic" if "area_um2" in a else "ecp5"]})
    row["fmax_mhz"] = min(a["fmax_mhz"], b["fmax_mhz"])
    row["mpixels_per_s"] = row["fmax_mhz"]
    if "area_um2" in a:
        row["area_delay"] = row["area_um2"] * 1e3 / row["fmax_mhz"]
    else:
        row["lut_eq"] = lut_equivalent(row)
    return row


def _accuracy(methods, n):
    try:
        from phongfx.explore.evaluate import evaluate
    except ImportError:
        return None
    result = {}
    for method in methods:
        metrics = evaluate(method, {"n": n}, scenes=("torus",))["metrics"]
        result[method] = {"phong": metrics["torus.phong.max"], "self": metrics["torus.self.max"]}
    return result


def cost_table(blocks=BLOCKS, *, target="ecp5", device=None, freq=150, n=N, workdir=None,
               progress=None):
    """Rows of synthesis results for ``blocks`` plus ``difference+shape``; accuracy of the
    whole datapaths and the Phong baseline.  ``target`` ``"asic"`` with ``device`` a
    library (``osu018``, ``osu035``) prices in µm² instead of LUT-eq.

    A block whose synthesis fails gets a row with ``error`` instead of numbers.  Each block
    takes up to minutes, so ``progress(text)`` (default: a ``cost:`` line on stderr) hears
    "synthesizing candidate i of N (block) T s" and the flow's stages
    (:class:`~phongfx.explore.progress.Candidates`), and a failed block's error.
    """
    unknown = [b for b in blocks if b not in BLOCKS]
    if unknown:
        raise ValueError(f"blocks must be among {', '.join(BLOCKS)}, not {unknown[0]!r}")
    steps = Candidates(len(blocks), progress or _to_stderr)
    rows = {b: _synthesize(b, target, device, freq, workdir, steps) for b in blocks}
    if all(b in rows and "error" not in rows[b] for b in ("difference", "shape")):
        rows["difference+shape"] = _combined(rows["difference"], rows["shape"], "difference+shape",
                                             "Figure 7c + 7d in series")
    order = [b for b in ("difference", "shape", "difference+shape", "root", "fig7", "fig8", "blinn",
                         "conventional") if b in rows]
    accuracy = _accuracy([m for m in ("fig7", "fig8", "conventional") if m in blocks], n)
    return {"table": "cost", "claim": CLAIM, "target": target, "device": device, "freq": freq, "n": n,
            "dsp_weight": DSP_LUT_WEIGHT, "multipliers": multipliers(),
            "rows": [rows[b] for b in order], "accuracy": accuracy}


def run_table(name, out_dir=None, blocks=BLOCKS, **options):
    """The table called ``name`` (``"cost"``); nothing is written to ``out_dir``.  ``options``
    go to :func:`cost_table` (``target``, ``device``, ``freq``, ``n``, ``workdir``, ``progress``)."""
    if name not in TABLES:
        raise ValueError(f"unknown table {name!r}; valid tables: {', '.join(TABLES)}")
    return cost_table(blocks, **options)


def _sizes(pairs):
    counts = {}
    for a, b in pairs:
        counts[f"{a}×{b}"] = counts.get(f"{a}×{b}", 0) + 1
    return " + ".join(f"{c} × {size}" for size, c in counts.items())


def _compare(a, b, smaller, larger, tolerance=0.02):
    """``smaller`` / ``larger`` / "about the same" for ``a`` against ``b`` (within ``tolerance``)."""
    if abs(a - b) <= tolerance * max(abs(a), abs(b)):
        return f"about the same (±{tolerance:.0%})"
    return smaller if a < b else larger


def _verdict(rows):
    by = {r["block"]: r for r in rows if "error" not in r}
    asic = any("area_um2" in r for r in by.values())
    unit, fmt = ("area µm²", "{:,.0f}") if asic else ("LUT-eq", "{:.0f}")
    lines = []
    for ours, theirs in (("root", "difference"), ("root", "difference+shape"), ("fig8", "fig7"),
                         ("fig7", "conventional"), ("fig8", "conventional")):
        if ours in by and theirs in by:
            a, b = by[ours], by[theirs]
            ca, cb = cost_of(a), cost_of(b)
            dsp = "" if asic else f"DSP {a['dsp']} vs {b['dsp']}, "
            lines.append(f"* {ours} vs {theirs}: {unit} {fmt.format(ca)} vs {fmt.format(cb)} "
                         f"({_compare(ca, cb, 'smaller', '**larger**')}; {ca / cb:.2f}×), "
                         f"{dsp}Fmax {a['fmax_mhz']:.1f} vs {b['fmax_mhz']:.1f} MHz "
                         f"({_compare(-a['fmax_mhz'], -b['fmax_mhz'], 'faster', '**slower**')}).")
    if lines and not asic:
        lines.append("* Every multiplier up to 18×18 takes one MULT18X18D whatever its size, so "
                     "narrower multipliers save DSPs only where they avoid a split (a 13×22 takes two).")
    elif lines:
        lines.append("* On standard cells a multiplier's area grows with the product of its operand "
                     "widths, the setting Lyon's claim is about.")
    return lines


def _rows_markdown(result):
    if result["target"] == "asic":
        lines = [f"| block | what | area µm² | cells | FF | Fmax MHz | Mpixel/s | area×delay µm²·ns | latency | "
                 f"≥ {result['freq']:g} MHz |", "|---|---|---:|---:|---:|---:|---:|---:|---:|---|"]
        cell = ("{area_um2:,.0f} | {cell_count} | {ff} | {fmax_mhz:.1f} | {mpixels_per_s:.1f} | "
                "{area_delay:,.0f} | {latency}")
    else:
        lines = [f"| block | what | LUT4 | FF | carry | DSP | BRAM bits | LUT-eq (+{result['dsp_weight']}/DSP) | "
                 f"Fmax MHz | Mpixel/s | latency | ≥ {result['freq']:g} MHz |",
                 "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|"]
        cell = ("{lut4} | {ff} | {carry} | {dsp} | {bram_bits} | {lut_eq:.0f} | {fmax_mhz:.1f} | "
                "{mpixels_per_s:.1f} | {latency}")
    columns = lines[1].count("|") - 1
    for r in result["rows"]:
        if "error" in r:
            lines.append(f"| {r['block']} | {r['what']} | synthesis failed: {r['error']} |" + " |" * (columns - 3))
            continue
        lines.append(f"| {r['block']} | {r['what']} | {cell.format(**r)} | {'yes' if r['met'] else 'no'} |")
    return lines


def markdown(result):
    """The claim, the multiplier sizes, the side-by-side table, the accuracy and a verdict."""
    sizes = result["multipliers"]
    where = result["target"] + (f" {result['device']}" if result.get("device") else "")
    lines = [f"# Figure 8 vs Figure 7c, synthesized ({where}, {result['freq']:g} MHz constraint)",
             "", f"Lyon's claim — {result['claim']}", "",
             f"Our formats: Figure 7c has {_sizes(sizes['fig7c'])} multipliers; Figure 8 has "
             f"{_sizes(sizes['fig8'])} (plus the k = 1 shape's one squaring in `root`).", "",
             *_rows_markdown(result), ""]
    if result["accuracy"] is None:
        lines += ["Accuracy column left out: `phongfx.explore.evaluate` is not available.", ""]
    elif result["accuracy"]:
        lines += [f"Accuracy at equal shininess n = {result['n']} (Figure 8: m = √n), torus scene, "
                  "max error in 8-bit levels:", "", "| datapath | vs Phong (R·L)^n | vs own float form |",
                  "|---|---:|---:|"]
        lines += [f"| {m} | {a['phong']:.2f} | {a['self']:.2f} |" for m, a in result["accuracy"].items()]
        lines.append("")
    verdict = _verdict(result["rows"])
    if verdict:
        lines += ["Measured against the claim:", "", *verdict, ""]
    return "\n".join(lines)


def to_json(result):
    return json.dumps(result, indent=2, ensure_ascii=False)
