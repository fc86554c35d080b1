import json
import os

import pytest

from phongfx.explore import report
from phongfx.explore.report import (DSP_LUT_WEIGHT, build_report, cheapest_invisible, load, lut_equivalent,
                                    pareto, pareto_plot, summary_markdown)

KEY = "torus.phong.max"
PNG = b"\x89PNG\r\n\x1a\n"


def rec(id, method, err, lut=None, dsp=0, mpix=None, status="ok", error=None, **params):
    cost = None if lut is None else {"lut4": lut, "ff": 10, "carry": 1, "dsp": dsp, "bram_bits": 0,
                                     "fmax_mhz": mpix, "mpixels_per_s": mpix, "latency": 3}
    return {"id": id, "method": method, "params": params, "status": status, "error": error, "seconds": 0.1,
            "metrics": {} if err is None else {KEY: err}, "cost": cost}


def front_records():
    return [rec("A", "fig7", 5.0, 100, mpix=100.0), rec("B", "fig7", 2.0, 200, mpix=150.0),
            rec("C", "fig8", 3.0, 300, mpix=120.0),  # dominated by B in cost and in speed
            rec("D", "fig8", 2.0, 200, mpix=150.0),  # tied with B in both: kept
            rec("E", "fig8", 1.0, 100, dsp=1, mpix=90.0),  # 100 + 958 LUT-equivalents
            rec("H", "fig7", 5.0, 150, mpix=200.0),  # dominated by A in cost; dominates A in speed
            rec("F", "fig7", 0.1, 10, mpix=500.0, status="failed", error="boom"),
            rec("G", "fig8", 0.5)]  # no cost


def ids(records):
    return [r["id"] for r in records]


def test_lut_equivalent():
    assert lut_equivalent({"lut4": 100, "dsp": 2}) == 100 + 2 * DSP_LUT_WEIGHT
    assert lut_equivalent({"lut4": 100, "dsp": 2}, dsp_weight=10) == 120
    assert lut_equivalent(None) is None


def test_pareto_cost_excludes_dominated_keeps_ties():
    front = pareto(front_records(), KEY, "lut_eq")
    assert ids(front) == ["A", "B", "D", "E"]  # cheapest first; C, H dominated; F failed; G no cost


def test_pareto_speed_is_maximized_by_default():
    assert ids(pareto(front_records(), KEY, "mpixels_per_s")) == ["H", "B", "D", "E"]
    # the same records with speed minimized: E is both slowest and most accurate
    assert ids(pareto(front_records(), KEY, "mpixels_per_s", maximize=False)) == ["E"]


def test_pareto_equal_error_keeps_only_cheapest():
    records = [rec("x", "m", 1.0, 50), rec("y", "m", 1.0, 60), rec("z", "m", 1.0, 50)]
    assert ids(pareto(records, KEY, "lut4")) == ["x", "z"]


def test_load_ignores_torn_last_line(tmp_path):
    path = tmp_path / "points.jsonl"
    records = front_records()
    path.write_text("".join(json.dumps(r) + "\n" for r in records) + '{"id": "torn", "met')
    assert load(path) == records


def test_load_rejects_bad_middle_line(tmp_path):
    path = tmp_path / "points.jsonl"
    path.write_text('{"id": 1}\nnot json\n{"id": 2}\n')
    with pytest.raises(ValueError, match=r"^.*points\.jsonl line 2 is not JSON"):
        load(path)


def test_pareto_plot_writes_png_and_returns_fronts(tmp_path):
    path = tmp_path / "pareto.png"
    result = pareto_plot(front_records(), path)
    assert path.read_bytes()[:8] == PNG
    assert ids(result["lut_eq"]) == ["A", "B", "D", "E"]
    assert ids(result["mpixels_per_s"]) == ["H", "B", "D", "E"]
    assert result["plotted"] == 6 and result["skipped"] == 1  # G has no cost; F failed
    assert os.listdir(tmp_path) == ["pareto.png"]


