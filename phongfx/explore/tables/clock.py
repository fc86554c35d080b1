"""``phongfx tables clock``: the tool-free clock proxy against synthesis, per target and depth.

:func:`phongfx.explore.synth.clock.proxy_clock` prices the slowest register-to-register
stage of a design's RTLIL; its coefficients
(:data:`~phongfx.explore.synth.clock.COEFFICIENTS`) were fitted by :func:`fit` to the
synthesized clock of every point of :func:`points`: every datapath the compiler can
choose (Lyon's Figures 7, 8 and 5, the Blinn–Phong, spherical and conventional units) at
every pipeline depth they take, and whole shaders (:data:`SHADERS`: Figure 7 holding two lights
at every depth, in turns, and with the two-light scene's blend; two Phong or Blinn–Phong copies,
one per light), on ECP5 (nextpnr's Fmax on the LFE5U-45F, seed 1, 150 MHz asked) and on osu018
(Yosys with ABC's buffering and sizing, OpenSTA pre-layout).  This table reruns that comparison: per
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
from phongfx.core.words import plural

from phongfx.explore.progress import Candidates
from phongfx.explore.synth.clock import (COEFFICIENTS, ERROR, FEATURES, LIBRARY_COEFFICIENTS, LIBRARY_ERROR,
                                        LIBRARY_MARGIN, MARGIN, clock_netlist, critical_path, promise_margin)
from phongfx.explore.synth.proxy import RESOURCE_MARGIN, rtlil_cost, rtlil_of
from phongfx.explore.tables.proxy import relative_nnls

__all__ = ["TABLES", "NAMES", "DEPTHS", "TARGETS", "FREQ", "SEED", "MARGIN_FROM_LUT4", "SHADERS", "points",
           "calibration_rows", "fit", "summary", "resource_errors", "fit_lut4", "clock_table", "run_table", "markdown", "to_json"]

TABLES = ("clock",)
#: Every unit the compiler can choose; a unit without a depth has one row.
NAMES = ("fig7", "fig8", "halfway_datapath", "blinn", "spherical", "conventional")
DEPTHS = tuple(range(MAX_PIPELINE + 1))
#: (target, device) measured: the FPGA the compiler targets by default, and osu018.
TARGETS = (("ecp5", "45k"), ("asic", "osu018"))
#: nextpnr's clock constraint (MHz) and placement seed for every point.
FREQ = 150
SEED = 1


def _two(unit, interval=1):
    """Two lights on copies of one-light ``unit`` (at its defaults), taking ``interval`` turns."""
    config = get_block(unit).config
    return ShaderConfig(unit=unit, units=(config, config), interval=interval,
                        blend=BlendConfig(lights=2, diff="1.15", spec="1.15"))


def _scene_blend(config):
    """``config`` with the blend of the two-light example scene (5 coefficient bits, its
    intensities): a gate whose select steers every bit of a wide product, the path that
    limits the compiler's choice for that scene at depth 4."""
    blend = config.blend.replace(coef_frac=5, diffuse=(((0.42,) * 3, (0.18,) * 3),),
                                 specular=(((0.28,) * 3, (0.12,) * 3),))
    return config.replace(blend=blend)


#: Whole shaders beside the blocks, at the depths given (None: every one): where the blend,
#: the light turns and the nets fanned out to every copy (the normal, the turn counter's
#: enable) set the clock rather than one datapath's stage.
SHADERS = (("shader blinn×2", _two("blinn"), ()),
           ("shader conventional×2", _two("conventional"), (0, 4)),
           ("shader conventional i2", _two("conventional", 2), (0, 4)))


def _configs():
    yield "shader", "shader", get_block("shader").config, None
    for label, config, depths in SHADERS:
        yield label, "shader", config, depths
    yield "shader i2", "shader", get_block("shader").config.replace(interval=2), (0, 2, 4)
    yield "shader i2 coef 5", "shader", _scene_blend(get_block("shader").config.replace(interval=2)), (4,)
    for name in NAMES:
        yield name, name, get_block(name).config, None


def _deepen(config, depth):
    try:
        return config.replace(pipeline=depth)
    except (TypeError, ValueError):
        return None


