"""The pixel-rate section of the compile report page (:mod:`phongfx.deliver.page`): what
the manifest records of each candidate's speed, as a table and a chart, and the chosen
design's timing and fit to its part.

The compiler prices every architecture of a method (pipeline depth, interval) and keeps in
the method's ``cost`` the one it was priced at: the cheapest that meets the pixel rate and
clock asked, or the default architecture when nothing is asked; where none meets, the
cost also holds ``fastest``, the highest pixel rate any architecture reached
(``phongfx.explore.compile.architecture.pick``).  So the front shown is those points
alone, one or two per method, not every architecture priced (``architectures_priced``
counts those); an infeasible method has no cost and no point.  The chart
(:func:`phongfx.deliver.chart.scatter`) puts pixel rate (Mpixel/s) against cost, with the
pixel rate asked as a vertical line.
"""

import math

from phongfx.core.words import plural

from .chart import Point, scatter
from .markup import Html, cost_text, esc, heading, number, pairs, table

__all__ = ["architecture_text", "speed_points", "speed_section"]

#: The chart's legend: what each point kind means on this chart.
LEGEND = {"chosen": "chosen", "feasible": "meets the speed asked", "infeasible": "too slow, or over the part",
          "other": "its fastest architecture"}


def architecture_text(architecture):
    """``depth 2, interval 1, shared inputs`` of an architecture dict (depth 0, interval 1
    and shared inputs where a key is missing: the compiler's default)."""
    a = {"pipeline": 0, "interval": 1, "share": True, **(architecture or {})}
    return f"depth {a['pipeline']}, interval {a['interval']}, {'shared' if a['share'] else 'per-copy'} inputs"


def _finite(*values):
    return all(isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) for v in values)


def _verdict(cost):
    if cost.get("why_not") == "fit":
        return "over the part"
    return {True: "met", False: "too slow", None: "—"}[cost.get("met")]


def _fastest(cost):
    """A cost's ``fastest`` architecture when it is another than the one priced, else ``{}``."""
    fastest = cost.get("fastest") or {}
    return {} if fastest.get("architecture") == cost.get("architecture") else fastest


def speed_points(data):
    """The chart's points: each costed method at the architecture it was priced at, and its
    fastest where recorded; kinds as in :data:`LEGEND`."""
    points = []
    for name, r in (data.get("methods") or {}).items():
        cost = r.get("cost") or {}
        if _finite(cost.get("pixel_rate_mpx"), cost.get("cost")):
            kind = ("chosen" if name == data.get("chosen")
                    else "feasible" if cost.get("met") is not False and cost.get("why_not") is None else "infeasible")
            label = f"{name} ({architecture_text(cost.get('architecture')).rsplit(',', 1)[0]})"
            points.append(Point(float(cost["pixel_rate_mpx"]), float(cost["cost"]), label, kind,
                                f"{label}: {number(cost['pixel_rate_mpx'])} Mpixel/s, {cost_text(cost)}"))
        fastest = _fastest(cost)
        if _finite(fastest.get("pixel_rate_mpx"), fastest.get("cost")):
            label = f"{name} fastest ({architecture_text(fastest.get('architecture')).rsplit(',', 1)[0]})"
            points.append(Point(float(fastest["pixel_rate_mpx"]), float(fastest["cost"]), label, "other",
                                f"{label}: {number(fastest['pixel_rate_mpx'])} Mpixel/s"))
    return points


def _rows(data):
    rows, classes = [], []
    for name, r in (data.get("methods") or {}).items():
        cost = r.get("cost")
        if not cost:
            continue
        for what, c in (("priced", cost), ("fastest", _fastest(cost))):
            if not c:
                continue
            rows.append([name, what, architecture_text(c.get("architecture")), number(c.get("clock_mhz")),
                         c.get("clock_source") or "—", number(c.get("pixel_rate_mpx")), _verdict(c),
                         cost_text({**cost, **c}) if c.get("cost") is not None else "—",
                         number(c.get("latency_ns"))])
            classes.append("chosen" if name == data.get("chosen") and what == "priced" else None)
    return rows, classes