def test_pareto_plot_is_atomic(tmp_path, monkeypatch):
    import matplotlib.figure

    path = tmp_path / "pareto.png"
    path.write_bytes(b"old")

    def fail(self, *args, **kwargs):
        raise OSError("disk full")

    monkeypatch.setattr(matplotlib.figure.Figure, "savefig", fail)
    with pytest.raises(OSError, match=r"^disk full$"):
        pareto_plot(front_records(), path)
    assert path.read_bytes() == b"old" and os.listdir(tmp_path) == ["pareto.png"]


def summary_records():
    return [rec("f1", "fig7", 0.9, 500, dsp=2, vec_frac=10),  # 2416 LUT-eq
            rec("f2", "fig7", 1.0, 2000, dsp=0, vec_frac=9),  # cheapest at exactly 1 level
            rec("f3", "fig7", 1.5, 100, vec_frac=7),  # cheaper but visible
            rec("s1", "spherical", 3.0, 50, addr_bits=5), rec("s2", "spherical", 1.2, 80, addr_bits=6),
            rec("x1", "fig8", None, status="failed", error="ValueError: frac must be 0.m\ntraceback", k=1)]


def row(text, label):
    return next(line for line in text.splitlines() if line.startswith(f"| {label} |"))


def test_summary_picks_cheapest_invisible_point():
    text = summary_markdown(summary_records())
    assert "vec_frac=9" in row(text, "fig7") and "| 1.000 |" in row(text, "fig7")
    spherical = row(text, "spherical")
    assert "none ≤ 1 level" in spherical and "addr_bits=6" in spherical and "| 1.200 |" in spherical
    assert "* `x1` fig8 (k=1): ValueError: frac must be 0.m" in text
    assert "6 points: 5 ok, 1 failed." in text
    picks = cheapest_invisible(summary_records())
    assert picks["fig7"][0]["id"] == "f2" and picks["fig7"][1] is True
    assert picks["spherical"][0]["id"] == "s2" and picks["spherical"][1] is False


def test_summary_splits_methods_by_shininess():
    records = [rec("a", "fig7", 0.5, 100, n=4), rec("b", "fig7", 0.5, 90, n=64)]
    picks = cheapest_invisible(records)
    assert {label: r["id"] for label, (r, _) in picks.items()} == {"fig7 (n=4)": "a", "fig7 (n=64)": "b"}


def test_build_report_links_plot_and_baseline(tmp_path):
    sweep = tmp_path / "sweep"
    sweep.mkdir()
    records = summary_records() + [rec("c1", "blinn", 0.4, 800, dsp=4, vec_frac=12)]
    (sweep / "points.jsonl").write_text("".join(json.dumps(r) + "\n" for r in records))
    (sweep / "points.csv").write_text("id\n")
    out = tmp_path / "report"
    index = build_report(out_dir=str(out), sweep_dir=str(sweep), tables=())
    text = open(index).read()
    assert index == str(out / "index.md")
    assert "![Pareto plot of torus.phong.max](pareto.png)" in text and (out / "pareto.png").read_bytes()[:8] == PNG
    assert "No point has `torus.self.max`." in text and not (out / "pareto_torus_self_max.png").exists()
    assert "[points.csv](../sweep/points.csv)" in text
    assert "## Blinn–Phong baseline" in text and "| blinn | vec_frac=12 | 0.400 |" in text
    assert "vec_frac=9" in row(text, "fig7")


