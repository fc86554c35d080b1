"""Smoke test of ``bench/golden.py`` and its rival Figure 7 models.

The bit-exact rivals (apytypes arrays, a per-pixel Python loop) must be bit-identical to
our golden model, or the throughput ratios would compare different computations; the
float64 one must compute the same formula (within the golden model's rounding).
"""

import json

import numpy as np
import pytest

from phongfx.config import fig7_config
from phongfx.core.registry import get_block

from bench.golden import inputs, main, peak_memory
from bench.golden_models import fig7_apytypes, fig7_float, fig7_loop

apytypes = pytest.importorskip("apytypes")


@pytest.mark.parametrize("config", [
    fig7_config(),
    fig7_config().replace(lights=1, shape=fig7_config().shape.replace(k=4, rounding="truncate")),
    fig7_config().replace(normalize=fig7_config().normalize.replace(z="1.14", y2="1.13", g="1.14")),
], ids=["default", "k4-truncate", "wide-normalizer"])
def test_rivals_are_bit_identical_to_the_golden_model(config):
    block = get_block("fig7", config=config)
    raw = block.stimulus(count=3000, seed=5)  # directed extremes first: N' = 0, R = L, grazing, V = -L
    ours = block.golden(raw)
    assert set(ours) == {f"{kind}{i}" for i in range(config.lights) for kind in ("spec", "diff")}
    for rival in (fig7_apytypes(config, raw), fig7_loop(config, raw)):
        for key, value in ours.items():
            np.testing.assert_array_equal(rival[key], value, err_msg=key)
    assert max(int(v.max()) for v in ours.values()) > 0  # the sample shades something


def test_the_float64_rival_is_the_same_formula_unquantized():
    block = get_block("fig7")
    raw = block.stimulus(count=20000, seed=5)
    ours, floats = block.golden(raw), fig7_float(block.config, raw)
    assert set(floats) == set(ours)
    for key, value in ours.items():
        error = np.abs(value * block.config.outputs[key][0].lsb - floats[key])
        # the diffuse term within 2 LSB of its 10 fraction bits; the highlight, where 2x is
        # large and steep, within 0.03 (the roundings of D, D·D and 2x, amplified by f_k)
        assert error.max() <= (2 ** -9 if key.startswith("diff") else 0.03), key
        assert np.median(error) < 2 ** -12, key
    assert floats["spec0"].max() == pytest.approx(1.0) and floats["diff0"].max() > 0.99


def test_rivals_refuse_what_they_do_not_model():
    config = fig7_config().replace(specular="fig8")
    with pytest.raises(ValueError, match=r"^the rival models cover Figure 7 with lights and viewer at infinity"):
        fig7_loop(config, {})


def test_inputs_tile_to_the_batch_size():
    raw = inputs("fig7", 5000)
    assert {k: v.shape[0] for k, v in raw.items()} == dict.fromkeys(raw, 5000)
    euler = inputs("euler", 3000)
    assert euler["init"][0] == 1 and len(euler["init"]) == 3000


def test_bench_runs_small_and_writes_json(tmp_path, capsys):
    assert main(["--sizes", "0.002", "--loop-pixels", "300", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "| fig7 | 0.002 |" in out and "| euler | 0.002 |" in out and "ours time ÷ float64" in out
    result = json.loads((tmp_path / "golden.json").read_text())
    fig7 = next(r for r in result["rows"] if r["datapath"] == "fig7")
    assert fig7["ratio_apytypes"] == pytest.approx(fig7["apytypes_seconds"] / fig7["ours_seconds"])
    fastest = min(fig7["float64_seconds"], fig7["float64_whole_seconds"])
    assert fig7["ratio_float64"] == pytest.approx(fig7["ours_seconds"] / fastest)
    assert fig7["ours_peak_bytes"] >= 0 and result["loop"]["pixels"] == 300
    assert result["targets"]["ratio_float64"] == 2.0
    assert [p.name for p in tmp_path.iterdir()] == ["golden.json"]  # no temporary left behind


def test_peak_memory_grows_with_the_batch():
    assert peak_memory("fig7", "whole", 400_000) > peak_memory("fig7", "whole", 20_000) + 20 * 2**20


def test_chunks_keep_the_peak_memory_down():
    # the whole batch's temporaries against one chunk's and the outputs (measured: half)
    assert peak_memory("fig7", "ours", 400_000) < peak_memory("fig7", "whole", 400_000) * 2 / 3