def points(depths=DEPTHS):
    """(label, block name, config, depth) of every calibration point: each datapath and
    shader at every depth it takes (one row, depth None, for a unit without one; a whole
    shader of :data:`SHADERS` at its own depths)."""
    result = []
    for label, name, config, own in _configs():
        if _deepen(config, 0) is None or own == ():
            result.append((label, name, config, None))
            continue
        result.extend((label, name, _deepen(config, d), d) for d in (depths if own is None else own))
    return result


def _where(target, device):
    """The name a calibration is filed under: the target, or on ``asic`` a library other than
    osu018 by its :func:`~phongfx.explore.synth.asic.library_name`."""
    from phongfx.explore.synth.asic import library_name

    if target != "asic" or device in (None, "osu018"):
        return target
    return library_name(device)


def _stored(where):
    """The stored coefficients, error and promise margin of calibration ``where``, or
    osu018's coefficients (a starting point for a fit), no error and no margin."""
    if where in COEFFICIENTS:
        return COEFFICIENTS[where], ERROR[where], MARGIN[where]
    return (LIBRARY_COEFFICIENTS.get(where, COEFFICIENTS["asic"]), LIBRARY_ERROR.get(where),
            LIBRARY_MARGIN.get(where, 0.0))


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
            netlist = clock_netlist(block, target)
            where = _where(target, device)
            coefficients, _, margin = _stored(where)
            ns, amounts, path = critical_path(netlist, coefficients)
            row = {"label": label, "block": name, "depth": depth, "target": target, "device": device, "where": where,
                   "interval": getattr(config, "interval", 1),
                   "fmax_mhz": result["fmax_mhz"], "critical_path": result.get("critical_path"),
                   "proxy_mhz": 1000 / ns, "amounts": amounts, "proxy_path": f"{path[0]} → {path[-1]}",
                   "error": (1000 / ns) / result["fmax_mhz"] - 1, "promise_mhz": (1000 / ns) * (1 - margin),
                   "promise_error": (1000 / ns) * (1 - margin) / result["fmax_mhz"] - 1, "netlist": netlist}
            if target != "asic":
                cost = rtlil_cost(rtlil_of(block))
                row.update({"lut4": result["lut4"] + 2 * result["carry"], "dsp": result["dsp"],
                            "proxy_lut4": cost["lut4"], "proxy_dsp": cost["dsp"], "proxy_lut": cost["lut"],
                            "proxy_carry_bits": cost["carry_bits"]})
            rows.append(row)
    return rows


def fit(netlists, periods, start, rounds=24):
    """Non-negative ns per feature (:data:`~phongfx.explore.synth.clock.FEATURES`) that
    minimize the squared relative error of the proxy's period against ``periods`` (ns),
    one per netlist.  The critical path depends on the coefficients, so the fit alternates:
    each round takes every netlist's critical path under the current coefficients
    (``start`` the first), fits them by :func:`~phongfx.explore.tables.proxy.relative_nnls`,
    and moves halfway to that fit (after the first round: taken whole, two fits can pick
    each other's paths and swap for ever), keeping the best round (least spread of the
    measured over the estimated period)."""
    coefficients, best = dict(start), (float("inf"), dict(start))
    for round_ in range(rounds):
        amounts = [critical_path(netlist, coefficients)[1] for netlist in netlists]
        ratios = [p / sum(coefficients[k] * a[k] for k in FEATURES) for a, p in zip(amounts, periods)]
        worst = 1 - min(ratios) / max(ratios)  # how far below synthesis the promise may be
        if worst < best[0]:
            best = (worst, dict(coefficients))
        found = relative_nnls([[a[k] for k in FEATURES] for a in amounts], periods)
        new = {k: round(float(v) if round_ == 0 else (coefficients[k] + float(v)) / 2, 3)
               for k, v in zip(FEATURES, found)}
        if new == coefficients:
            break
        coefficients = new
    return best[1]