def test_build_report_plots_each_error_key(tmp_path):
    sweep = tmp_path / "sweep"
    sweep.mkdir()
    records = summary_records()
    for r in records:
        if r["metrics"]:
            r["metrics"]["torus.self.max"] = r["metrics"][KEY] / 4  # all within a level of their own form
    (sweep / "points.jsonl").write_text("".join(json.dumps(r) + "\n" for r in records))
    out = tmp_path / "report"
    text = open(build_report(out_dir=str(out), sweep_dir=str(sweep), tables=())).read()
    assert "![Pareto plot of torus.self.max](pareto_torus_self_max.png)" in text
    assert (out / "pareto_torus_self_max.png").read_bytes()[:8] == PNG
    self_part = text.split("### Cheapest invisible-error datapaths (`torus.self.max`)")[1]
    assert "addr_bits=5" in row(self_part, "spherical")  # 3.0 / 4 = 0.75: now invisible, and cheapest
    with pytest.raises(ValueError, match=r"^error_keys must be a non-empty sequence of metric keys, not 'x'$"):
        build_report(out_dir=str(out), sweep_dir=str(sweep), tables=(), error_keys="x")


def test_build_report_without_sweep_says_run_make_sweep(tmp_path):
    index = build_report(out_dir=str(tmp_path / "r"), sweep_dir=str(tmp_path / "none"), tables=())
    assert "run `make sweep` first" in open(index).read()
    assert not (tmp_path / "r" / "pareto.png").exists()


def test_build_report_leaves_index_on_error(tmp_path, monkeypatch):
    sweep = tmp_path / "sweep"
    sweep.mkdir()
    (sweep / "points.jsonl").write_text(json.dumps(summary_records()[0]) + "\n")
    out = tmp_path / "report"
    out.mkdir()
    (out / "index.md").write_text("old report\n")

    def fail(*args, **kwargs):
        raise RuntimeError("plot failed")

    monkeypatch.setattr(report, "pareto_plot", fail)
    with pytest.raises(RuntimeError, match=r"^plot failed$"):
        build_report(out_dir=str(out), sweep_dir=str(sweep), tables=())
    assert (out / "index.md").read_text() == "old report\n"


def test_build_report_rejects_unknown_table(tmp_path):
    with pytest.raises(ValueError, match=r"^unknown table 'nope'; valid tables: lyon, szirmay, schlick, hast, cost, proxy, pipeline, clock, extremes$"):
        build_report(out_dir=str(tmp_path), sweep_dir=str(tmp_path), tables=("nope",))


def test_build_report_embeds_table_markdown_and_plots(tmp_path):
    index = build_report(out_dir=str(tmp_path / "r"), sweep_dir=str(tmp_path), tables=("schlick",))
    text = open(index).read()
    assert "## Figure 1, measured" in text  # the module's heading, one level down
    assert "![schlick figure1.png](schlick/figure1.png)" in text
    assert (tmp_path / "r" / "schlick" / "figure1.png").read_bytes()[:8] == PNG


