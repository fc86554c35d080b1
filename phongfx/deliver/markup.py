"""HTML pieces of the compile report page (:mod:`phongfx.deliver.page`): escaped text,
tables, a manifest's numbers, costs and widths in words, and PNGs as ``data:`` URIs.

Every text that comes from a manifest reaches the page through :func:`esc`
(``html.escape``); only :class:`Html`, text a builder made itself, passes as it is.
"""

import base64
import html

__all__ = ["Html", "esc", "heading", "number", "levels", "cost_text", "params_text", "table", "pairs", "png_data_uri"]

#: The first bytes of every PNG file.
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


class Html(str):
    """Text that is already HTML: not escaped again by :func:`esc`."""


def esc(value):
    """``value`` as HTML text: escaped, unless it is :class:`Html`; None as an empty cell."""
    if isinstance(value, Html):
        return value
    return html.escape("" if value is None else str(value))


def heading(anchor, title):
    """A section heading ``<h2 id="anchor">`` (the page's contents link to it)."""
    return Html(f'<h2 id="{esc(anchor)}">{esc(title)}</h2>')


def number(value, fmt=".3g"):
    """A manifest number for reading: whole floats as integers with thousands separated,
    others by ``fmt``; ``"inf"`` (the manifest's infinity) as it is, None as a dash."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return "—" if value is None else str(value)
    if isinstance(value, float) and value.is_integer():
        value = int(value)
    return f"{value:,}" if isinstance(value, int) else f"{value:{fmt}}"


def levels(value):
    """``1 level``, ``1.42 levels`` of an error in display levels (a dash for None)."""
    if value is None:
        return "—"
    text = number(value)
    return f"{text} level" if text == "1" else f"{text} levels"


def cost_text(cost):
    """``LUT-eq 28,595`` or ``area 56,789 µm²`` of a manifest cost dict, or why it has none."""
    if not cost or cost.get("cost") is None:
        return f"unknown ({(cost or {}).get('why', 'not costed')})"
    if cost.get("unit") == "µm²":
        return f"area {cost['cost']:,.0f} µm²"
    return f"{cost.get('unit') or 'cost'} {cost['cost']:,.0f}"


def params_text(params):
    """``vec_frac 11, k 4`` of a widths dict."""
    return ", ".join(f"{k} {v}" for k, v in (params or {}).items())


def table(rows, header=None, classes=None):
    """An HTML table of ``rows`` (lists of cells, escaped by :func:`esc`) under ``header``;
    ``classes``: a CSS class per row, or None."""
    out = ["<table>"]
    if header:
        out.append("<tr>" + "".join(f"<th>{esc(h)}</th>" for h in header) + "</tr>")
    for index, row in enumerate(rows):
        cls = classes[index] if classes else None
        out.append((f'<tr class="{cls}">' if cls else "<tr>") + "".join(f"<td>{esc(c)}</td>" for c in row) + "</tr>")
    return Html("\n".join(out + ["</table>"]))


def pairs(items):
    """A two-column table of ``(name, value)``, leaving out those whose value is None or False."""
    return table([[Html(f"<b>{esc(k)}</b>"), v] for k, v in items if v is not None and v is not False])


def png_data_uri(path):
    """The PNG file ``path`` as a ``data:image/png;base64,...`` URI; ``ValueError`` naming the
    file if it is not a PNG."""
    with open(path, "rb") as file:
        data = file.read()
    if not data.startswith(PNG_SIGNATURE):
        raise ValueError(f"{path}: not a PNG (its first bytes are {data[:8]!r}); the report embeds PNGs only")
    return "data:image/png;base64," + base64.b64encode(data).decode("ascii")