def summary(rows):
    """Per target (or library: a row's ``where``): ``rows``, ``median`` and ``max`` of the
    absolute relative Fmax error of the fitted estimate; ``margin``, the share of it to give
    up so that no row's estimate is above its synthesized clock (:func:`promise_margin`);
    with the rows' stored promises, ``misses`` (rows whose promise is above synthesis) and
    ``promise_max``, the largest absolute error of the promise."""
    result = {}
    for target in dict.fromkeys(row.get("where", row["target"]) for row in rows):
        mine = [row for row in rows if row.get("where", row["target"]) == target]
        errors = [abs(row["error"]) for row in mine]
        result[target] = {"rows": len(errors), "median": statistics.median(errors), "max": max(errors),
                          "margin": promise_margin([row["error"] for row in mine])}
        if all("promise_error" in row for row in mine):
            result[target].update(misses=sum(row["promise_error"] > 1e-9 for row in mine),
                                  promise_max=max(abs(row["promise_error"]) for row in mine))
    return result


#: The smallest design (synthesized LUT4 sites) whose LUT4 error sets the margin: a device
#: fit is a question for large designs, and a small one's error is a large share of little.
MARGIN_FROM_LUT4 = 1000


def resource_errors(rows, weights=None):
    """The area proxy's ``|synthesized / proxy − 1|`` on ``lut4`` and ``dsp`` over the FPGA
    rows of :data:`MARGIN_FROM_LUT4` sites or more: ``max`` and ``median`` of each, and the
    largest over every row (``max_all``); ``weights`` (``{"lut", "carry_bits"}``) price the
    LUT4 sites afresh instead of the stored ones."""
    fpga = [row for row in rows if "lut4" in row]
    result = {}
    for key in ("lut4", "dsp"):
        errors = []
        for row in fpga:
            proxy = row[f"proxy_{key}"]
            if key == "lut4" and weights is not None:
                proxy = weights["lut"] * row["proxy_lut"] + weights["carry_bits"] * row["proxy_carry_bits"]
            if proxy:
                errors.append((row["lut4"] >= MARGIN_FROM_LUT4, abs(row[key] / proxy - 1)))
        large = [e for big, e in errors if big]
        result[key] = {"max": max(large, default=0.0), "median": statistics.median(large) if large else 0.0,
                       "max_all": max((e for _, e in errors), default=0.0)}
    return result


def fit_lut4(rows):
    """LUT4 sites per logic bit and per carry bit (``{"lut", "carry_bits"}``) that fit the
    synthesized LUT4 sites of the FPGA ``rows`` (:func:`~phongfx.explore.tables.proxy.relative_nnls`)."""
    fpga = [row for row in rows if "lut4" in row]
    found = relative_nnls([[row["proxy_lut"], row["proxy_carry_bits"]] for row in fpga], [row["lut4"] for row in fpga])
    return {"lut": round(float(found[0]), 3), "carry_bits": round(float(found[1]), 3)}


def clock_table(selected=None, *, targets=TARGETS, workdir=None, refit=False, progress=None):
    """The calibration: ``rows`` (without their netlists), the stored ``coefficients`` and
    ``error`` margins, the ``summary`` per target, the area proxy's ``resources`` errors
    against the stored :data:`~phongfx.explore.synth.proxy.RESOURCE_MARGIN`; with
    ``refit``, ``refit`` coefficients per target and the ``refit_summary`` they give."""
    rows = calibration_rows(selected, targets=targets, workdir=workdir, progress=progress)
    wheres = dict.fromkeys(row["where"] for row in rows)
    result = {"table": "clock", "freq": FREQ, "seed": SEED,
              "coefficients": {w: _stored(w)[0] for w in wheres}, "error": {w: _stored(w)[1] for w in wheres},
              "margin": {w: _stored(w)[2] for w in wheres},
              "summary": summary(rows), "resources": resource_errors(rows), "resource_margin": RESOURCE_MARGIN}
    if refit:
        result["refit"], refitted = {}, []
        for target in wheres:
            mine = [row for row in rows if row["where"] == target]
            found = fit([row["netlist"] for row in mine], [1000 / row["fmax_mhz"] for row in mine],
                        _stored(target)[0])
            result["refit"][target] = found
            errors = [(1000 / critical_path(row["netlist"], found)[0]) / row["fmax_mhz"] - 1 for row in mine]
            margin = promise_margin(errors)
            refitted.extend({"target": target, "error": e, "promise_error": (1 + e) * (1 - margin) - 1}
                            for e in errors)
        result["refit_summary"] = summary(refitted)
        if any("lut4" in row for row in rows):
            result["refit_lut4"] = fit_lut4(rows)
            result["refit_resources"] = resource_errors(rows, result["refit_lut4"])
    result["rows"] = [{k: v for k, v in row.items() if k != "netlist"} for row in rows]
    return result