def _asic(id, method, err, area, mpix=None, model=None):
    cost = {"area_um2": area, "cell_count": int(area // 30), "area_delay": area * 10.0,
            "fmax_mhz": mpix, "mpixels_per_s": mpix}
    if model:
        cost = {"area_um2": area, "model": model}
    return {"id": id, "method": method, "params": {"vec_frac": 10}, "status": "ok", "error": None,
            "seconds": 0.1, "metrics": {KEY: err}, "cost": cost, "synth": {"target": "asic", "device": "osu035"}}


def test_standard_cell_records_are_compared_in_square_microns(tmp_path):
    records = [_asic("A", "fig7", 0.9, 1_600_000.0, 100.0), _asic("B", "fig8", 0.8, 1_300_000.0, 105.0),
               _asic("C", "fig8", 0.7, 900_000.0, model="asic-proxy")]  # cheaper, but only an estimate
    assert report.cost_key(records) == "area_um2"
    picks = cheapest_invisible(records)
    assert picks["fig8"][0]["id"] == "B"  # a synthesized cost before a proxy's
    text = summary_markdown(records)
    assert "cost = area on asic osu035" in text and "| fig8 | vec_frac=10 | 0.800 | 1,300,000 | 43333 |" in text
    front = pareto_plot(records, tmp_path / "p.png")
    assert ids(front["area_um2"]) == ["B"]  # the front over synthesized points only
    assert front["plotted"] == 3 and (tmp_path / "p.png").read_bytes().startswith(PNG)


def test_build_report_shows_the_synthesis_progress_of_its_tables(tmp_path, monkeypatch, capsys):
    # `phongfx report` synthesizes for minutes: every candidate is named, counted and timed
    import re

    from phongfx.explore.tables import cost as cost_table

    def fake(name, *, target, freq, workdir, progress=None, **kwargs):
        progress("yosys")
        return {"lut4": 10, "ff": 20, "carry": 1, "dsp": 1, "bram_bits": 0, "fmax_mhz": 99.0, "met": False,
                "pixels_per_second": 99e6, "latency": 3, "cached": True}

    monkeypatch.setattr(cost_table, "synth", fake)
    build_report(out_dir=tmp_path / "r", sweep_dir=tmp_path / "none", tables=("cost",), quick=True)
    lines = [re.sub(r" \d+ s$", "", line) for line in capsys.readouterr().err.splitlines()]
    assert lines == [f"cost: synthesizing candidate {i} of 3 ({block}){stage}"
                     for i, block in enumerate(("difference", "shape", "root"), 1) for stage in ("", ": yosys")]


def test_the_quick_report_runs_every_synthesizing_table_small(tmp_path, monkeypatch):
    # `report --quick`, "a smoke run", had run 830 s and was at the proxy table's point 13 of 22;
    # now 96 s on 2 cores with an empty cache: 4 FPGA syntheses and 2 standard-cell runs
    from phongfx.explore.synth import fpga
    from phongfx.explore.tables import clock, cost, pipeline, proxy

    runs = []

    def fake(name, *, config=None, target="ecp5", device=None, freq=150, seed=1, workdir=None, progress=None):
        runs.append((name, target, getattr(config, "pipeline", 0)))
        raise fpga.SynthError("stand-in")

    for module in (fpga, cost, proxy):
        monkeypatch.setattr(module, "synth", fake)
    calls = {}
    for module in (pipeline, proxy, clock):
        original = module.run_table

        def recorded(name, out_dir=None, original=original, **options):
            calls[name] = options
            try:
                return original(name, out_dir=out_dir, **options)
            except fpga.SynthError:
                raise KeyError(name) from None  # stop here: what matters is what was asked
        monkeypatch.setattr(module, "run_table", recorded)
    for name in ("pipeline", "proxy", "clock"):
        with pytest.raises(KeyError):
            build_report(out_dir=tmp_path / "r", sweep_dir=tmp_path / "none", tables=(name,), quick=True)
    assert calls == {"pipeline": {"names": ("shape",), "depths": (0, 2), "seeds": (1,)},
                     "proxy": {"points": (("shape", "shape", None), ("root", "root", None))},
                     "clock": {"selected": [("shape", "shape", None, 0)]}}
    assert runs[0] == ("shape", "ecp5", 0) and runs[1][:2] == ("shape", "asic")


def test_a_table_whose_synthesis_fails_is_shown_and_the_others_still_run(tmp_path, monkeypatch, capsys):
    from phongfx.cli import main
    from phongfx.explore.synth.fpga import SynthError
    from phongfx.explore.tables import pipeline

    def fails(name, out_dir=None, **options):
        raise SynthError("nextpnr failed (exit code 1); log x/nextpnr.log:\nERROR: Net 'in_shift[39]' is multiply driven")
    monkeypatch.setattr(pipeline, "run_table", fails)
    out = tmp_path / "r"
    assert main(["report", "--out", str(out), "--sweep", str(tmp_path / "none"), "--tables", "pipeline", "schlick"]) == 1
    err = capsys.readouterr().err.splitlines()
    assert err == ["report: table pipeline FAILED: nextpnr failed (exit code 1); log x/nextpnr.log:",
                   f"phongfx: 1 table failed (pipeline); see {out / 'index.md'}"]
    text = (out / "index.md").read_text()
    assert "## pipeline: failed\n\nA synthesis failed: nextpnr failed (exit code 1)" in text
    assert "Figure 1, measured" in text  # schlick's table, after the failed one
