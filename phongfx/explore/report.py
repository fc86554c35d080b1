"""Sweep results read back: the cheapest invisible-error datapaths, summary and
``build/report/index.md``.

A sweep (:mod:`phongfx.explore.sweep.run`) writes one JSON record per point to ``points.jsonl``
(``id, method, params, status, error, seconds, metrics, cost``).  This module answers the
user's question from those records: for each method, the cheapest datapath whose max
error is at most one 8-bit level, and which points are Pareto-optimal in error against
cost.  How records are costed and ranked (LUT-equivalents, µm², the Pareto front) is
:mod:`phongfx.explore.sweep.front`, the plots :mod:`phongfx.explore.sweep.plot`; both are
re-exported here, where the report's readers have always found them.
"""

import os
import sys

from phongfx.explore.sweep.front import (DSP_LUT_WEIGHT, INVISIBLE, MAXIMIZE, cost_key, is_proxy,
                                         lut_equivalent, pareto, target_label, value)
from phongfx.explore.sweep.plot import pareto_plot

__all__ = ["DSP_LUT_WEIGHT", "MAXIMIZE", "INVISIBLE", "load", "value", "cost_key", "is_proxy", "lut_equivalent", "pareto", "BASELINES",
           "cheapest_invisible", "pareto_plot", "summary_markdown", "build_report"]


def load(path):
    """Records of ``points.jsonl`` at ``path`` (:func:`phongfx.explore.sweep.run.load_records`: one per
    point, the last written winning; a torn last line ignored, a bad line elsewhere a
    ``ValueError``).  A missing file is ``FileNotFoundError``."""
    from phongfx.explore.sweep.run import load_records
    if not os.path.exists(path):
        raise FileNotFoundError(f"no sweep results at {path}: run `make sweep` first")
    return load_records(path)


def _params(record):
    return ", ".join(f"{k}={v}" for k, v in sorted((record.get("params") or {}).items())) or "defaults"


def _number(x, fmt):
    return "–" if x is None else fmt.format(x)


def _groups(records):
    """``label -> records`` per method, split by shininess ``n`` where a method has several."""
    by_method = {}
    for r in records:
        by_method.setdefault(r["method"], []).append(r)
    groups = {}
    for method in sorted(by_method):
        shininess = {(r.get("params") or {}).get("n") for r in by_method[method]}
        for r in by_method[method]:
            n = (r.get("params") or {}).get("n")
            groups.setdefault(method if len(shininess) <= 1 else f"{method} (n={n})", []).append(r)
    return groups


def cheapest_invisible(records, error_key="torus.phong.max", *, dsp_weight=DSP_LUT_WEIGHT):
    """``label -> (record, invisible)``: per group of :func:`_groups`, the cheapest ``ok`` record
    with error <= :data:`INVISIBLE` (``invisible`` True), else the lowest-error one (False).
    Cheapest = fewest LUT-equivalents (µm² on standard cells: :func:`cost_key`);
    records costed by a proxy rank after synthesized ones, records without cost last."""
    ok = [r for r in records if r.get("status") == "ok" and value(r, error_key) is not None]
    key = cost_key(ok)
    picks = {}
    for label, group in _groups(ok).items():
        good = [r for r in group if value(r, error_key) <= INVISIBLE]
        if good:  # synthesized costs first, then the proxy's estimates, then none
            cost = [(is_proxy(r), value(r, key, dsp_weight), value(r, error_key), r) for r in good]
            best = min(cost, key=lambda c: (c[1] is None, c[0], c[1] or 0.0, c[2]))[3]
            picks[label] = (best, True)
        else:
            picks[label] = (min(group, key=lambda r: value(r, error_key)), False)
    return picks


def _head(asic):
    if asic:
        return ["| method | params | max error (levels) | area µm² | cells | area×delay µm²·ns | Fmax MHz | Mpixel/s |",
                "|---|---|---:|---:|---:|---:|---:|---:|"]
    return ["| method | params | max error (levels) | LUT4 | DSP | LUT-eq | Fmax MHz | Mpixel/s |",
            "|---|---|---:|---:|---:|---:|---:|---:|"]


def _row(label, record, error_key, dsp_weight, note="", asic=False):
    cost = record.get("cost") or {}
    if asic:
        middle = (f"{_number(cost.get('area_um2'), '{:,.0f}')} | {_number(cost.get('cell_count'), '{:d}')} | "
                  f"{_number(cost.get('area_delay'), '{:,.0f}')}")
    else:
        middle = (f"{_number(cost.get('lut4'), '{:d}')} | {_number(cost.get('dsp'), '{:d}')} | "
                  f"{_number(lut_equivalent(cost, dsp_weight), '{:.0f}')}")
    return (f"| {label} | {note}{_params(record)} | {value(record, error_key):.3f} | {middle} | "
            f"{_number(cost.get('fmax_mhz'), '{:.1f}')} | {_number(cost.get('mpixels_per_s'), '{:.1f}')} |")


