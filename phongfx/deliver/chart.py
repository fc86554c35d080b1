"""Scatter charts as inline SVG text, for the compile report page (:mod:`phongfx.deliver.page`).

:func:`scatter` draws labelled points on linear axes with "nice" ticks (1, 2 or 5 times a
power of ten), a title, axis titles, optional reference lines (a requirement: a horizontal
line at a y value, or a vertical one at an x value) and a legend of the point kinds present.
Each point is a ``<g class="point">`` carrying its label and kind in ``data-label`` and
``data-kind`` (and a ``<title>``: the browser's tooltip), so a page or a test can find every
point of a chart.  Everything is written by Python: no script, no font, no external file;
every text goes through ``html.escape``.
"""

import dataclasses
import html
import math

__all__ = ["Point", "KINDS", "nice_ticks", "scatter"]

#: Marker of each point kind: (fill, stroke, radius, legend text).
KINDS = {"chosen": ("#d62728", "#7f0000", 7, "chosen"),
         "feasible": ("#1f77b4", "#0b3d66", 5, "meets the requirement"),
         "infeasible": ("#ffffff", "#7f7f7f", 5, "misses it (default widths)"),
         "other": ("#2ca02c", "#145214", 5, "other")}

WIDTH, HEIGHT = 720, 420
#: Plot area margins (left, right, top, bottom) in SVG units: room for tick labels and titles.
MARGIN = (80, 150, 40, 60)


@dataclasses.dataclass(frozen=True)
class Point:
    """One point of a chart: where, its label, its kind (a key of :data:`KINDS`) and the
    tooltip text (the label when empty)."""
    x: float
    y: float
    label: str
    kind: str = "feasible"
    tip: str = ""

    def __post_init__(self):
        if self.kind not in KINDS:
            raise ValueError(f"Point.kind must be one of {', '.join(KINDS)}, not {self.kind!r}")
        for name in ("x", "y"):
            value = getattr(self, name)
            if not isinstance(value, (int, float)) or not math.isfinite(value):
                raise ValueError(f"Point.{name} must be a finite number, not {value!r} (point {self.label!r})")


def nice_ticks(low, high, count=6):
    """About ``count`` round tick values covering ``[low, high]`` (steps of 1, 2 or 5 times a
    power of ten); ``low == high`` gets a range around the value."""
    if high < low:
        raise ValueError(f"nice_ticks: high must be >= low, not {high!r} < {low!r}")
    if high == low:
        pad = abs(low) * 0.1 or 1.0
        low, high = low - pad, high + pad
    raw = (high - low) / max(count - 1, 1)
    power = 10 ** math.floor(math.log10(raw))
    step = next(m * power for m in (1, 2, 5, 10) if m * power >= raw)
    first = math.floor(low / step) * step
    ticks = []
    value = first
    while value <= high + step * 1e-9 or len(ticks) < 2:
        ticks.append(round(value, 12))
        value += step
    if ticks[-1] < high:
        ticks.append(round(value, 12))
    return ticks


def _number(value):
    """A tick label: thousands separated, no trailing zeros."""
    if float(value).is_integer():
        return f"{value:,.0f}"
    return f"{value:,.6g}"


def _text(x, y, text, *, anchor="start", size=12, weight="normal", extra=""):
    return (f'<text x="{x:.1f}" y="{y:.1f}" text-anchor="{anchor}" font-size="{size}" '
            f'font-weight="{weight}"{extra}>{html.escape(str(text))}</text>')


def _label_rows(placed, height=13):
    """Vertical label offsets that keep labels of points near each other from overlapping:
    ``placed`` is ``[(px, py, width)]`` in drawing order; each label starts beside its point
    and moves down past any earlier label it would cover."""
    boxes, offsets = [], []
    for px, py, width in placed:
        y = py + 4
        moved = True
        while moved:
            moved = False
            for bx, by, bw in boxes:
                if abs(by - y) < height and px + 9 < bx + bw and bx < px + 9 + width:
                    y = by + height
                    moved = True
        boxes.append((px + 9, y, width))
        offsets.append(y)
    return offsets


