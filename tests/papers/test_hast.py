"""``phongfx tables hast``: Hast's Tables 1 and 2 on tori, a few frames."""

import json
import re

import pytest

from phongfx.papers.hast import PAPER_TABLE1, PAPER_TABLE2, POLYGONS, markdown, measure, run_table, to_json


@pytest.fixture(scope="module")
def result(tmp_path_factory):
    out = tmp_path_factory.mktemp("hast")
    return run_table("hast", out, frames=4), out


def test_trends(result):
    rows = result[0]["rows"]
    assert [r["polygons"] for r in rows] == list(POLYGONS)
    for method in ("gouraud", "euler", "corrected", "vertex", "fixed"):
        means = [r[method]["mean"] for r in rows]
        assert means == sorted(means, reverse=True) and means[0] > means[-1], method
    for r in rows:
        assert r["corrected"]["mean"] < r["euler"]["mean"] < r["gouraud"]["mean"] < r["vertex"]["mean"]
        assert r["corrected"]["max"] <= 3 and r["fixed"]["max"] <= 3
        assert abs(r["fixed"]["mean"] - r["corrected"]["mean"]) < 0.01  # 30 fraction bits
        t = r["table1"]
        # the test (eq. 23-24) passes more spans than have equal truncated levels
        assert t["adaptive"] > t["euler_equal"]
        assert t["adaptive"] - t["fp"] + t["fn"] == pytest.approx(t["euler_equal"])
        for n in ("1", "10", "50"):
            h = r["highlight"][n]
            assert h["vertex"] <= h["test"] and h["exact"] <= h["test"]
    equal = [r["table1"]["phong_equal"] for r in rows]
    assert equal == sorted(equal) and 40 < equal[0] < equal[-1] < 100
    # higher shininess, smaller highlight
    assert all(r["highlight"]["1"]["test"] > r["highlight"]["10"]["test"] > r["highlight"]["50"]["test"]
               for r in rows)


def test_about_20k_pixels_a_frame(result):
    for r in result[0]["rows"]:
        assert 15_000 < r["pixels"] / r["frames"] < 25_000


def test_markdown_has_the_paper(result):
    text = markdown(result[0])
    for polygons, paper in PAPER_TABLE2.items():
        row = next(line for line in text.splitlines() if line.startswith(f"| {polygons} | ") and "/" in line)
        for method, (mean, worst) in paper.items():
            assert f"{mean:.{3 if method == 'corrected' else 2}f} / {worst}" in row
    for polygons, percent in PAPER_TABLE1.items():
        assert re.search(rf"^\| {polygons} \| \d+ \| {percent} \| ", text, re.M), text


def test_json_round_trips(result):
    assert json.loads(to_json(result[0])) == result[0]


def test_plot_written(result):
    png = result[1] / "hast.png"
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert [p.name for p in result[1].iterdir()] == ["hast.png"]


def test_arguments():
    with pytest.raises(ValueError, match=r"^unknown table 'lyon'; valid tables: hast$"):
        run_table("lyon")
    with pytest.raises(ValueError, match=r"^frames must be a positive integer, not 0$"):
        measure(288, frames=0)
    with pytest.raises(ValueError, match=r"^light must be a unit 3-vector, not \[0\.0, 0\.0, 2\.0\]$"):
        measure(288, frames=1, light=(0, 0, 2))