def summary_markdown(records, error_key="torus.phong.max", *, dsp_weight=DSP_LUT_WEIGHT):
    """Per method, the cheapest point with max error <= 1 level (or "none"), then the failed points."""
    asic = cost_key(records) == "area_um2"
    unit = f"area on {target_label(records)}" if asic else f"LUT4 + {dsp_weight}·DSP"
    lines = [f"Cheapest point per method with `{error_key}` ≤ {INVISIBLE:g} level "
             f"(cost = {unit}; – = not synthesized):", "", *_head(asic)]
    for label, (record, invisible) in cheapest_invisible(records, error_key, dsp_weight=dsp_weight).items():
        note = "" if invisible else f"**none ≤ {INVISIBLE:g} level**; best: "
        lines.append(_row(label, record, error_key, dsp_weight, note, asic))
    failed = [r for r in records if r.get("status") != "ok"]
    ok = sum(r.get("status") == "ok" for r in records)
    lines += ["", f"{len(records)} points: {ok} ok, {len(failed)} failed."]
    if failed:
        lines += ["", "Failed points:", ""]
        lines += [f"* `{r.get('id', '?')}` {r.get('method', '?')} ({_params(r)}): "
                  f"{(str(r.get('error') or '').strip().splitlines() or ['no message'])[0]}" for r in failed]
    return "\n".join(lines) + "\n"


#: The baselines the report lists every point of: what each computes.
BASELINES = {"conventional": ("Phong baseline", "normalize N by reciprocal square root, (R·V)^n by log/exp tables"),
             "blinn": ("Blinn–Phong baseline", "normalize by reciprocal square root, (N̂·H)^n by table")}


def _baseline(records, error_key, dsp_weight):
    asic = cost_key(records) == "area_um2"
    key = cost_key(records)
    lines = []
    for method, (title, what) in BASELINES.items():
        mine = [r for r in records if r.get("method") == method and r.get("status") == "ok"
                and value(r, error_key) is not None]
        lines += [f"## {title}", ""]
        if not mine:
            lines += [f"The sweep has no `{method}` point.", ""]
            continue
        lines += [f"Every `{method}` point of the sweep ({what}), cheapest first:", "", *_head(asic)]
        mine.sort(key=lambda r: (value(r, key, dsp_weight) is None, value(r, key, dsp_weight) or 0.0,
                                 value(r, error_key)))
        lines += [_row(method, r, error_key, dsp_weight, asic=asic) for r in mine] + [""]
    return lines


#: Smaller runs of the slow tables for ``quick=True``: a smoke run of every table, under 2
#: minutes on 2 cores with an empty cache.  4 frames of Hast's; 3 blocks of the cost table's
#: 7; for the pipeline table (3 datapaths × 5 depths × 3 seeds, 45 syntheses) the shape
#: block at depths 0 and 2 with one seed; 2 of the area proxy's 22 points (standard cells);
#: for the clock proxy's (every datapath at every depth, on ECP5 and standard cells) the
#: shape block at depth 0.  The shape block's runs at its defaults are shared (cached).
_QUICK = {"hast": {"frames": 4}, "cost": {"blocks": ("difference", "shape", "root")},
          "pipeline": {"names": ("shape",), "depths": (0, 2), "seeds": (1,)},
          "proxy": {"points": (("shape", "shape", None), ("root", "root", None))},
          "clock": {"selected": [("shape", "shape", None, 0)]}}


def _demote(text):
    """Headings one level down; the modules' own plot links dropped (we link them relative)."""
    return "\n".join("#" + line if line.startswith("#") else line for line in text.splitlines()
                     if not line.startswith(("Plots: ", "![")))


def _table_section(name, out_dir, quick, failed):
    from phongfx.explore.synth.toolrun import SynthError
    from phongfx.explore.tables import table_module

    module = table_module(name)
    where = os.path.join(out_dir, name)
    os.makedirs(where, exist_ok=True)
    try:
        result = module.run_table(name, out_dir=where, **(_QUICK.get(name, {}) if quick else {}))
    except SynthError as error:  # one table's failed synthesis: the others still run, and it shows
        first = (str(error).strip().splitlines() or ["no message"])[0]
        print(f"report: table {name} FAILED: {first}", file=sys.stderr, flush=True)
        failed.append(name)
        return [f"## {name}: failed", "", f"A synthesis failed: {first}", ""]
    lines = [_demote(module.markdown(result)), ""]
    plots = sorted(f for f in os.listdir(where) if f.endswith(".png"))
    lines += [f"![{name} {p}]({name}/{p})" for p in plots]
    return lines + [""]


