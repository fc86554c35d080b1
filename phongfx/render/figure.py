"""Pictures a person can read: a title, a visible scale, and for an error a colour bar.

A shaded frame of 96 × 96 pixels, written one PNG pixel per frame pixel, is a postage stamp
with no way to tell what it shows; an error picture whose white means "twice the requirement"
says so only in a manifest.  These functions write the same data as a figure instead:

* :func:`frame_figure`: a picture, titled, enlarged by an integer factor (nearest
  neighbour, so every frame pixel stays a sharp square of one colour) to at least
  :data:`MIN_SIZE` pixels on its longer side;
* :func:`error_figure`: per-pixel error in 8-bit display levels the same way, with a colour
  bar in those levels beside it; ``white_levels`` and above are white;
* :func:`contact_sheet`: many frames (or error pictures) in one grid, each tile titled,
  e.g. every frame of a scene's animation at a glance; the tiles are enlarged until the
  sheet is :data:`MIN_SHEET_WIDTH` pixels wide (one 96 × 96 frame was a 311 × 140 sheet).

A colour bar's label is wrapped to the bar's length (it was cut to "ror, 8-bit display
levels" beside a short picture).

The layout is set in pixels (Agg, :data:`DPI`), not left to ``tight_layout``: the picture
is drawn at exactly ``scale`` PNG pixels per frame pixel, which a resampling layout would
blur.  Pixels not covered (NaN in an error picture) are drawn in :data:`UNCOVERED`, a
colour outside the grey scale, so that "no error" and "no surface" differ.
"""

import math
import textwrap

import numpy as np

from phongfx.core.files import atomic_write

__all__ = ["MIN_SIZE", "TILE_SIZE", "MIN_SHEET_WIDTH", "DPI", "MARGIN", "UNCOVERED", "ERROR_LABEL", "scale_for",
           "frame_figure", "error_figure", "contact_sheet"]

#: Longer side, in PNG pixels, that a single picture is enlarged to at least.
MIN_SIZE = 384
#: Longer side, in PNG pixels, that a contact sheet's tile is enlarged to at least.
TILE_SIZE = 192
#: Width, in PNG pixels, that a contact sheet is brought to at least by enlarging its tiles.
MIN_SHEET_WIDTH = 800
#: The label of an error picture's colour bar.
ERROR_LABEL = "error, 8-bit display levels"
#: Dots per inch of the figures; the layout below is in pixels at this density.
DPI = 100
#: Colour of pixels with no value (NaN): light blue, outside every grey of the scale.
UNCOVERED = "#b8cce4"

#: PNG pixels between a single picture and the figure's left and bottom edges.
MARGIN = 10
_LINE = 17  # pixels per title line at _FONT points
_FONT = 10
_HEAD_FONT = 12  # a contact sheet's title
_CHAR = 6.8  # average pixels per character at _FONT points, to wrap titles
_BAR = (14, 12, 72)  # colour bar: gap to the picture, its width, room for ticks and one label line


def scale_for(shape, min_size=MIN_SIZE):
    """The integer enlargement that brings a picture of ``shape`` (H, W, ...) to at least
    ``min_size`` pixels on its longer side (1 if it is already that large)."""
    if min(int(shape[0]), int(shape[1])) < 1:
        raise ValueError(f"picture must have at least one pixel, not shape {tuple(shape)}")
    return max(1, math.ceil(min_size / max(int(shape[0]), int(shape[1]))))


def _pyplot():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def _picture(picture):
    """``picture`` as (H, W, 3) RGB in [0, 1]: drawn as colours, not through a colour map,
    so that each grey is the PNG grey ``round(255·value)``."""
    data = np.asarray(picture, dtype=np.float64)
    if data.ndim not in (2, 3) or (data.ndim == 3 and data.shape[2] != 3):
        raise ValueError(f"picture must be (H, W) grey or (H, W, 3) RGB, not shape {data.shape}")
    data = np.clip(data, 0.0, 1.0)
    return np.repeat(data[..., None], 3, axis=2) if data.ndim == 2 else data


