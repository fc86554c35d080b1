"""Smoke runs of the benchmarks (``make bench`` runs them at full size)."""

import json

import pytest

from bench import rtl, scaling


@pytest.mark.needs_verilator
def test_scaling_smoke_checks_every_size_and_plots(tmp_path):
    rows = scaling.measure(blocks=("euler", "shape"), sizes=(64, 256))
    assert [(r["block"], r["pixels"]) for r in rows] == [("euler", 64), ("euler", 256),
                                                         ("shape", 64), ("shape", 256)]
    assert all(r["mismatches"] == 0 and r["check"] > 0 and r["golden"] > 0 for r in rows)
    path = scaling.plot(rows, str(tmp_path / "scaling.png"))
    assert open(path, "rb").read(8) == b"\x89PNG\r\n\x1a\n"


@pytest.mark.needs_verilator
def test_rtl_smoke_reports_every_back_end(tmp_path):
    out = tmp_path / "rtl.json"
    assert rtl.main(["--pixels", "300", "--small", "40", "--no-cold-build", "--out", str(out)]) == 0
    data = json.loads(out.read_text())
    assert data["frame"]["pixels"] == 300 and data["frame"]["mismatches"] == 0
    assert [row["backend"] for row in data["backends"]] == ["amaranth", "verilator", "verilator-fast"]
    assert data["backends"][0]["ratio_to_amaranth"] == 1.0
