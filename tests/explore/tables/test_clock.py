"""The clock proxy's calibration (phongfx.explore.tables.clock): the points, the fit, the
table on stand-in synthesis, and the stored margins against the real flows."""

import pytest

from phongfx.core.registry import get_block
from phongfx.explore.synth import fpga
from phongfx.explore.synth.clock import (COEFFICIENTS, ERROR, FEATURES, MARGIN, clock_netlist, critical_path,
                                        promise_margin, proxy_clock)
from phongfx.explore.tables import clock as clock_table


def test_points_cover_every_datapath_at_every_depth():
    points = clock_table.points()
    depths = {}
    for label, _, config, depth in points:
        depths.setdefault(label, []).append(depth)
        if depth is not None:
            assert getattr(config, "blend", config).pipeline == depth
    assert depths["fig7"] == depths["shader"] == [0, 1, 2, 3, 4]
    assert depths["conventional"] == [None]  # no depth: one row
    assert {"fig8", "halfway_datapath", "blinn", "spherical", "shader blinn×2"} <= set(depths)


def test_the_promise_margin_takes_off_the_largest_optimism():
    assert promise_margin([0.25, -0.1, 0.0]) == pytest.approx(0.2)
    assert promise_margin([-0.3, -0.01]) == 0.0  # nowhere high: nothing to give up
    # with the margin off, no estimate is above its measure and the worst is as far below
    errors = [0.46, -0.05, 0.1]
    promised = [(1 + e) * (1 - promise_margin(errors)) - 1 for e in errors]
    assert max(promised) == pytest.approx(0.0) and min(promised) == pytest.approx(0.95 / 1.46 - 1)


def test_fit_recovers_the_periods_of_known_coefficients():
    truth = {k: v for k, v in zip(FEATURES, (0.9, 2.5, 0.0, 0.08, 0.4, 0.0, 0.2, 0.3, 0.15))}
    blocks = [get_block(name, pipeline=depth) for name in ("shape", "difference", "diffuse", "lirp")
              for depth in (0, 2)]
    netlists = [clock_netlist(block, "asic") for block in blocks]
    periods = [critical_path(netlist, truth)[0] for netlist in netlists]
    start = dict.fromkeys(FEATURES, 1.0)
    found = clock_table.fit(netlists, periods, start)
    assert set(found) == set(FEATURES) and min(found.values()) >= 0
    for netlist, period in zip(netlists, periods):
        assert critical_path(netlist, found)[0] == pytest.approx(period, rel=0.02)


def _fake_synth(name, *, config, target, device, freq, workdir, progress, seed=1):
    result = proxy_clock(get_block(name, config), target)
    return {"fmax_mhz": result["estimate_mhz"] / 1.25, "critical_path": {"from": "a", "to": "b", "ns": 1.0},
            "lut4": 1500, "carry": 50, "dsp": 3}


def test_table_rows_errors_and_summary(monkeypatch):
    monkeypatch.setattr(fpga, "synth", _fake_synth)
    selected = [p for p in clock_table.points() if p[0] == "fig7" and p[3] in (0, 4)]
    result = clock_table.clock_table(selected, progress=lambda text: None)
    assert len(result["rows"]) == 4 and all("netlist" not in row for row in result["rows"])
    assert all(row["error"] == pytest.approx(0.25) for row in result["rows"])
    # the estimate is 25 % high everywhere: giving up 20 % of it makes it exact (with margin 0
    # stored, both points' promises are above synthesis)
    assert result["summary"]["ecp5"] == {"rows": 2, "median": pytest.approx(0.25), "max": pytest.approx(0.25),
                                         "margin": pytest.approx(0.2), "misses": 2 * (MARGIN["ecp5"] < 0.2),
                                         "promise_max": pytest.approx(abs(1.25 * (1 - MARGIN["ecp5"]) - 1))}
    ecp5 = [row for row in result["rows"] if row["target"] == "ecp5"]
    assert ecp5[0]["lut4"] == 1600 and ecp5[0]["dsp"] == 3 and ecp5[0]["proxy_dsp"] == 39
    assert result["resources"]["dsp"]["max"] == pytest.approx(1 - 3 / 39)
    text = clock_table.markdown(result)
    assert "| fig7 | 4 | 1 |" in text and "+25.0%" in text and "median error 25.0%" in text
    assert "margin needed 20.0%" in text


@pytest.mark.slow
def test_stored_margins_hold_on_fig7_against_the_real_flows():
    """The stored coefficients give the rows proxy_clock gives, and its promise holds."""
    selected = [p for p in clock_table.points() if p[0] == "fig7" and p[3] in (0, 4)]
    rows = clock_table.calibration_rows(selected, progress=lambda text: None)
    for row in rows:
        block = get_block("fig7", pipeline=row["depth"])
        stated = proxy_clock(block, row["target"])
        assert row["promise_mhz"] == pytest.approx(stated["fmax_mhz"])
        assert row["proxy_mhz"] == pytest.approx(stated["estimate_mhz"])
        # a promise: never above synthesis, and no further below it than the stored error
        assert -ERROR[row["target"]] <= row["promise_error"] <= 1e-9
    assert set(COEFFICIENTS) == {row["target"] for row in rows}
