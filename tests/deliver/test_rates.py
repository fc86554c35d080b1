"""The report page's pixel-rate section: each costed method at the architecture it was priced
at, its fastest beside it when that is another one, the chosen design's timing and fit."""

import copy

from phongfx.deliver.rates import architecture_text, speed_points, speed_section

from tests.deliver.test_page import MANIFEST


def _slow_conventional(data):
    data = copy.deepcopy(data)
    fast = {"architecture": {"pipeline": 4, "interval": 1}, "pixel_rate_mpx": 28.2, "cost": 41000,
            "clock_mhz": 28.2, "met": False}
    data["methods"]["conventional"] = {
        "feasible": True, "params": {"vec_frac": 10}, "max": 1.0, "mean": 0.04,
        "cost": {"cost": 38019, "unit": "LUT-eq", "pixel_rate_mpx": 20.5, "met": False, "why_not": "speed",
                 "architecture": {"pipeline": 0, "interval": 1}, "fastest": fast}}
    return data


def test_architectures_in_words():
    assert architecture_text({"pipeline": 2, "interval": 2, "share": False}) == "depth 2, interval 2, per-copy inputs"
    assert architecture_text(None) == "depth 0, interval 1, shared inputs"


def test_each_costed_method_is_a_point_and_its_fastest_another():
    points = speed_points(_slow_conventional(MANIFEST))
    assert [(p.label, p.kind, p.x, p.y) for p in points] == [
        ("fig7 (depth 0, interval 1)", "chosen", 34.81, 28595.0),
        ("conventional (depth 0, interval 1)", "infeasible", 20.5, 38019.0),
        ("conventional fastest (depth 4, interval 1)", "other", 28.2, 41000.0)]
    # a fastest that is the architecture priced is the same point: not drawn twice
    data = _slow_conventional(MANIFEST)
    data["methods"]["conventional"]["cost"]["fastest"]["architecture"] = {"pipeline": 0, "interval": 1}
    assert len(speed_points(data)) == 2


def test_the_section_tables_what_is_recorded_and_nothing_when_nothing_is():
    html = speed_section(_slow_conventional(MANIFEST))
    assert "Asked: 30 Mpixel/s." in html and "10 architectures priced per method" in html
    assert "<td>too slow</td>" in html and "<td>met</td>" in html
    assert "The chosen design's timing" in html and "574.56" not in html and "575 ns" in html
    data = {k: v for k, v in MANIFEST.items() if k != "timing"}
    data["methods"] = {name: {k: v for k, v in r.items() if k != "cost"} for name, r in MANIFEST["methods"].items()}
    assert speed_section(data) == ""
