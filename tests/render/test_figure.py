"""The readable pictures of :mod:`phongfx.render.figure`: enlarged, titled, error with a colour bar."""

import numpy as np
import pytest
from PIL import Image

from phongfx.render.figure import MARGIN, MIN_SIZE, TILE_SIZE, contact_sheet, error_figure, frame_figure, scale_for

PNG = b"\x89PNG\r\n\x1a\n"


def _disc(size=24):
    y, x = np.mgrid[0:size, 0:size]
    return np.clip(1 - ((x - size / 2) ** 2 + (y - size / 2) ** 2) / (size / 2) ** 2, 0, 1)


def _colours(image, box):
    return len(np.unique(np.asarray(image.convert("RGB").crop(box)).reshape(-1, 3), axis=0))


def test_scale_is_the_integer_reaching_the_minimum():
    assert scale_for((96, 96)) == 4 and scale_for((96, 50)) == 4 and scale_for((500, 10)) == 1
    assert scale_for((24, 24), TILE_SIZE) == 8
    with pytest.raises(ValueError, match=r"^picture must have at least one pixel, not shape \(0, 3\)$"):
        scale_for((0, 3))


def test_frame_figure_is_an_enlarged_titled_png(tmp_path):
    picture = _disc()
    path = frame_figure(tmp_path / "frame.png", picture, "frame 0 of 1")
    assert path.read_bytes()[:8] == PNG
    image = Image.open(path).convert("L")
    assert min(image.size) >= MIN_SIZE
    # nearest neighbour at 16× (24 → 384): every frame pixel is one flat 16 × 16 square
    grid = np.asarray(image, dtype=np.int64)
    inner = grid[-MARGIN - 384:-MARGIN, MARGIN:MARGIN + 384].reshape(24, 16, 24, 16)
    assert np.all(inner.max(axis=(1, 3)) - inner.min(axis=(1, 3)) <= 1)
    assert np.allclose(inner[:, 0, :, 0], np.round(picture * 255), atol=1)
    # the title is drawn above the picture: dark text on white
    assert grid[:4].min() == 255 and grid[4:30].min() < 128


def test_error_figure_has_a_colour_bar_in_levels(tmp_path):
    levels = np.zeros((24, 24))  # no error at all: only the bar has colours
    levels[:2] = np.nan  # uncovered pixels
    image = Image.open(error_figure(tmp_path / "error.png", levels, "error", 2.0))
    width, height = image.size
    assert width >= MIN_SIZE + 80 and height >= MIN_SIZE
    picture = _colours(image, (12, height - 300, 390, height - 12))
    assert picture <= 3  # black, and nothing else in the lower picture
    assert _colours(image, (400, 0, width, height)) > 50  # the bar's greys, ticks and label
    with pytest.raises(ValueError, match=r"^white_levels must be a positive number of 8-bit levels, "
                                         r"not 0$"):
        error_figure(tmp_path / "bad.png", levels, "error", 0)
    assert not (tmp_path / "bad.png").exists()


def test_contact_sheet_tiles_every_frame(tmp_path):
    pictures = [_disc() * (i + 1) / 5 for i in range(5)]
    path = contact_sheet(tmp_path / "sheet.png", pictures, [f"frame {i}" for i in range(5)], title="five")
    image = Image.open(path)
    assert image.size[0] >= 3 * TILE_SIZE and image.size[1] >= 2 * TILE_SIZE  # 3 columns, 2 rows
    errors = contact_sheet(tmp_path / "errors.png", [p * 4 for p in pictures], list("abcde"),
                           white_levels=2)
    assert Image.open(errors).size[0] > image.size[0]  # the shared colour bar
    with pytest.raises(ValueError, match=r"one title per picture"):
        contact_sheet(tmp_path / "x.png", pictures, ["only one"])
    with pytest.raises(ValueError, match=r"^contact_sheet pictures must share one shape"):
        contact_sheet(tmp_path / "x.png", [_disc(8), _disc(9)], ["a", "b"])


def _texts_inside(monkeypatch):
    """A list that fills, for every figure closed, with its texts whose drawn extent leaves the
    figure (a clipped label or title)."""
    import matplotlib.pyplot as plt
    from matplotlib.text import Text

    outside, close = [], plt.close

    def record(fig=None):
        renderer = fig.canvas.get_renderer()
        for text in fig.findobj(Text):
            if text.get_text() and text.get_visible():
                box = text.get_window_extent(renderer)
                if box.x0 < -1 or box.y0 < -1 or box.x1 > fig.bbox.x1 + 1 or box.y1 > fig.bbox.y1 + 1:
                    outside.append(text.get_text())
        close(fig)
    monkeypatch.setattr(plt, "close", record)
    return outside


def test_colour_bar_label_is_whole_beside_low_pictures_and_in_sheets(tmp_path, monkeypatch):
    outside = _texts_inside(monkeypatch)
    error_figure(tmp_path / "wide.png", np.full((8, 200), 1.0), "a wide, low error picture", 2.0)
    error_figure(tmp_path / "square.png", _disc(96), "a 96 × 96 error picture", 2.0)
    contact_sheet(tmp_path / "one.png", [_disc(96)], ["frame 0"], white_levels=2.0, title="1 frame")
    contact_sheet(tmp_path / "thin.png", [np.ones((12, 96))] * 8, [f"frame {i}" for i in range(8)], columns=4,
                  white_levels=2.0, title="8 thin frames")
    assert outside == []  # the label was cut to "ror, 8-bit display levels" beside a low picture


def test_a_contact_sheet_of_one_small_frame_is_readable(tmp_path):
    contact_sheet(tmp_path / "sheet.png", [_disc(96)], ["frame 0"], title="torus_fig7: every frame")
    width, height = Image.open(tmp_path / "sheet.png").size
    assert width >= 800 and height >= 700  # it was 311 × 140 px; the tile is the frame × 8