def scatter(points, *, title, x_title, y_title, hline=None, vline=None, chart_id="chart", note="", legend=None):
    """The SVG text of a scatter chart of ``points`` (:class:`Point`), titled ``title``, its
    axes titled ``x_title`` and ``y_title`` (with their units); ``hline``/``vline``:
    ``(value, label)`` of a dashed reference line, or None; ``note``: a line under the plot;
    ``legend``: ``{kind: text}`` in place of :data:`KINDS`' legend texts.
    The axes span the points and the reference lines, from zero when every value is
    positive and zero is near."""
    points = list(points)
    if not points:
        raise ValueError(f"scatter {chart_id!r}: points must not be empty (nothing to draw)")
    xs = [p.x for p in points] + ([vline[0]] if vline else [])
    ys = [p.y for p in points] + ([hline[0]] if hline else [])

    def span(values, pad=0.0):
        low, high = min(values), max(values)
        if low >= 0 and low <= 0.5 * high:
            low = 0.0  # a range close to zero reads best from zero
        return nice_ticks(low, high + pad * (high - low))

    # room on the right for the last point's label, and above the highest point
    xt, yt = span(xs, pad=0.15), span(ys, pad=0.05)
    left, right, top, bottom = MARGIN
    x0, x1, y0, y1 = left, WIDTH - right, top, HEIGHT - bottom

    def sx(v):
        return x0 + (v - xt[0]) / (xt[-1] - xt[0]) * (x1 - x0)

    def sy(v):
        return y1 - (v - yt[0]) / (yt[-1] - yt[0]) * (y1 - y0)

    out = [f'<svg id="{html.escape(chart_id)}" class="chart" viewBox="0 0 {WIDTH} {HEIGHT}" width="{WIDTH}" '
           f'height="{HEIGHT}" role="img" '
           f'aria-label="{html.escape(title)}" font-family="sans-serif">',
           f"<title>{html.escape(title)}</title>",
           f'<rect x="0" y="0" width="{WIDTH}" height="{HEIGHT}" fill="#ffffff"/>',
           _text(WIDTH / 2, 22, title, anchor="middle", size=15, weight="bold")]
    for v in xt:
        out.append(f'<line x1="{sx(v):.1f}" y1="{y0}" x2="{sx(v):.1f}" y2="{y1}" stroke="#e5e5e5"/>')
        out.append(_text(sx(v), y1 + 16, _number(v), anchor="middle", size=11))
    for v in yt:
        out.append(f'<line x1="{x0}" y1="{sy(v):.1f}" x2="{x1}" y2="{sy(v):.1f}" stroke="#e5e5e5"/>')
        out.append(_text(x0 - 6, sy(v) + 4, _number(v), anchor="end", size=11))
    out.append(f'<rect x="{x0}" y="{y0}" width="{x1 - x0}" height="{y1 - y0}" fill="none" stroke="#333333"/>')
    out.append(_text((x0 + x1) / 2, HEIGHT - 18, x_title, anchor="middle", size=13))
    out.append(_text(18, (y0 + y1) / 2, y_title, anchor="middle", size=13,
                     extra=f' transform="rotate(-90 18 {(y0 + y1) / 2:.1f})"'))
    if hline:
        y = sy(hline[0])
        out.append(f'<line class="reference" x1="{x0}" y1="{y:.1f}" x2="{x1}" y2="{y:.1f}" stroke="#d62728" '
                   f'stroke-dasharray="6 4"/>')
        out.append(_text(x1 + 4, y + 4, hline[1], size=11, extra=' fill="#d62728"'))
    if vline:
        x = sx(vline[0])
        out.append(f'<line class="reference" x1="{x:.1f}" y1="{y0}" x2="{x:.1f}" y2="{y1}" stroke="#d62728" '
                   f'stroke-dasharray="6 4"/>')
        out.append(_text(x + 4, y0 + 12, vline[1], size=11, extra=' fill="#d62728"'))
    # the chosen point is drawn last: on top of any point at the same place
    order = sorted(points, key=lambda p: (p.kind == "chosen", -sy(p.y)))
    rows = _label_rows([(sx(p.x), sy(p.y), 7 * len(p.label)) for p in order])
    for p, label_y in zip(order, rows):
        fill, stroke, radius, _ = KINDS[p.kind]
        px, py = sx(p.x), sy(p.y)
        out.append(f'<g class="point" data-label="{html.escape(p.label)}" data-kind="{p.kind}">'
                   f"<title>{html.escape(p.tip or p.label)}</title>"
                   f'<circle cx="{px:.1f}" cy="{py:.1f}" r="{radius}" fill="{fill}" stroke="{stroke}" '
                   f'stroke-width="{2 if p.kind == "chosen" else 1.5}"/>'
                   + _text(px + 9, label_y, p.label, size=12, weight="bold" if p.kind == "chosen" else "normal")
                   + "</g>")
    kinds = [k for k in KINDS if any(p.kind == k for p in points)]
    for row, kind in enumerate(kinds):
        fill, stroke, radius, text = KINDS[kind]
        text = (legend or {}).get(kind, text)
        y = y0 + 40 + 18 * row
        out.append(f'<circle cx="{x1 + 14}" cy="{y}" r="{radius}" fill="{fill}" stroke="{stroke}"/>')
        out.append(_text(x1 + 24, y + 4, text, size=11))
    if note:
        out.append(_text(x0, HEIGHT - 2, note, size=10, extra=' fill="#555555"'))
    out.append("</svg>")
    return "\n".join(out)
