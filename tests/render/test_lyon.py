import json

import numpy as np
import pytest

from phongfx.render.lyon import run


def test_small_scene_is_bit_identical_and_reported(tmp_path, backend):
    summary = run(radius=6, span=4, backend=backend, out_dir=str(tmp_path), sample=0, quiet=True)
    assert summary["mismatches"] == 0
    assert summary["pixels_checked"] == 2 * summary["error_8bit"]["exact"]["pixels"]
    assert summary["cycles"] >= summary["pixels_checked"]
    assert summary["cycles_per_second"][backend]["cycles_per_second"] > 0
    written = json.loads((tmp_path / "summary.json").read_text())
    assert written["pixels_checked"] == summary["pixels_checked"]
    for name in ("fig7.png", "fig7_error.png"):
        assert (tmp_path / name).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    # the fixed-point datapath computes Lyon's k = 2 shape: against its float form with
    # exact normals the error is quantization only; against Phong it is the approximation
    exact = summary["error_8bit"]["exact"]
    assert exact["specular_vs_lyon-k2"]["max"] < 3
    assert exact["specular_vs_phong"]["max"] > exact["specular_vs_lyon-k2"]["max"]
    assert exact["diffuse_vs_float"]["max"] < 1
    assert np.isfinite(summary["error_8bit"]["spans"]["specular_vs_lyon-k2"]["mean"])


def test_a_configured_k_is_compared_with_its_own_float_form(tmp_path):
    """``--set shape.k=1``: the datapath computes f_1, so its float form is lyon-k1 (against
    lyon-k2 the error would be the two shapes' difference, some 24 levels, not the fixed point's)."""
    from phongfx.config import ShapeConfig, fig7_config
    summary = run(fig7_config(shape=ShapeConfig(k=1)), radius=6, span=4, backend="amaranth",
                  out_dir=str(tmp_path), sample=0, quiet=True)
    exact = summary["error_8bit"]["exact"]
    assert summary["float_form"] == "lyon-k1"
    assert "specular_vs_lyon-k2" not in exact and "specular_vs_lyon-k1-interpolated" in exact
    assert exact["specular_vs_lyon-k1"]["max"] < 3


@pytest.mark.needs_verilator
def test_a_speed_sample_times_the_other_back_ends_on_its_pixels_only(tmp_path):
    """Without a sample only the back end asked for is timed (``make sim``); with one, each other
    back end runs that many span-mode pixels, bit-identical too."""
    alone = run(radius=6, span=4, backend="verilator-fast", out_dir=str(tmp_path / "a"), quiet=True)
    assert list(alone["cycles_per_second"]) == ["verilator-fast"]
    timed = run(radius=6, span=4, backend="verilator-fast", out_dir=str(tmp_path / "b"), sample=5, quiet=True)
    assert timed["mismatches"] == 0
    assert set(timed["cycles_per_second"]) == {"verilator-fast", "verilator", "amaranth"}
    assert timed["cycles_per_second"]["amaranth"]["note"] == ("speed sample: first 5 span-mode pixels, "
                                                             "also bit-identical")
