"""``phongfx.explore.tables.pipeline``: Fmax, size and latency against pipeline depth."""

import json
import re

import pytest

from phongfx.core.registry import get_block
from phongfx.explore.tables import pipeline as pipeline_table
from phongfx.explore.synth import fpga as synth
from phongfx.explore.tables.pipeline import DEPTHS, NAMES, SEEDS, markdown, pipeline_rows, run_table, to_json


def _fake_synth(calls):
    """A stand-in for :func:`phongfx.explore.synth.fpga.synth`: 35 MHz more per depth, normalize 40 MHz
    higher, seed 1 MHz below and seed 3 5 MHz above seed 2, latency from the config as the
    real one reports it, the DSPs' internal multiply untimed from depth 1."""

    def fake(name, *, config, target, freq, workdir, device=None, seed=1, progress=None):
        calls.append((name, config.pipeline, target, freq, seed))
        if progress is not None:
            progress("yosys")
        fmax = 30.0 + 35 * config.pipeline + (40 if name == "normalize" else 0) + {1: -1, 2: 0, 3: 5}[seed]
        return {"fmax_mhz": fmax, "lut4": 1000 - 10 * config.pipeline + seed, "ff": 2000 + 500 * config.pipeline,
                "dsp": 39, "latency": get_block(name, config=config).latency,
                "dsp_untimed": 39 if config.pipeline else 0, "fmax_bound_mhz": min(fmax, 256.4),
                "critical_path": {"from": f"{name}.a", "to": f"{name}.b", "ns": 1e3 / fmax,
                                  "logic_ns": 4.0, "routing_ns": 1e3 / fmax - 4.0},
                "cached": True}
    return fake


@pytest.fixture
def fake(monkeypatch):
    calls = []
    monkeypatch.setattr(synth, "synth", _fake_synth(calls))
    return calls


def test_progress_counts_every_run_and_passes_the_stages_through(fake):
    lines = []
    pipeline_rows(names=("fig7", "fig8"), depths=(0, 3), seeds=(1, 2), progress=lines.append)
    assert [re.sub(r" \d+ s$", "", line) for line in lines[:4]] == [
        "synthesizing candidate 1 of 8 (fig7, pipeline=0 seed=1)",
        "synthesizing candidate 1 of 8 (fig7, pipeline=0 seed=1): yosys",
        "synthesizing candidate 2 of 8 (fig7, pipeline=0 seed=2)",
        "synthesizing candidate 2 of 8 (fig7, pipeline=0 seed=2): yosys"]
    assert re.sub(r" \d+ s$", "", lines[-2]) == "synthesizing candidate 8 of 8 (fig8, pipeline=3 seed=2)"
    assert len(lines) == 16


def test_rows_cover_every_name_and_depth_and_take_the_median_seed(fake):
    rows = pipeline_rows()
    assert [(r["name"], r["depth"]) for r in rows] == [(n, d) for n in NAMES for d in DEPTHS]
    assert fake[:3] == [("fig7", 0, "ecp5", 150, seed) for seed in SEEDS] and SEEDS == (1, 2, 3)
    fig7 = [r for r in rows if r["name"] == "fig7"]
    assert [r["latency"] for r in fig7] == [get_block("fig7", pipeline=d).latency for d in DEPTHS]
    assert fig7[0]["latency"] == 17  # depth 0 is the original design
    # the median seed (2) gives Fmax and the rest of the row; every seed's Fmax is kept
    assert fig7[1]["fmax_mhz"] == 65.0 and fig7[1]["fmax_seeds"] == [64.0, 65.0, 70.0]
    assert fig7[1]["lut4"] == 992 and fig7[1]["dsp_untimed"] == 39
    # 150 MHz is met only where the stand-in reaches it: normalize at 30 + 40 + 35·3 = 175
    assert [r["met"] for r in rows if r["name"] == "normalize"] == [False, False, False, True, True]


def test_markdown_names_the_first_depth_that_meets_the_goal_or_the_limit(fake, tmp_path):
    result = run_table("pipeline", tmp_path)
    text = markdown(result)
    assert "median of 3 placement seeds" in text
    assert re.search(r"^\| fig7 \| 0 \| 30\.0 ✗ \| 29\.0 / 30\.0 / 35\.0 \| 1002 \| 2000 \| 39 \| 17 \| "
                     r"fig7\.a → fig7\.b \(4\.00 \+ 29\.33\) \|$", text, re.M), text
    assert re.search(r"^\* normalize: meets 150 MHz from depth 3 \(latency 15 cycles\); critical path at "
                     r"depth 4: normalize\.a → normalize\.b", text, re.M), text
    # fig8 at 30 + 35·4 = 170 MHz only at the deepest depth; with one depth fewer it falls short
    assert re.search(rf"^\* fig8: meets 150 MHz from depth 4 \(latency {get_block('fig8', pipeline=4).latency} "
                     rf"cycles\); critical path at depth 4: fig8\.a → fig8\.b", text, re.M), text
    short = markdown({**result, "rows": [row for row in result["rows"] if row["depth"] < 4]})
    assert re.search(r"^\* fig8: \*\*falls short of 150 MHz\*\*: 135\.0 MHz at depth 3; critical path at "
                     r"depth 3: fig8\.a → fig8\.b", short, re.M), short
    assert re.search(r"^Caveat: .* nextpnr does not time the multiply between them; .* 3\.9 ns, so the DSPs "
                     r"themselves bound the clock at 256 MHz", text, re.M), text
    assert "![Fmax against depth](pipeline_fmax.png)" in text
    png = (tmp_path / "pipeline_fmax.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 5000
    assert json.loads(to_json(result))["rows"] == result["rows"]


def test_unknown_table():
    with pytest.raises(ValueError, match=r"^unknown table 'lyon'; valid tables: pipeline$"):
        run_table("lyon")


@pytest.mark.slow
@pytest.mark.needs_yosys
def test_real_synthesis_of_a_small_block():
    rows = pipeline_rows(names=("shape",), depths=(0, 1), seeds=(1,))
    assert [r["latency"] for r in rows] == [3, 5]
    assert all(r["fmax_mhz"] > 20 and r["dsp"] == 2 for r in rows)
    # depth 1 registers the two products: more flip-flops, a shorter critical path
    assert rows[1]["ff"] > rows[0]["ff"]
    assert rows[1]["critical_path"]["ns"] < rows[0]["critical_path"]["ns"]
    assert pipeline_table.markdown({"target": "ecp5", "freq": 150, "rows": rows}).count("| shape |") == 2
