"""The compile report page: ``DIR/report.html``, one self-contained HTML file of a compiled folder.

Built from the folder's manifest dict (``phongfx.explore.compile.emit`` writes both) and
the PNGs beside it, the page shows, top to bottom:

* a summary: the scene, the chosen design, its error against the requirement, its cost,
  pixel rate, certificate and RTL check (or why nothing was chosen, with the manifest's hint);
* the requirement: max error in display levels and against what, the pixel rate and clock
  asked, the cost model, the search (certified or sampled) and what it measured;
* the chosen design and why: its widths, cost, error, timing, fit, its default widths and
  the conventional Phong baseline, a tie, the witness rounds and the minimality proof;
* every candidate: a table (widths, error, cost, pixel rate, why not chosen or why
  infeasible), the methods rejected before the search, and a cost/error chart
  (:func:`phongfx.deliver.chart.scatter`: an infeasible method at its default widths);
* the pixel-rate front as far as the manifest records it: each candidate's priced
  architecture (and its fastest, where that was recorded), as a table and a chart;
* the certificate (bound, method, parts, seconds) and the witness (error, unrounded,
  found by, its replay command);
* the error maps and frames (the contact sheets, else each frame's PNG, embedded), with
  their captions and the error maps' white level;
* the RTL check, the testbench and the flow files; the shipped top's ports and its input
  contract (:func:`phongfx.deliver.contract.contract_lines`).

A section whose data the manifest lacks is left out.  No network: the pictures are
``data:`` URIs, the charts inline SVG, the style inline, no script; every text from the
manifest goes through ``html.escape``.
"""

import math
import os
import re

from phongfx.core.files import atomic_write
from phongfx.core.methods import BASELINE

from .chart import Point, scatter
from .contract import contract_lines
from .rates import speed_section
from .markup import Html, cost_text, esc, heading, levels, number, pairs, params_text, png_data_uri, table

__all__ = ["REPORT_NAME", "report_html", "write_report", "candidate_points"]

#: The page's file name in a compiled folder.
REPORT_NAME = "report.html"
#: The pictures embedded: (subfolder, heading); its ``sheet.png``, else each of its PNGs.
PICTURES = (("error", "Error maps"), ("frames", "Frames"))
#: A section heading of :func:`~phongfx.deliver.markup.heading`: its anchor and (escaped) title.
HEADING = re.compile(r'<h2 id="([^"]*)">(.*?)</h2>')
STYLE = """
body { font-family: sans-serif; margin: 2em auto; max-width: 1100px; padding: 0 1em; color: #222; line-height: 1.4 }
h1 { font-size: 1.6em } h2 { border-bottom: 1px solid #ccc; margin-top: 2em }
table { border-collapse: collapse; margin: 0.6em 0 } td, th { border: 1px solid #ccc; padding: 0.25em 0.6em;
  text-align: left; vertical-align: top } th { background: #f2f2f2 }
tr.chosen td { background: #fde8e8; font-weight: bold }
code, pre { background: #f6f6f6 } pre { padding: 0.5em; white-space: pre-wrap }
.summary { background: #f4f8fc; border: 1px solid #c9dbee; padding: 0.6em 1.2em }
.bad { color: #b00000; font-weight: bold } .good { color: #106010; font-weight: bold }
nav ul { columns: 2; margin: 0.5em 0 }
img { max-width: 100%; border: 1px solid #ddd } figcaption { color: #555; font-size: 0.9em }
"""


def _against(requirement):
    return "true Phong" if requirement.get("against") == "phong" else "the method's own float form"