def _wrap(title, width_px):
    """``title`` as lines that fit ``width_px`` pixels (its own newlines kept)."""
    columns = max(12, int(width_px / _CHAR))
    # "n = 20" is one term: no-break spaces (which textwrap does not split at) keep it whole
    text = str(title).replace(" = ", "\u00a0=\u00a0")
    return [line for part in text.split("\n") for line in (textwrap.wrap(part, columns) or [""])]


def _bar_label(label, length_px):
    """``label`` wrapped to lines that fit along a colour bar ``length_px`` long (no word
    broken), and the extra width in pixels its lines beyond the first take."""
    columns = max(max(map(len, label.split())), int(length_px / _CHAR))
    lines = textwrap.wrap(label, columns)
    return "\n".join(lines), _LINE * (len(lines) - 1)


def _grey_map(name):
    import matplotlib
    return matplotlib.colormaps[name].with_extremes(bad=UNCOVERED)


def _save(fig, path):
    plt = _pyplot()
    try:
        atomic_write(path, lambda tmp: fig.savefig(tmp, dpi=DPI, format="png"))
    finally:
        plt.close(fig)
    return path


def _show(ax, data, **style):
    ax.imshow(data, interpolation="nearest", aspect="auto", **style)
    ax.set_axis_off()


def _single(path, data, title, min_size, style, bar_label=None):
    """One picture at an integer scale under its title; a colour bar right of it if
    ``bar_label`` is given."""
    plt = _pyplot()
    scale = scale_for(data.shape, min_size)
    h, w = data.shape[0] * scale, data.shape[1] * scale
    # beside a low picture the bar stands taller than it, so that its label fits in two lines
    length = max(h, math.ceil(_CHAR * len(bar_label or "") / 2) + 2 * _LINE) if bar_label else h
    if bar_label:
        bar_label, extra = _bar_label(bar_label, length)
    bar = sum(_BAR) + extra if bar_label else 0
    width = w + bar + 2 * MARGIN
    lines = _wrap(title, width - 2 * MARGIN)
    top = _LINE * len(lines) + MARGIN
    height = length + top + MARGIN
    fig = plt.figure(figsize=(width / DPI, height / DPI), dpi=DPI)
    ax = fig.add_axes((MARGIN / width, (MARGIN + length - h) / height, w / width, h / height))  # under the title
    _show(ax, data, **style)
    fig.text(0.5, 1 - (MARGIN / 2) / height, "\n".join(lines), ha="center", va="top", fontsize=_FONT)
    if bar_label:
        cax = fig.add_axes(((MARGIN + w + _BAR[0]) / width, MARGIN / height, _BAR[1] / width, length / height))
        fig.colorbar(ax.images[0], cax=cax, extend="max", label=bar_label)
    return _save(fig, path)


def frame_figure(path, picture, title, *, min_size=MIN_SIZE):
    """Write ``picture`` ((H, W) grey or (H, W, 3) RGB, floats in [0, 1], e.g. a shader's
    colour codes / 255) to the PNG ``path``, titled ``title``, enlarged by an integer factor
    to at least ``min_size`` pixels on its longer side.  Returns ``path``."""
    return _single(path, _picture(picture), title, min_size, {})


def _error_style(levels, white_levels, cmap):
    if not (isinstance(white_levels, (int, float)) and math.isfinite(white_levels) and white_levels > 0):
        raise ValueError(f"white_levels must be a positive number of 8-bit levels, not {white_levels!r}")
    data = np.asarray(levels, dtype=np.float64)
    if data.ndim != 2:
        raise ValueError(f"levels must be an (H, W) array of 8-bit levels, not shape {data.shape}")
    return data, {"cmap": _grey_map(cmap), "vmin": 0.0, "vmax": float(white_levels)}