def _write_text(path, text):
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)


def _sweep_section(records, points, sweep_dir, out_dir, error_keys, dsp_weight):
    csv = os.path.join(sweep_dir, "points.csv")
    lines = [f"{len(records)} points from `{points}`"
             + (f" (table: [points.csv]({os.path.relpath(csv, out_dir)}))" if os.path.isfile(csv) else "")
             + ".", "",
             "Errors are 8-bit levels, 255·|fixed − float| over the visible pixels "
             "(`phongfx.explore.evaluate`): `<scene>.phong.*` against float per-pixel Phong of the same "
             "quantity, `<scene>.self.*` against the method's own float form.  `euler` and "
             "`gouraud` (Hast et al.) measure the diffuse N·L, the other methods the specular term.", ""]
    for i, key in enumerate(error_keys):
        if not any(value(r, key) is not None for r in records):
            lines += [f"No point has `{key}`.", ""]
            continue
        png = "pareto.png" if i == 0 else f"pareto_{key.replace('.', '_')}.png"
        front = pareto_plot(records, os.path.join(out_dir, png), key, dsp_weight=dsp_weight)
        lines += [f"## `{key}` against cost", "",
                  f"{front['plotted']} points plotted, {front['skipped']} without cost not plotted.", "",
                  f"![Pareto plot of {key}]({png})", "",
                  "Pareto front in cost, cheapest first: " + (", ".join(
                      f"{r['method']} ({_params(r)})" for r in front[cost_key(records)]) or "–"), "",
                  f"### Cheapest invisible-error datapaths (`{key}`)", "",
                  summary_markdown(records, key, dsp_weight=dsp_weight)]
    return lines + _baseline(records, error_keys[0], dsp_weight)


def build_report(out_dir="build/report", sweep_dir="build/sweep",
                 tables=("lyon", "szirmay", "hast", "schlick", "cost", "pipeline"), quick=False,
                 error_keys=("torus.phong.max", "torus.self.max"), dsp_weight=DSP_LUT_WEIGHT, failed=None):
    """Write ``out_dir/index.md``: the papers' tables measured, then the sweep's Pareto plots,
    cheapest invisible-error datapaths and the Blinn–Phong baseline.

    Each table module's ``run_table`` writes its plots under ``out_dir/<table>``.  For each
    of ``error_keys`` (default: error against float Phong, then against the method's own
    float form, on the torus) the sweep gets a Pareto plot (``out_dir/pareto.png`` for the
    first, ``pareto_<key>.png`` for the others) and a summary; the Blinn–Phong baseline is
    listed by the first key.  ``index.md`` is written last and atomically: on any error it
    is left as it was.  ``quick`` runs the slow tables smaller (:data:`_QUICK`).  A table whose
    synthesis fails is a section saying so (and a ``report: table NAME FAILED`` line on
    stderr) and its name is appended to ``failed`` (a list, when given); the other tables
    still run.  Returns the path of ``index.md``.
    """
    from phongfx.core.files import atomic_write

    if isinstance(error_keys, str) or not error_keys:
        raise ValueError(f"error_keys must be a non-empty sequence of metric keys, not {error_keys!r}")
    lines = ["# phongfx report", "",
             "Measurements of the papers' claims and of the bit-width sweep: what each datapath costs and how far it is from Phong. "
             "Regenerate with `make report`."
             + (f" Quick run: smaller {', '.join(t for t in _QUICK if t in tables)} tables." if quick else ""), ""]
    if tables:
        lines += ["# The papers' tables, measured", ""]
    failed = [] if failed is None else failed
    for name in tables:
        lines += _table_section(name, out_dir, quick, failed)
    lines += ["# Sweep: error against hardware cost", ""]
    points = os.path.join(sweep_dir, "points.jsonl")
    if not os.path.isfile(points):
        lines += [f"No sweep results at `{points}`: run `make sweep` first, then `make report`.", ""]
    else:
        lines += _sweep_section(load(points), points, sweep_dir, out_dir, tuple(error_keys), dsp_weight)
    index = os.path.join(out_dir, "index.md")
    text = "\n".join(lines).rstrip() + "\n"
    atomic_write(index, lambda p: _write_text(p, text))
    return index