def _summary(data):
    req = data.get("requirement") or {}
    asked = f"≤ {levels(req.get('max_error_levels'))} against {_against(req)}"
    if data.get("chosen") is None:
        why = (data.get("refused") or {}).get("text") or []
        hint = (data.get("hint") or {}).get("text") or []
        return (f"<p>No design meets the requirement ({esc(asked)}) on the scene {esc(data.get('scene'))}.</p>"
                + "".join(f"<p>{esc(line)}</p>" for line in why)
                + "".join(f"<p>hint: {esc(line)}</p>" for line in hint))
    error, witness, timing = data.get("error") or {}, data.get("witness") or {}, data.get("timing") or {}
    items = [f"The compiler chose <b>{esc(data['chosen'])}</b> (module <code>{esc(data.get('module'))}</code>) "
             f"for the scene <b>{esc(data.get('scene'))}</b>: requirement {esc(asked)}."]
    worst = witness.get("error_levels", error.get("max"))
    items.append(f"Max error {esc(levels(worst))} over the scene's domain (frames "
                 f"{esc(levels(error.get('frames_max')))}), mean {esc(number(error.get('mean'), '.4f'))}; "
                 f"cost {esc(cost_text(data.get('cost')))}.")
    if timing.get("pixel_rate_mpx") is not None:
        met = "" if timing.get("met") is None else (" (met)" if timing["met"] else " (NOT MET)")
        items.append(f"Speed: {esc(number(timing['pixel_rate_mpx']))} Mpixel/s at "
                     f"{esc(number(timing.get('clock_mhz')))} MHz ({esc(timing.get('clock_source'))}){esc(met)}.")
    certificate = data.get("certificate")
    items.append(_certified(certificate) + ".")
    check = data.get("rtl_check")
    if check:
        css = "good" if check.get("mismatches") == 0 else "bad"
        items.append(f'RTL check of frame {esc(check.get("frame"))}: <span class="{css}">'
                     f"{esc(check.get('mismatches'))} mismatches</span> in {esc(check.get('pixels'))} pixels.")
    else:
        items.append("RTL check: not run (--no-check).")
    return '<div class="summary">' + "".join(f"<p>{item}</p>" for item in items) + "</div>"


def _certified(certificate):
    if not certificate:
        return 'Error <span class="bad">not certified</span> (--sampled: chosen by the measured error alone)'
    if certificate.get("certified"):
        return (f'Error <span class="good">certified</span> ≤ {esc(number(certificate.get("bound_levels"), ".4g"))} '
                f"levels ({esc(certificate.get('method'))})")
    return f'Error <span class="bad">not certified</span>: {esc(certificate.get("why"))}'


def _requirement(data):
    req, evaluation = data.get("requirement") or {}, data.get("evaluation") or {}
    return heading("requirement", "Requirement") + pairs([
        ("scene", data.get("scene")), ("scene file", data.get("path")),
        ("max error", f"{levels(req.get('max_error_levels'))} (display levels at out_r, out_g, out_b)"),
        ("against", _against(req)),
        ("pixel rate asked", req.get("mpixels_per_second") and f"{number(req['mpixels_per_second'])} Mpixel/s"),
        ("clock asked", req.get("clock_mhz") and f"{number(req['clock_mhz'])} MHz"),
        ("cost model", data.get("cost_model")), ("search", data.get("search")),
        ("frames measured", evaluation.get("frames")),
        ("domain samples", evaluation.get("domain_samples") and f"{evaluation['domain_samples']:,}"),
        ("width points measured", evaluation.get("points_measured"))])