def _timing(data):
    timing, fit = data.get("timing") or {}, data.get("fit")
    out = []
    if timing:
        missed = (f"{number(timing.get('missed_by_mhz'))} MHz ({number(timing.get('missed_by_percent'))}%)"
                  if timing.get("missed_by_mhz") is not None else None)
        out.append("<h3>The chosen design's timing</h3>" + pairs([
            ("architecture", timing.get("architecture") and architecture_text(timing["architecture"])),
            ("clock", timing.get("clock_mhz") is not None and f"{number(timing['clock_mhz'])} MHz"),
            ("clock source", timing.get("clock_source")), ("clock model", timing.get("clock_model")),
            ("clock proxy's estimate", timing.get("clock_estimate_mhz") is not None
             and f"{number(timing['clock_estimate_mhz'])} MHz less a {number(100 * (timing.get('clock_margin') or 0))}% "
                 "margin"),
            ("clock required", timing.get("clock_required_mhz") is not None
             and f"{number(timing['clock_required_mhz'])} MHz"),
            ("pixel rate", timing.get("pixel_rate_mpx") is not None and f"{number(timing['pixel_rate_mpx'])} Mpixel/s"),
            ("pixel rate asked", timing.get("requirement_mpx") is not None
             and f"{number(timing['requirement_mpx'])} Mpixel/s"),
            ("met", None if timing.get("met") is None else str(timing["met"])), ("missed by", missed),
            ("latency", timing.get("latency") is not None
             and f"{timing['latency']} cycles ({number(timing.get('latency_ns'))} ns)"),
            ("critical path", (data.get("cost") or {}).get("clock_path"))]))
    if fit and fit.get("resources"):
        out.append(f"<h3>Fit to the {esc(fit.get('part'))} ({esc(fit.get('source'))}: {esc(fit.get('status'))})</h3>"
                   + table([[k, f"{r.get('need', 0):,}", f"{r.get('available', 0):,}",
                             f"±{100 * (r.get('margin') or 0):g}%"] for k, r in fit["resources"].items()],
                           ["resource", "needed", "available", "proxy's margin"]))
    return out


def speed_section(data):
    """The section's HTML, or empty text when the manifest records no speed at all."""
    rows, classes = _rows(data)
    timing = _timing(data)
    if not rows and not timing:
        return ""
    req = data.get("requirement") or {}
    asked = req.get("mpixels_per_second")
    priced = next((r["cost"].get("architectures_priced") for r in (data.get("methods") or {}).values()
                   if r.get("cost") and r["cost"].get("architectures_priced")), None)
    out = [heading("pixel-rate", "Pixel rate: the front the manifest records"),
           f"<p>Asked: {esc(f'{number(asked)} Mpixel/s' if asked else 'no pixel rate')}"
           + esc(f", a clock of {number(req['clock_mhz'])} MHz" if req.get("clock_mhz") else "")
           + ". Each method is shown at the architecture it was priced at (the cheapest meeting the speed "
             "asked, the default one when none is asked) and, where none met, its fastest"
           + esc(f"; {plural(priced, 'architecture')} priced per method" if priced else "") + ".</p>"]
    if rows:
        out.append(table(rows, ["method", "architecture", "layout", "clock (MHz)", "clock source",
                                "pixel rate (Mpixel/s)", "speed", "cost", "latency (ns)"], classes))
    points = speed_points(data)
    if points:
        unit = next(((r.get("cost") or {}).get("unit") for r in data["methods"].values() if r.get("cost")), None)
        out.append(Html(scatter(points, chart_id="pixel-rate", title="Pixel rate against cost",
                                x_title="pixel rate (Mpixel/s)", y_title=f"cost ({unit or 'cost units'})",
                                vline=(asked, f"asked {number(asked)}") if _finite(asked) else None,
                                legend=LEGEND)))
    elif rows:
        out.append("<p>No pixel rate is recorded (no clock estimate for this target: --synth measures it).</p>")
    return "\n".join(out + timing)
