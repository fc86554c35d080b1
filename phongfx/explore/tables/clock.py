"""``phongfx tables clock``: the tool-free clock proxy against synthesis, per target and depth.

:func:`phongfx.explore.synth.clock.proxy_clock` prices the slowest register-to-register
stage of a design's RTLIL; its coefficients
(:data:`~phongfx.explore.synth.clock.COEFFICIENTS`) were fitted by :func:`fit` to the
synthesized clock of every point of :func:`points`: every datapath the compiler can
choose (Lyon's Figures 7, 8 and 5, the Blinn–Phong, spherical and conventional units) and
two whole shaders (Figure 7 holding two lights; two Blinn–Phong copies, one per light) at
every pipeline depth they take, on ECP5 (nextpnr's Fmax on the LFE5U-45F, seed 1, 150 MHz
asked) and on osu018 (OpenSTA, pre-layout).  This table reruns that comparison: per
point and target the measured Fmax, the proxy's, the error and both critical paths; per
target the median and largest error.  On ECP5 it also compares the area proxy's LUT4
and DSP counts with the synthesized ones, the margins of
:data:`~phongfx.explore.synth.proxy.RESOURCE_MARGIN`.  With ``refit`` it fits afresh.

Deterministic: synthesis runs with a fixed seed and is cached on disk.
"""

import json
import statistics
import sys

from phongfx.config import MAX_PIPELINE, BlendConfig, ShaderConfig
from phongfx.core.registry import get_block

from phongfx.explore.progress import Candidates
from phongfx.explore.synth.clock import COEFFICIENTS, ERROR, FEATURES, clock_rtlil, critical_path
from phongfx.explore.synth.netgraph import flatten
from phongfx.explore.synth.proxy import RESOURCE_MARGIN, rtlil_cost, rtlil_of
from phongfx.explore.tables.proxy import relative_nnls

__all__ = ["TABLES", "NAMES", "DEPTHS", "TARGETS", "FREQ", "SEED", "points", "calibration_rows", "fit",
           "summary", "resource_errors", "clock_table", "run_table", "markdown", "to_json"]

TABLES = ("clock",)
#: Every unit the compiler can choose; a unit without a depth has one row.
NAMES = ("fig7", "fig8", "halfway_datapath", "blinn", "spherical", "conventional")
DEPTHS = tuple(range(MAX_PIPELINE + 1))
#: (target, device) measured: the FPGA the compiler targets by default, and osu018.
TARGETS = (("ecp5", "45k"), ("asic", "osu018"))
#: nextpnr's clock constraint (MHz) and placement seed for every point.
FREQ = 150
SEED = 1


def _two_blinn():
    unit = get_block("blinn").config
    return ShaderConfig(unit="blinn", units=(unit, unit), blend=BlendConfig(lights=2, diff="1.15", spec="1.15"))


def _configs():
    yield "shader", "shader", get_block("shader").config
    yield "shader blinn×2", "shader", _two_blinn()
    for name in NAMES:
        yield name, name, get_block(name).config


def _deepen(config, depth):
    try:
        return config.replace(pipeline=depth)
    except (TypeError, ValueError):
        return None


def points(depths=DEPTHS):
    """(label, block name, config, depth) of every calibration point: each datapath and
    shader at every depth it takes (one row, depth None, for a unit without one)."""
    result = []
    for label, name, config in _configs():
        if _deepen(config, 0) is None:
            result.append((label, name, config, None))
            continue
        result.extend((label, name, _deepen(config, d), d) for d in depths)
    return result


def _netlist(block, target):
    return flatten(clock_rtlil(block, target))