def _chosen(data):
    if data.get("chosen") is None:
        return ""
    error, default = data.get("error") or {}, data.get("default_widths") or {}
    out = [heading("chosen", "The chosen design and why"), pairs([
        ("method", data["chosen"]), ("module", data.get("module")), ("block", data.get("block")),
        ("widths", params_text(data.get("widths"))), ("cost", cost_text(data.get("cost"))),
        ("max error", f"{levels(error.get('max'))} (frames {number(error.get('frames_max'))}, domain "
                      f"{number(error.get('domain_max'))} on {number(error.get('domain_points'))} points)"),
        ("max unrounded", number(error.get("max_unrounded"))), ("mean error", number(error.get("mean"), ".4f")),
        ("latency", data.get("latency") is not None and f"{data['latency']} cycles"),
        ("default widths", default and f"max {levels(default.get('max'))}, {cost_text(default.get('cost'))}"
                                       + (" (misses the requirement)" if _misses(default, data) else "")),
        ("against conventional Phong", _baseline(data)), ("tie", _tie(data.get("tie")))])]
    rounds = data.get("witness_rounds") or []
    if rounds:
        out.append("<h3>Witness rounds</h3>" + table(
            [[r.get("method"), params_text(r.get("params")), levels(r.get("witness_levels")), r.get("action"),
              params_text(r.get("params_after"))] for r in rounds],
            ["method", "widths", "witness", "action", "widths after"]))
    proof = data.get("minimality_proof") or {}
    if proof:
        out.append("<h3>Minimality: each width one lower</h3>" + table(
            [[name, p.get("value"), p.get("lower"), _lower_error(p), p.get("why", "misses the requirement")]
             for name, p in proof.items() if isinstance(p, dict)],
            ["width", "chosen", "one lower", "its error", "why not lower"]))
    return "\n".join(out)


def _lower_error(entry):
    """A proof entry's error one lower: measured (``max_error``), or its certificate's bound."""
    if entry.get("max_error") is not None:
        return f"max {levels(entry['max_error'])}"
    if entry.get("bound_levels") is not None:
        return f"bound {levels(entry['bound_levels'])}"
    return "—"


def _misses(default, data):
    limit = (data.get("requirement") or {}).get("max_error_levels")
    value = default.get("max")
    return isinstance(value, str) or (isinstance(value, (int, float)) and limit is not None and value > limit)


def _baseline(data):
    if data.get("chosen") == BASELINE:
        return "the chosen design is conventional Phong itself"
    baseline = data.get("conventional_baseline") or {}
    if "why_not" in baseline:
        return baseline["why_not"]
    if not baseline:
        return None
    state = "meets the requirement" if baseline.get("feasible") else "misses the requirement"
    return f"{state}: max {levels(baseline.get('max'))}, {cost_text(baseline.get('cost'))}"


def _tie(tie):
    if not tie:
        return None
    return (f"{tie.get('runner_up')} is within {number(100 * tie.get('within', 0))}% "
            f"(cost {number(tie.get('runner_up_cost'))}, max {levels(tie.get('runner_up_max'))}); "
            f"decided by {tie.get('decided_by')}")


def _status(name, result, chosen):
    if name == chosen:
        return "chosen"
    return "feasible" if result.get("feasible") else "infeasible"


def candidate_points(data):
    """``(points, left out)`` of the cost/error chart: each method of the manifest at its
    result's cost and max error, an infeasible one at its default widths; the names of those
    without a finite cost and error."""
    points, left = [], []
    for name, r in (data.get("methods") or {}).items():
        kind = _status(name, r, data.get("chosen"))
        source = r if r.get("feasible") and r.get("cost") else (r.get("default") or {})
        cost, value = (source.get("cost") or {}).get("cost"), source.get("max")
        if not all(isinstance(v, (int, float)) and math.isfinite(v) for v in (cost, value)):
            left.append(name)
            continue
        label = name if kind != "infeasible" else f"{name} (defaults)"
        points.append(Point(float(cost), float(value), label, kind,
                            f"{label}: {cost_text(source.get('cost'))}, max {levels(value)}"))
    return points, left


def _superseded(earlier):
    """Why a method's result replaced an earlier one: the earlier widths' witness missed."""
    if not isinstance(earlier, dict):
        return ""
    witness = (earlier.get("witness") or {}).get("error_levels")
    return (f"searched again: its earlier widths ({params_text(earlier.get('params'))}) had a witness of "
            f"{levels(witness)}" + (f" against a measured max of {levels(earlier.get('max'))}"
                                    if earlier.get("max") is not None else ""))