def error_figure(path, levels, title, white_levels, *, min_size=MIN_SIZE, cmap="gray"):
    """Write ``levels`` ((H, W) error in 8-bit display levels; NaN where nothing is drawn)
    to the PNG ``path`` as :func:`frame_figure` does, black = 0 and white = ``white_levels``
    or more, with a colour bar in 8-bit levels beside it.  Returns ``path``."""
    data, style = _error_style(levels, white_levels, cmap)
    return _single(path, data, title, min_size, style, bar_label=ERROR_LABEL)


def contact_sheet(path, pictures, titles, *, title=None, columns=None, tile_size=TILE_SIZE,
                  white_levels=None, cmap="gray"):
    """Write ``pictures`` (equal-shape frames as :func:`frame_figure` takes, or with
    ``white_levels`` error pictures as :func:`error_figure` takes, then sharing one colour
    bar) to the PNG ``path`` as one grid: ``columns`` tiles a row (default about square),
    each tile titled by its entry of ``titles`` and enlarged by one integer factor to at
    least ``tile_size`` pixels, and further until the sheet is at least
    :data:`MIN_SHEET_WIDTH` wide; ``title`` above the whole sheet.  Returns ``path``."""
    plt = _pyplot()
    pictures = list(pictures)
    titles = list(titles)
    if not pictures or len(titles) != len(pictures):
        raise ValueError(f"contact_sheet needs one title per picture and at least one picture, "
                         f"not {len(pictures)} picture(s) and {len(titles)} title(s)")
    if white_levels is None:
        data, style = [_picture(p) for p in pictures], {}
    else:
        pairs = [_error_style(p, white_levels, cmap) for p in pictures]
        data, style = [d for d, _ in pairs], pairs[0][1]
    shape = data[0].shape
    if any(d.shape != shape for d in data):
        raise ValueError(f"contact_sheet pictures must share one shape; the first is {shape}")
    columns = columns or math.ceil(math.sqrt(len(data)))
    if not isinstance(columns, int) or columns < 1:
        raise ValueError(f"columns must be a positive integer, not {columns!r}")
    rows = math.ceil(len(data) / columns)
    bar = sum(_BAR) if white_levels is not None else 0
    room = MIN_SHEET_WIDTH - bar - (columns + 1) * MARGIN  # for the tiles of a row
    scale = max(scale_for(shape, tile_size), math.ceil(room / (columns * shape[1])))
    h, w = shape[0] * scale, shape[1] * scale
    label = max(len(_wrap(t, w)) for t in titles) * _LINE + 4
    span = rows * (h + label + MARGIN) - MARGIN - label  # the colour bar's length
    if white_levels is not None:
        bar_label, extra = _bar_label(ERROR_LABEL, span)
        bar += extra
    width = columns * (w + MARGIN) + MARGIN + bar
    # the sheet's title a size larger than the tiles': what the sheet is, read first
    head = _wrap(title, (width - 2 * MARGIN) * _FONT / _HEAD_FONT) if title else []
    top = math.ceil(_LINE * _HEAD_FONT / _FONT) * len(head) + MARGIN
    height = top + rows * (h + label + MARGIN)
    fig = plt.figure(figsize=(width / DPI, height / DPI), dpi=DPI)
    for index, (picture, name) in enumerate(zip(data, titles)):
        r, c = divmod(index, columns)
        x, y = MARGIN + c * (w + MARGIN), height - top - (r + 1) * (h + label + MARGIN) + MARGIN
        ax = fig.add_axes((x / width, y / height, w / width, h / height))
        _show(ax, picture, **style)
        fig.text((x + w / 2) / width, (y + h + 2) / height, "\n".join(_wrap(name, w)),
                 ha="center", va="bottom", fontsize=_FONT - 1)
    if head:
        fig.text(0.5, 1 - (MARGIN / 2) / height, "\n".join(head), ha="center", va="top", fontsize=_HEAD_FONT)
    if white_levels is not None:
        cax = fig.add_axes(((width - bar + _BAR[0] - MARGIN) / width, MARGIN / height, _BAR[1] / width,
                            span / height))
        fig.colorbar(fig.axes[0].images[0], cax=cax, extend="max", label=bar_label)
    return _save(fig, path)