def run_table(name, out_dir=None, refit=False, progress=None, selected=None, device=None):
    """The table called ``name`` (``"clock"``) over ``selected`` points (default
    :func:`points`; ``(label, block, config or None for its defaults, depth)``, fewer for a
    smoke run); nothing is written to ``out_dir``.  With ``device`` (a library name or
    Liberty file) only the standard-cell flow on it is measured."""
    if name not in TABLES:
        raise ValueError(f"unknown table {name!r}; valid tables: {', '.join(TABLES)}")
    targets = TARGETS if device is None else (("asic", device),)
    return clock_table(selected, targets=targets, refit=refit, progress=progress)


def _margin(error):
    return "not calibrated: osu018's coefficients" if error is None else f"stored error {error:.0%}"


def _coefficients(values):
    return ", ".join(f"{k} {v:g}" for k, v in values.items())


def _promise(numbers, stored):
    text = f"margin needed {numbers['margin']:.1%} (stored {stored:.1%})"
    if "misses" in numbers:
        text += (f": the promise is above synthesis on {plural(numbers['misses'], 'point')}, at most "
                 f"{numbers['promise_max']:.1%} off")
    return text


def markdown(result):
    """Per target and point: measured, fitted and promised Fmax, errors, both critical paths;
    the summary."""
    lines = [f"# The clock proxy against synthesis (ECP5 LFE5U-45F seed {result['seed']} at {result['freq']} MHz; "
             f"osu018 pre-layout)", ""]
    for target, numbers in result["summary"].items():
        lines += [f"## {target}: {plural(numbers['rows'], 'point')}, median error {numbers['median']:.1%}, "
                  f"largest {numbers['max']:.1%} ({_margin(result['error'][target])}); "
                  f"{_promise(numbers, result['margin'][target])}", "",
                  f"Coefficients (ns): {_coefficients(result['coefficients'][target])}", "",
                  "| point | depth | interval | synthesized MHz | proxy MHz | error | promise MHz | promise error | "
                  "synthesized path | proxy path |",
                  "|---|---:|---:|---:|---:|---:|---:|---:|---|---|"]
        for row in (r for r in result["rows"] if r.get("where", r["target"]) == target):
            path = row["critical_path"] or {}
            depth = "–" if row["depth"] is None else row["depth"]
            lines.append(f"| {row['label']} | {depth} | {row.get('interval', 1)} | {row['fmax_mhz']:.1f} | "
                         f"{row['proxy_mhz']:.1f} | {row['error']:+.1%} | {row['promise_mhz']:.1f} | "
                         f"{row['promise_error']:+.1%} | {path.get('from', '?')} → {path.get('to', '?')} | "
                         f"{row['proxy_path']} |")
        lines.append("")
    res = result["resources"]
    if any("lut4" in row for row in result["rows"]):
        lines.append(f"Area proxy on ECP5, designs of {MARGIN_FROM_LUT4} LUT4 sites or more: LUT4 error median "
                 f"{res['lut4']['median']:.1%}, largest {res['lut4']['max']:.1%} ({res['lut4']['max_all']:.1%} over "
                 f"every design); DSP median {res['dsp']['median']:.1%}, largest {res['dsp']['max']:.1%} (stored "
                 f"margins {_coefficients(result['resource_margin'])}).")
    if "refit" in result:
        for target, values in result["refit"].items():
            numbers = result["refit_summary"][target]
            lines.append(f"* Refitted now, {target}: {_coefficients(values)} (median {numbers['median']:.1%}, "
                         f"largest {numbers['max']:.1%}; promise margin {numbers['margin']:.1%}, the promise at "
                         f"most {numbers['promise_max']:.1%} below synthesis).")
        if "refit_lut4" in result:
            lines.append(f"* LUT4 sites per bit refitted now: {_coefficients(result['refit_lut4'])} (largest error "
                         f"{result['refit_resources']['lut4']['max']:.1%}).")
    return "\n".join(lines) + "\n"


def to_json(result):
    return json.dumps(result, indent=2, ensure_ascii=False, default=float)