def _candidates(data):
    methods = data.get("methods") or {}
    if not methods and not data.get("rejected"):
        return ""
    out = [heading("candidates", "Candidates")]
    rows, classes = [], []
    for name, r in methods.items():
        status = _status(name, r, data.get("chosen"))
        why = r.get("why_not_chosen") or "; ".join(r.get("why") or []) or _superseded(r.get("superseded"))
        rows.append([name, status, params_text(r.get("params")), levels(r.get("max")), number(r.get("mean"), ".4f"),
                     cost_text(r.get("cost")) if r.get("cost") else "—", why])
        classes.append("chosen" if status == "chosen" else None)
    if rows:
        out.append(table(rows, ["method", "status", "widths (best point)", "max error", "mean", "cost", "why"],
                         classes))
    if data.get("rejected"):
        out.append("<h3>Rejected before the search</h3>"
                   + table([[k, v] for k, v in data["rejected"].items()], ["method", "why"]))
    points, left = candidate_points(data)
    if points:
        req = (data.get("requirement") or {}).get("max_error_levels")
        unit = next((((r.get("cost") or {}).get("unit") or ((r.get("default") or {}).get("cost") or {}).get("unit"))
                     for r in methods.values()), None) or "cost units"
        out.append(Html(scatter(
            points, chart_id="cost-error", title="Every candidate: cost against max error",
            x_title=f"cost ({unit}, {data.get('cost_model') or 'cost model'})",
            y_title="max error (display levels)",
            hline=(req, f"requirement {number(req)}") if isinstance(req, (int, float)) else None,
            note="infeasible methods at their default widths" if any(p.kind == "infeasible" for p in points)
            else "")))
    if left:
        out.append(f"<p>Not on the chart (no finite cost and error): {esc(', '.join(left))}.</p>")
    return "\n".join(out)


def _certificate(data):
    certificate, witness = data.get("certificate"), data.get("witness")
    if data.get("chosen") is None and not witness:
        return ""
    out = [heading("certificate", "Certificate and witness"), f"<p>{_certified(certificate)}.</p>"]
    if certificate:
        parts = certificate.get("parts") or {}
        out.append(pairs([("certified", str(bool(certificate.get("certified")))),
                          ("bound", f"{number(certificate.get('bound_levels'), '.4g')} levels"),
                          ("method", certificate.get("method")), ("seconds", number(certificate.get("seconds"))),
                          ("why", certificate.get("why") or None)]
                         + [(f"part: {k}", number(v, ".4g")) for k, v in parts.items()
                            if isinstance(v, (int, float))]))
    if witness:
        out.append("<h3>Witness: the worst input found</h3>" + pairs([
            ("error", levels(witness.get("error_levels"))),
            ("unrounded", number(witness.get("unrounded"))), ("found by", witness.get("found_by")),
            ("outputs", witness.get("outputs") and ", ".join(f"{k} {v}" for k, v in witness["outputs"].items())),
            ("reference levels", witness.get("reference_levels") and str(witness["reference_levels"]))]))
        if witness.get("replay"):
            out.append(f"<p>Replay (DIR: this report's folder):</p><pre>{esc(witness['replay'])}</pre>")
    return "\n".join(out)


def _pictures(data, folder):
    if folder is None:
        return ""
    out, captions = [], data.get("pictures") or {}
    for sub, title in PICTURES:
        where = os.path.join(folder, sub)
        names = ["sheet.png"] if os.path.isfile(os.path.join(where, "sheet.png")) else sorted(
            n for n in (os.listdir(where) if os.path.isdir(where) else []) if n.endswith(".png"))
        if not names:
            continue
        out.append(f"<h3>{esc(title)}</h3>")
        for name in names:
            caption = f"{sub}/{name}" + (f": {captions[sub]}" if captions.get(sub) else "")
            out.append(f'<figure><img alt="{esc(sub)}/{esc(name)}" src="{png_data_uri(os.path.join(where, name))}">'
                       f"<figcaption>{esc(caption)}</figcaption></figure>")
        white = data.get("error_png_white_levels")
        if sub == "error" and white is not None:
            out.append(f"<p>Error scale: black = 0, white = {esc(levels(white))} or more (twice the requirement), "
                       "the worst of r, g, b per pixel; the colour bar beside each map.</p>")
    return heading("pictures", "Error maps and frames") + "\n" + "\n".join(out) if out else ""