def calibration_rows(selected=None, *, targets=TARGETS, workdir=None, progress=None):
    """One row per point of ``selected`` (default :func:`points`) and target: ``label``,
    ``block``, ``depth``, ``target``, the synthesized ``fmax_mhz`` and ``critical_path``,
    the proxy's ``proxy_mhz``, ``amounts`` (:data:`~phongfx.explore.synth.clock.FEATURES`
    along its path) and ``proxy_path``, the ``error`` (proxy / synthesis − 1); on an FPGA
    also the synthesized ``lut4`` (LUT4 and two per CCU2C) and ``dsp`` beside the area
    proxy's (``proxy_lut4``, ``proxy_dsp``).  Each row's ``netlist`` is kept for :func:`fit`
    (not written out)."""
    from phongfx.explore.synth.fpga import synth

    selected = points() if selected is None else selected
    steps = Candidates(len(selected) * len(targets), progress or (lambda text: print(f"clock: {text}",
                                                                                    file=sys.stderr, flush=True)))
    rows = []
    for target, device in targets:
        for label, name, config, depth in selected:
            block = get_block(name, config)
            stage = steps.next(label, {"pipeline": depth, "target": target})
            options = {} if target == "asic" else {"seed": SEED}
            result = synth(name, config=config, target=target, device=device, freq=FREQ, workdir=workdir,
                           progress=stage, **options)
            netlist = _netlist(block, target)
            ns, amounts, path = critical_path(netlist, COEFFICIENTS[target])
            row = {"label": label, "block": name, "depth": depth, "target": target, "device": device,
                   "fmax_mhz": result["fmax_mhz"], "critical_path": result.get("critical_path"),
                   "proxy_mhz": 1000 / ns, "amounts": amounts, "proxy_path": f"{path[0]} → {path[-1]}",
                   "error": (1000 / ns) / result["fmax_mhz"] - 1, "netlist": netlist}
            if target != "asic":
                cost = rtlil_cost(rtlil_of(block))
                row.update({"lut4": result["lut4"] + 2 * result["carry"], "dsp": result["dsp"],
                            "proxy_lut4": cost["lut4"], "proxy_dsp": cost["dsp"]})
            rows.append(row)
    return rows


def fit(netlists, periods, start, rounds=12):
    """Non-negative ns per feature (:data:`~phongfx.explore.synth.clock.FEATURES`) that
    minimize the squared relative error of the proxy's period against ``periods`` (ns),
    one per netlist.  The critical path depends on the coefficients, so the fit alternates:
    each round takes every netlist's critical path under the previous round's
    coefficients (``start`` the first), fits them by
    :func:`~phongfx.explore.tables.proxy.relative_nnls`, and keeps the best round (least
    largest error)."""
    coefficients, best = dict(start), (float("inf"), dict(start))
    for _ in range(rounds):
        amounts = [critical_path(netlist, coefficients)[1] for netlist in netlists]
        worst = max(abs(sum(coefficients[k] * a[k] for k in FEATURES) / p - 1) for a, p in zip(amounts, periods))
        if worst < best[0]:
            best = (worst, dict(coefficients))
        found = relative_nnls([[a[k] for k in FEATURES] for a in amounts], periods)
        new = {k: round(float(v), 3) for k, v in zip(FEATURES, found)}
        if new == coefficients:
            break
        coefficients = new
    return best[1]


def summary(rows):
    """Per target: ``rows``, ``median`` and ``max`` of the absolute relative Fmax error."""
    result = {}
    for target in dict.fromkeys(row["target"] for row in rows):
        errors = [abs(row["error"]) for row in rows if row["target"] == target]
        result[target] = {"rows": len(errors), "median": statistics.median(errors), "max": max(errors)}
    return result


def resource_errors(rows):
    """The area proxy's largest ``|synthesized / proxy − 1|`` on ``lut4`` and ``dsp`` over the
    FPGA rows, and the median of each."""
    fpga = [row for row in rows if "lut4" in row]
    result = {}
    for key in ("lut4", "dsp"):
        errors = [abs(row[key] / row[f"proxy_{key}"] - 1) for row in fpga if row[f"proxy_{key}"]]
        result[key] = {"max": max(errors, default=0.0), "median": statistics.median(errors) if errors else 0.0}
    return result


