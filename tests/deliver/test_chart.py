"""The report page's SVG scatter charts: round ticks that cover the data, one labelled group
per point (the chosen one drawn last), reference lines, escaped text, refused bad points."""

import re

import pytest

from phongfx.deliver.chart import Point, nice_ticks, scatter


@pytest.mark.parametrize("low, high, ticks", [
    (0, 9, [0, 2, 4, 6, 8, 10]),
    (22000, 29495, [22000, 24000, 26000, 28000, 30000]),
    (0.3, 0.31, [0.3, 0.305, 0.31]),
    (5, 5, [4.4, 4.6, 4.8, 5.0, 5.2, 5.4, 5.6]),  # one value: a range around it
])
def test_ticks_are_round_and_cover_the_range(low, high, ticks):
    assert nice_ticks(low, high) == ticks


def test_ticks_refuse_a_reversed_range():
    with pytest.raises(ValueError, match=r"nice_ticks: high must be >= low, not 1 < 2"):
        nice_ticks(2, 1)


def test_every_point_is_a_labelled_group_and_the_chosen_one_is_drawn_last():
    svg = scatter([Point(28595, 1, "fig7", "chosen"), Point(23231, 8, "blinn <defaults>", "infeasible"),
                   Point(30000, 1, "fig8")],
                  title="cost & error", x_title="cost (LUT-eq)", y_title="max error (display levels)",
                  hline=(1.0, "requirement 1"), chart_id="c")
    assert svg.startswith('<svg id="c" class="chart"') and svg.endswith("</svg>")
    assert re.findall(r'<g class="point" data-label="([^"]*)" data-kind="(\w+)"', svg) == [
        ("fig8", "feasible"), ("blinn &lt;defaults&gt;", "infeasible"), ("fig7", "chosen")]  # bottom up
    assert "<title>cost &amp; error</title>" in svg and ">cost (LUT-eq)</text>" in svg
    assert svg.count('class="reference"') == 1 and ">requirement 1</text>" in svg
    # the legend names the kinds present, and only those
    assert ">chosen</text>" in svg and ">meets the requirement</text>" in svg and ">other</text>" not in svg
    assert "http" not in svg and "<script" not in svg


def test_points_at_the_same_height_get_labels_that_do_not_overlap():
    svg = scatter([Point(100, 1, "aaaa"), Point(101, 1, "bbbb"), Point(300, 5, "far")],
                  title="t", x_title="x", y_title="y")
    ys = [float(y) for y in re.findall(r'<text x="[^"]*" y="([^"]*)"[^>]*>(?:aaaa|bbbb)</text>', svg)]
    assert len(ys) == 2 and abs(ys[0] - ys[1]) >= 13


@pytest.mark.parametrize("point, message", [
    (dict(x=float("inf"), y=1, label="p"), r"Point\.x must be a finite number, not inf \(point 'p'\)"),
    (dict(x=1, y=None, label="p"), r"Point\.y must be a finite number, not None \(point 'p'\)"),
    (dict(x=1, y=1, label="p", kind="best"), r"Point\.kind must be one of chosen, feasible, infeasible, other, "
                                             r"not 'best'"),
])
def test_a_bad_point_is_refused_naming_the_field(point, message):
    with pytest.raises(ValueError, match=message):
        Point(**point)


def test_no_points_is_refused():
    with pytest.raises(ValueError, match=r"scatter 'chart': points must not be empty"):
        scatter([], title="t", x_title="x", y_title="y")
