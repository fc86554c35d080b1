"""``phongfx tables proxy``: the tool-free area proxy against standard-cell synthesis.

:func:`phongfx.explore.synth.proxy.proxy_area` prices the bits of a block's RTLIL
(:func:`~phongfx.explore.synth.proxy.rtlil_features`: a multiplier by the product of its
operand widths, adders, comparators, multiplexers, logic and registers by their width,
ROMs by words × bits) with one coefficient per kind, in µm².  The coefficients
(:data:`~phongfx.explore.synth.proxy.AREA_COEFFICIENTS`) were fitted by :func:`fit` to
the real flow (:mod:`phongfx.explore.synth.asic`) on :data:`POINTS`: every registry block at
its defaults and the datapaths at narrower widths too.  This table reruns that
comparison: per point, the synthesized area, the proxy's, the error, and whether the
proxy ranks the points as synthesis does; with ``refit`` it also fits afresh, so the
stored coefficients can be checked against the tools of the day.
"""

import json
import sys

import numpy as np

from phongfx.core.registry import block_names, get_block

from phongfx.explore.synth.proxy import AREA_COEFFICIENTS, FEATURES, rtlil_features, rtlil_of
from phongfx.explore.synth.fpga import synth

__all__ = ["TABLES", "POINTS", "DATAPATHS", "relative_nnls", "fit", "calibration_rows", "proxy_table", "run_table", "markdown",
           "to_json"]

TABLES = ("proxy",)
#: Lyon's whole datapaths: the proxy's error target (15%) is stated for them.
DATAPATHS = ("fig7", "fig8", "halfway_datapath")


def _narrow(name):
    """A narrower configuration of datapath ``name`` (10 → 7 fraction bits in the vectors),
    so that the fit sees width move within one block."""
    block = get_block(name)
    return block.config.replace(vec_frac=7)


#: (label, block, config or None for the defaults) the coefficients are fitted on.
POINTS = tuple((name, name, None) for name in block_names()) + tuple(
    (f"{name} vec_frac=7", name, _narrow) for name in DATAPATHS)


def relative_nnls(features, targets):
    """Non-negative ``x`` minimizing the squared *relative* error of ``features @ x``
    against ``targets`` (so that a small target counts as much as a large one);
    Lawson–Hanson active set.  Also the clock proxy's fit (:mod:`.clock`)."""
    a = np.asarray(features, dtype=float) / np.asarray(targets, dtype=float)[:, None]
    b = np.ones(len(a))
    passive = np.zeros(a.shape[1], dtype=bool)
    x = np.zeros(a.shape[1])
    for _ in range(10 * a.shape[1]):
        w = a.T @ (b - a @ x)
        if passive.all() or w[~passive].max() <= 1e-12:
            break
        passive[np.argmax(np.where(passive, -np.inf, w))] = True
        while True:
            z = np.zeros_like(x)
            z[passive] = np.linalg.lstsq(a[:, passive], b, rcond=None)[0]
            if (z[passive] > 0).all():
                x = z
                break
            bad = passive & (z <= 0)
            step = np.min(x[bad] / (x[bad] - z[bad]))
            x = x + step * (z - x)
            passive &= x > 1e-12
    return x


def fit(features, areas):
    """Non-negative coefficients, one per :data:`~phongfx.explore.synth.proxy.FEATURES`,
    minimizing the squared relative error of ``features @ c`` against ``areas``
    (:func:`relative_nnls`)."""
    return dict(zip(FEATURES, (float(v) for v in relative_nnls(features, areas))))


def _price(features, coefficients):
    return float(sum(coefficients[k] * features[k] for k in FEATURES))


def _stored(library):
    """The stored coefficients of ``library`` (a name or Liberty file), None if it has none."""
    from phongfx.explore.synth.asic import library_name

    return AREA_COEFFICIENTS.get(library_name(library))


def calibration_rows(points=POINTS, *, library="osu018", workdir=None, progress=None, coefficients=None):
    """One row per point: ``label``, ``block``, its :func:`rtlil_features`, the synthesized
    ``area_um2`` and ``fmax_mhz``, the ``proxy_um2`` of ``coefficients`` (default: the
    stored ones; a library without any gets none, nor an ``error``) and the ``error``
    (proxy / synthesis − 1)."""
    coefficients = coefficients or _stored(library)
    rows = []
    for index, (label, name, config) in enumerate(points):
        if progress is not None:
            progress(index, len(points), label)
        block = get_block(name, config(name) if callable(config) else config)
        result = synth(name, config=block.config, target="asic", device=library, workdir=workdir)
        features = rtlil_features(rtlil_of(block))
        row = {"label": label, "block": name, "features": features, "area_um2": result["area_um2"],
               "fmax_mhz": result["fmax_mhz"]}
        if coefficients:
            proxy = _price(features, coefficients)
            row.update(proxy_um2=proxy, error=proxy / result["area_um2"] - 1)
        rows.append(row)
    return rows