def clock_table(selected=None, *, workdir=None, refit=False, progress=None):
    """The calibration: ``rows`` (without their netlists), the stored ``coefficients`` and
    ``error`` margins, the ``summary`` per target, the area proxy's ``resources`` errors
    against the stored :data:`~phongfx.explore.synth.proxy.RESOURCE_MARGIN`; with
    ``refit``, ``refit`` coefficients per target and the ``refit_summary`` they give."""
    rows = calibration_rows(selected, workdir=workdir, progress=progress)
    result = {"table": "clock", "freq": FREQ, "seed": SEED, "coefficients": COEFFICIENTS, "error": ERROR,
              "summary": summary(rows), "resources": resource_errors(rows), "resource_margin": RESOURCE_MARGIN}
    if refit:
        result["refit"], refitted = {}, []
        for target in dict.fromkeys(row["target"] for row in rows):
            mine = [row for row in rows if row["target"] == target]
            found = fit([row["netlist"] for row in mine], [1000 / row["fmax_mhz"] for row in mine],
                        COEFFICIENTS[target])
            result["refit"][target] = found
            for row in mine:
                ns = critical_path(row["netlist"], found)[0]
                refitted.append({"target": target, "error": (1000 / ns) / row["fmax_mhz"] - 1})
        result["refit_summary"] = summary(refitted)
    result["rows"] = [{k: v for k, v in row.items() if k != "netlist"} for row in rows]
    return result


def run_table(name, out_dir=None, refit=False, progress=None):
    """The table called ``name`` (``"clock"``); nothing is written to ``out_dir``."""
    if name not in TABLES:
        raise ValueError(f"unknown table {name!r}; valid tables: {', '.join(TABLES)}")
    return clock_table(refit=refit, progress=progress)


def _coefficients(values):
    return ", ".join(f"{k} {v:g}" for k, v in values.items())


def markdown(result):
    """Per target and point: measured and proxy Fmax, error, both critical paths; the summary."""
    lines = [f"# The clock proxy against synthesis (ECP5 LFE5U-45F seed {result['seed']} at {result['freq']} MHz; "
             f"osu018 pre-layout)", ""]
    for target, numbers in result["summary"].items():
        lines += [f"## {target}: {numbers['rows']} points, median error {numbers['median']:.1%}, "
                  f"largest {numbers['max']:.1%} (stored margin {result['error'][target]:.0%})", "",
                  f"Coefficients (ns): {_coefficients(result['coefficients'][target])}", "",
                  "| point | depth | synthesized MHz | proxy MHz | error | synthesized path | proxy path |",
                  "|---|---:|---:|---:|---:|---|---|"]
        for row in (r for r in result["rows"] if r["target"] == target):
            path = row["critical_path"] or {}
            depth = "–" if row["depth"] is None else row["depth"]
            lines.append(f"| {row['label']} | {depth} | {row['fmax_mhz']:.1f} | {row['proxy_mhz']:.1f} | "
                         f"{row['error']:+.1%} | {path.get('from', '?')} → {path.get('to', '?')} | "
                         f"{row['proxy_path']} |")
        lines.append("")
    res = result["resources"]
    lines.append(f"Area proxy on ECP5: LUT4 error median {res['lut4']['median']:.1%}, largest {res['lut4']['max']:.1%}; "
                 f"DSP median {res['dsp']['median']:.1%}, largest {res['dsp']['max']:.1%} (stored margins "
                 f"{_coefficients(result['resource_margin'])}).")
    if "refit" in result:
        for target, values in result["refit"].items():
            numbers = result["refit_summary"][target]
            lines.append(f"* Refitted now, {target}: {_coefficients(values)} (median {numbers['median']:.1%}, "
                         f"largest {numbers['max']:.1%}).")
    return "\n".join(lines) + "\n"


def to_json(result):
    return json.dumps(result, indent=2, ensure_ascii=False, default=float)

