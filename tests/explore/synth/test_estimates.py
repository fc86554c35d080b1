"""Tool-free estimates kept (phongfx.explore.synth.estimates): a known design is priced without
being elaborated, from memory or from the per-user cache's proxy/ folder, and any change of the
design, the target or the estimators' code prices it afresh."""

import json

import pytest
from amaranth.back import rtlil

from phongfx.core.cache import folder
from phongfx.core.registry import get_block
from phongfx.explore.synth import estimates, toolrun
from phongfx.explore.synth.estimates import cached_estimate, estimate_key
from phongfx.explore.synth.proxy import proxy_cost, proxy_estimate
from phongfx.hdl import identity


@pytest.fixture
def home(tmp_path, monkeypatch):
    monkeypatch.setenv("PHONGFX_CACHE", str(tmp_path / "cache"))
    monkeypatch.setattr(estimates, "_KNOWN", {})
    return tmp_path / "cache"


def test_computed_once_then_read_back(home, monkeypatch):
    calls = []

    def compute():
        calls.append(1)
        return {"fmax_mhz": 123.5, "path": ["a", "b"]}

    shape = get_block("shape")
    first = cached_estimate("clock", shape, "ecp5", None, compute)
    assert first == {"fmax_mhz": 123.5, "path": ["a", "b"]} and len(calls) == 1
    first["path"].append("mine")  # each call has its own copy
    assert cached_estimate("clock", get_block("shape"), "ecp5", None, compute) == {"fmax_mhz": 123.5,
                                                                                   "path": ["a", "b"]}
    key = estimate_key("clock", shape, "ecp5", None)
    assert json.loads((folder("proxy") / key / "estimate.json").read_text()) == {"fmax_mhz": 123.5,
                                                                                 "path": ["a", "b"]}
    monkeypatch.setattr(estimates, "_KNOWN", {})  # a new process
    assert cached_estimate("clock", shape, "ecp5", None, compute)["fmax_mhz"] == 123.5 and len(calls) == 1
    # another kind, target, device or design is another estimate
    for kind, block, target, device in (("area", shape, "ecp5", None), ("clock", shape, "ice40", None),
                                        ("clock", shape, "ecp5", "85k"),
                                        ("clock", get_block("shape", k=1), "ecp5", None)):
        cached_estimate(kind, block, target, device, compute)
    assert len(calls) == 5


def test_an_edit_of_the_sources_or_the_estimators_prices_afresh(home, monkeypatch):
    shape = get_block("shape")
    key = estimate_key("area", shape, "ecp5", None)
    monkeypatch.setattr(identity, "source_digest", lambda: "edited hardware")
    hardware = estimate_key("area", shape, "ecp5", None)
    monkeypatch.setattr(estimates, "_estimators_digest", lambda: "edited estimator")
    assert len({key, hardware, estimate_key("area", shape, "ecp5", None)}) == 3


def test_the_proxy_prices_a_known_design_without_elaborating_it(home, monkeypatch):
    conversions = []
    convert = rtlil.convert
    monkeypatch.setattr(rtlil, "convert", lambda *a, **k: conversions.append(1) or convert(*a, **k))
    monkeypatch.setattr(toolrun, "_ELABORATED", {})
    fig7 = get_block("fig7")
    priced = proxy_estimate(fig7, "ecp5")
    # the text elaborated for the estimate is kept: proxy_cost reads it again
    assert priced == {**proxy_cost(fig7), "model": "ecp5-proxy"} and len(conversions) == 1
    assert priced["dsp"] >= 39  # Figure 7 needs 39 DSPs in synthesis; the proxy counts no fewer
    monkeypatch.setattr(toolrun, "_ELABORATED", {})
    assert proxy_estimate(get_block("fig7"), "ecp5") == priced and len(conversions) == 1
    monkeypatch.setattr(estimates, "_KNOWN", {})
    assert proxy_estimate(get_block("fig7"), "ecp5") == priced and len(conversions) == 1
    area = proxy_estimate(fig7, "asic")
    assert area["model"] == "asic-proxy" and area["area_um2"] > 0 and len(conversions) == 2
    with pytest.raises(ValueError, match=r"^library must be one of 'osu018', 'osu035', 'sg13g2_stdcell_typ_1p20V_25C', "
                                         r"'sg13g2_stdcell_slow_1p08V_125C', 'sg13g2_stdcell_fast_1p32V_m40C', not 'x'$"):
        proxy_estimate(fig7, "asic", "x")