def _priced(rows, coefficients):
    return [{**r, "proxy_um2": _price(r["features"], coefficients),
             "error": _price(r["features"], coefficients) / r["area_um2"] - 1} for r in rows]


def _ranking_agrees(rows):
    """Pairs of rows that the proxy orders as synthesis does, and all pairs."""
    pairs = [(a, b) for i, a in enumerate(rows) for b in rows[i + 1:]]
    agree = sum((a["proxy_um2"] - b["proxy_um2"]) * (a["area_um2"] - b["area_um2"]) > 0 for a, b in pairs)
    return int(agree), len(pairs)


def proxy_table(points=POINTS, *, library="osu018", workdir=None, refit=False, progress=None):
    """The calibration result: ``rows``, ``coefficients`` (stored), the ``refit`` ones
    (when asked), the largest error over all points and over :data:`DATAPATHS`, and
    the rank agreement over all points and over the datapaths' points."""
    from phongfx.explore.synth.asic import library_name

    stored = _stored(library)
    if stored is None and not refit:
        raise ValueError(f"library {library_name(library)!r} has no stored area proxy coefficients "
                         f"(calibrated: {', '.join(AREA_COEFFICIENTS)}): ask for refit (--refit) to fit them")
    rows = calibration_rows(points, library=library, workdir=workdir, progress=progress)
    found = fit([[r["features"][k] for k in FEATURES] for r in rows], [r["area_um2"] for r in rows]) if refit else None
    rows = _priced(rows, stored or found)
    datapaths = [r for r in rows if r["block"] in DATAPATHS]
    result = {"table": "proxy", "library": library_name(library), "coefficients": dict(stored or found),
              "stored": stored is not None, "rows": rows, "max_error": max(abs(r["error"]) for r in rows),
              "max_error_datapaths": max((abs(r["error"]) for r in datapaths), default=None),
              "ranking": _ranking_agrees(rows), "ranking_datapaths": _ranking_agrees(datapaths)}
    if refit:
        result["refit"] = found
        refitted = _priced(rows, found)
        result["refit_max_error"] = max(abs(r["error"]) for r in refitted)
        result["refit_max_error_datapaths"] = max((abs(r["error"]) for r in refitted
                                                   if r["block"] in DATAPATHS), default=None)
    return result


def run_table(name, out_dir=None, library="osu018", refit=False, points=POINTS):
    """The table called ``name`` (``"proxy"``) over ``points`` (a subset of :data:`POINTS`
    for a smoke run); nothing is written to ``out_dir``."""
    if name not in TABLES:
        raise ValueError(f"unknown table {name!r}; valid tables: {', '.join(TABLES)}")

    def progress(index, total, label):
        print(f"proxy: synthesizing point {index + 1} of {total} ({label}, {library}; cached runs are "
              f"instant)", file=sys.stderr, flush=True)
    return proxy_table(points, library=library, refit=refit, progress=progress)


def _share(value):
    return "–" if value is None else f"{value:.1%}"  # no datapath among the points


def markdown(result):
    """Per point: synthesized area, proxy, error; then the largest errors and the ranking."""
    source = "stored" if result.get("stored", True) else "fitted now: none stored for this library"
    lines = [f"# The area proxy against standard-cell synthesis ({result['library']})", "",
             f"Coefficients (µm² per bit, {source}): " + ", ".join(f"{k} {v:.1f}" for k, v in result["coefficients"].items()),
             "", "| point | synthesized µm² | proxy µm² | error |", "|---|---:|---:|---:|"]
    for r in result["rows"]:
        lines.append(f"| {r['label']} | {r['area_um2']:,.0f} | {r['proxy_um2']:,.0f} | {r['error']:+.1%} |")
    agree, pairs = result["ranking"]
    dagree, dpairs = result["ranking_datapaths"]
    datapaths = result["max_error_datapaths"]
    lines += ["", f"* Largest error: {result['max_error']:.1%} over every point; "
              + (f"{datapaths:.1%} over the datapaths ({', '.join(DATAPATHS)})." if datapaths is not None
                 else f"no datapath ({', '.join(DATAPATHS)}) among the points."),
              f"* Ranking: the proxy orders {agree} of {pairs} pairs of points as synthesis does; "
              f"{dagree} of {dpairs} pairs of datapath points."]
    if "refit" in result:
        lines.append("* Refitted now: " + ", ".join(f"{k} {v:.1f}" for k, v in result["refit"].items())
                     + f" (largest error {result['refit_max_error']:.1%} over every point, "
                       f"{_share(result['refit_max_error_datapaths'])} over the datapaths)")
    return "\n".join(lines) + "\n"


def to_json(result):
    return json.dumps(result, indent=2, ensure_ascii=False)
