import json
import math

import numpy as np
from PIL import Image

from phongfx.papers.lyon.figure9 import FIXED_ROWS, float_rows, run
from phongfx.render.lyon import composite
from phongfx.scene.lyon import Scene, pixels


def _specular_m_pixel(i, j, m, method):
    """One pixel of Lyon's specular.m, written out as his loop does (phong and lyon-k2)."""
    ns = [1, 4, 16, 64, 256]
    specfs = [400 / max(n ** 0.25 for n in ns) * n ** 0.25 for n in ns]
    lights = [np.array([1.0, 1, -1]) / math.sqrt(3), np.array([1.0, -1, 1]) / math.sqrt(3)]
    vv = np.array([0.0, 0, 1])
    xx, y = (0.5 + i) / m, (0.5 + j) / m
    for ni, n in enumerate(ns):
        x = xx - ni
        z = 1 - x * x - y * y
        if z >= 0:
            break
    nv = np.array([x, y, math.sqrt(z)])
    total = 0.0
    for lv in lights:
        dif = lv @ nv
        total += 35 * dif if dif > 0 else 0
        rv = 2 * nv * (vv @ nv) - vv
        if method == "phong":
            dot = rv @ lv
            amount = dot ** n if dot > 0 else 0
        else:
            dv = lv - rv
            xs = (dv @ dv) * n / 2
            amount = 0 if xs > 4 else (1 - xs / 4) ** 4
        total += specfs[ni] * amount
    return total


def test_float_rows_equal_the_appendix_code():
    scene = Scene(radius=16)
    px = pixels(scene)
    floats, diff = float_rows(scene, px)
    for method in ("phong", "lyon-k2"):
        image = composite(scene, px, floats[method], diff)
        for k in range(0, len(px), 97):
            i, j = px.col[k] - 16, 16 - px.row[k]
            want = min(max(_specular_m_pixel(i, j, 16, method), 0), 255)
            assert abs(image[px.row[k], px.col[k]] - want) < 1e-9


def test_small_figure_is_checked_through_the_rtl(tmp_path):
    table = run(out_dir=str(tmp_path), backend="amaranth", radius=5)
    rows_with_datapath = sum(len(rows) for rows in FIXED_ROWS.values())
    assert table["rtl_mismatches"] == 0
    assert table["rtl_pixels_checked"] == rows_with_datapath * table["pixels_per_row"]
    assert len(table["rows"]) == 12
    written = json.loads((tmp_path / "figure9.json").read_text())
    assert written["rtl_pixels_checked"] == table["rtl_pixels_checked"]
    for name in ("figure9.png", "figure9_diff.png"):
        assert (tmp_path / name).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    # the difference picture is scaled to its largest difference, which its colour bar shows
    assert written["diff_scale_levels"] == table["diff_scale_levels"] >= 1
    picture = np.asarray(Image.open(tmp_path / "figure9_diff.png").convert("RGB"))
    bar = picture[:, int(picture.shape[1] * 0.85):].reshape(-1, 3)
    assert len(np.unique(bar, axis=0)) > 50
    md = (tmp_path / "figure9.md").read_text()
    assert "| 4 | lyon-k2 | Figure 7, k = 2 |" in md and "| 1 | phong | (float only) |" in md
    # each fixed row tracks its own float method far better than it tracks Phong
    for row in table["rows"]:
        for fixed in row["fixed"]:
            assert fixed["vs_own_float"]["max"] < 8
