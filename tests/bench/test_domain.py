"""Smoke test of ``bench/domain.py``: every stage of a domain measurement timed, on the
designs the compiler chooses for the example scenes."""

import json

from bench.domain import DESIGNS, STAGES, main, measure


def test_every_stage_is_timed_on_the_chosen_design():
    row = measure("torus", *DESIGNS["torus"], points=3000)
    assert row["points"] == 3000 and set(row["seconds"]) == set(STAGES)
    assert all(rate > 0 for rate in row["points_per_second"].values())
    assert row["all_points_per_second"] < row["search_points_per_second"]  # sampling and reference cost too
    assert row["max_error_levels"] <= 1  # the chosen design meets its requirement on these points


def test_main_writes_the_json(tmp_path, capsys):
    assert main(["--points", "2000", "--out", str(tmp_path)]) == 0
    data = json.loads((tmp_path / "domain.json").read_text())
    assert [row["scene"] for row in data["rows"]] == list(DESIGNS)
    assert "| torus | fig7 | 2,000 |" in capsys.readouterr().out