def _check(data):
    check, bench, flow = data.get("rtl_check"), data.get("testbench"), data.get("flow")
    if not (check or bench or flow or data.get("top")):
        return ""
    out = [heading("check", "RTL check, testbench and flow")]
    if check:
        out.append(pairs([("frame", check.get("frame")), ("back end", check.get("backend")),
                          ("pixels", check.get("pixels")), ("cycles", check.get("cycles")),
                          ("out_ready stalls", f"{100 * (check.get('stalls') or 0):g}%"),
                          ("reset at cycle", check.get("reset_at_cycle")),
                          ("mismatches", Html(f'<span class="{"good" if check.get("mismatches") == 0 else "bad"}">'
                                              f'{esc(check.get("mismatches"))}</span>'))]))
    else:
        out.append("<p>The RTL check was not run (--no-check).</p>")
    files = [("shipped top", (data.get("top") or {}).get("file")),
             ("testbench", bench and f"{bench.get('folder')}/ ({bench.get('vectors')} vectors of frame "
                                     f"{bench.get('frame')}; {bench.get('run')})"),
             ("FuseSoC core", flow and flow.get("fusesoc_core")), ("run", flow and flow.get("run"))]
    out.append(pairs(files))
    return "\n".join(out)


def _ports(data):
    top, contract = data.get("top") or {}, data.get("contract")
    out = []
    if top.get("ports"):
        out.append(heading("ports", f"Ports of {top.get('module')}") + table(
            [[p.get("name"), p.get("direction"), p.get("width"), "signed" if p.get("signed") else "",
              p.get("format") or "", p.get("field") or "", "" if p.get("lane") is None else p["lane"],
              "" if p.get("offset") is None else p["offset"]] for p in top["ports"]],
            ["port", "direction", "width", "signed", "format", "field", "lane", "payload offset"]))
    if contract:
        out.append(heading("contract", "Input contract") + "".join(f"<p>{esc(line)}</p>" for line in contract_lines(contract)))
    return "\n".join(out)


def report_html(data, folder=None):
    """The page's HTML text of the manifest dict ``data``; ``folder``: where its PNGs are
    (None: a page without pictures)."""
    chosen = data.get("chosen")
    headline = f"{data.get('scene')}: {chosen} chosen" if chosen else f"{data.get('scene')}: no design chosen"
    sections = [part for part in (_requirement(data), _chosen(data), _candidates(data), speed_section(data),
                                  _certificate(data), _pictures(data, folder), _check(data), _ports(data)) if part]
    contents = "".join(f'<li><a href="#{anchor}">{title}</a></li>'
                       for part in sections for anchor, title in HEADING.findall(part))
    body = [f"<h1>{esc(headline)}</h1>", _summary(data), f"<nav><ul>{contents}</ul></nav>", *sections]
    return ("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
            f"<title>{esc(headline)}: phongfx compile report</title>\n<style>{STYLE}</style>\n</head>\n<body>\n"
            + "\n".join(body) + "\n</body>\n</html>\n")


def write_report(path, data, folder=None):
    """Write :func:`report_html` of ``data`` to ``path``, whole or not at all
    (:func:`~phongfx.core.files.atomic_write`); returns ``path``."""
    text = report_html(data, folder)
    atomic_write(path, lambda tmp: open(tmp, "w", encoding="utf-8").write(text))
    return path
