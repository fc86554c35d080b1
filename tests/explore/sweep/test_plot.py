"""The sweep's Pareto plots (phongfx.explore.sweep.plot): labelled fronts, and an error-only
sweep drawn against the tool-free cost proxy instead of an empty picture."""

from phongfx.explore.sweep.plot import pareto_plot, short_params, swept

KEY = "torus.phong.max"
PNG = b"\x89PNG\r\n\x1a\n"


def rec(id, method, err, lut=None, mpix=None, **params):
    cost = None if lut is None else {"lut4": lut, "dsp": 0, "fmax_mhz": mpix, "mpixels_per_s": mpix}
    return {"id": id, "method": method, "params": {"n": 16, **params}, "status": "ok", "error": None,
            "metrics": {KEY: err}, "cost": cost}


def test_front_points_are_labelled_by_the_swept_parameters_only(tmp_path):
    records = [rec("a", "fig7", 4.0, 100, 90.0, vec_frac=9, shape_t_frac=8),
               rec("b", "fig7", 2.0, 200, 80.0, vec_frac=10, shape_t_frac=8),
               rec("c", "fig7", 1.0, 300, 70.0, vec_frac=10, shape_t_frac=12)]
    result = pareto_plot(records, tmp_path / "p.png", KEY)
    assert result["labels"]["lut_eq"] == ["vec=9 t=8", "vec=10 t=8", "vec=10 t=12"]  # n is fixed: not shown
    assert result["labels"]["mpixels_per_s"] == ["vec=9 t=8", "vec=10 t=8", "vec=10 t=12"]
    assert (tmp_path / "p.png").read_bytes()[:8] == PNG


def test_labels_name_the_method_when_several_share_the_plot():
    records = [rec("a", "fig7", 1.0, vec_frac=9), rec("b", "fig7", 1.0, vec_frac=10), rec("c", "fig8", 1.0)]
    names = swept(records)
    assert names == {"fig7": ["vec_frac"], "fig8": []}
    assert short_params(records[0], names["fig7"], method=True) == "fig7 vec=9"
    assert short_params(records[2], names["fig8"]) == "fig8"


def test_an_error_only_sweep_is_drawn_against_the_cost_proxy(tmp_path):
    # no synthesis and no proxy in the records (proxy = false, or an older sweep): before, an empty plot
    records = [rec("a", "spherical", 3.0, addr_bits=4), rec("b", "spherical", 1.5, addr_bits=8),
               rec("c", "nosuch", 1.0, addr_bits=8)]  # cannot be priced: left out, counted
    result = pareto_plot(records, tmp_path / "p.png", KEY)
    assert (result["plotted"], result["skipped"]) == (2, 1)
    assert [r["id"] for r in result["lut_eq"]] == ["a", "b"]  # more ROM address bits cost more
    assert result["labels"]["lut_eq"] == ["addr_bits=4", "addr_bits=8"]
    assert "tool-free proxy (ecp5-proxy): no point synthesized" in result["xlabel"]["lut_eq"]
    assert result["mpixels_per_s"] == [] and "proxy" not in result["xlabel"]["mpixels_per_s"]
    assert all(r["cost"] is None for r in records)  # the caller's records are not changed


def test_synthesized_sweeps_are_not_mixed_with_proxy_estimates(tmp_path):
    records = [rec("a", "spherical", 3.0, 100, 50.0, addr_bits=4), rec("b", "spherical", 1.5, addr_bits=8)]
    result = pareto_plot(records, tmp_path / "p.png", KEY)
    assert (result["plotted"], result["skipped"]) == (1, 1)
    assert "proxy" not in result["xlabel"]["lut_eq"]
