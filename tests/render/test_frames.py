import json

import numpy as np
import pytest

from phongfx.core.registry import get_block
from phongfx.render.frames import chunk_starts, frame_spans, markdown, rtl_frame, run_all
from phongfx.scene.span_inputs import units


@pytest.mark.needs_verilator
@pytest.mark.parametrize("unit", units())
def test_small_frame_is_bit_identical_on_verilator(unit):
    # verilator-fast: the cocotb back end checks the same Verilog (tests/conftest.py COCOTB_TESTS)
    result = rtl_frame(unit, width=48, height=48, frame=30, backend="verilator-fast")
    spans = frame_spans(width=48, height=48, frame=30)
    assert result["mismatches"] == 0 and result["first_mismatch"] is None
    assert result["pixels"] == int(spans.length.sum()) > 500
    assert result["spans"] == len(spans.length)
    assert result["visible"] < result["pixels"]  # tilted torus: some surface is hidden
    # one chunk, back to back: a cycle per pixel plus the pipeline's drain
    assert result["chunks"] == 1
    assert result["cycles"] == result["pixels"] + get_block(unit).latency
    assert result["cycles_per_second"] > 0


def test_chunked_amaranth_frame_matches_and_reports_progress():
    seen = []
    result = rtl_frame("euler", width=12, height=12, backend="amaranth", chunk=20, progress=seen.append)
    assert result["mismatches"] == 0
    assert sum(seen) == result["pixels"] == int(frame_spans(width=12, height=12).length.sum())
    assert result["chunks"] == len(seen) > 2
    assert max(seen) <= 20  # no span of a 12-pixel-wide frame is longer than a chunk
    assert result["cycles"] == result["pixels"] + result["chunks"] * get_block("euler").latency


def test_sphere_frame_on_amaranth():
    result = rtl_frame("spherical", mesh="sphere", polygons=32, width=12, height=12, backend="amaranth")
    assert result["mismatches"] == 0 and result["mesh"] == "sphere"
    assert result["pixels"] == int(frame_spans("sphere", 32, 12, 12).length.sum()) > 50


def test_chunks_start_on_span_starts():
    first = np.array([0, 3, 10, 30, 31])
    assert chunk_starts(first, 40, 5) == [0, 3, 10, 30, 31, 40]  # 10..30 is one long span
    assert chunk_starts(first, 40, 12) == [0, 10, 30, 40]
    assert chunk_starts(first, 40, 100) == [0, 40]
    with pytest.raises(ValueError, match=r"^chunk must be a positive integer, not 0$"):
        chunk_starts(first, 40, 0)


def test_run_all_writes_the_table(tmp_path):
    result = run_all(str(tmp_path), units=("gouraud", "schlick"), quiet=True, width=10, height=10,
                     backend="amaranth")
    written = json.loads((tmp_path / "frames.json").read_text())
    assert written == result
    assert [row["unit"] for row in result["frames"]] == ["gouraud", "schlick"]
    assert result["mismatches"] == 0
    table = markdown(result)
    assert table.count("\n| gouraud |") == 1 and table.count("\n| schlick |") == 1
    # and the frames themselves, titled and enlarged (10 × 10 frame pixels → 390 PNG pixels)
    from PIL import Image
    for row in result["frames"]:
        assert row["png"] == str(tmp_path / f"{row['unit']}.png")
        assert min(Image.open(row["png"]).size) >= 384


def test_bad_names_are_refused():
    with pytest.raises(ValueError, match=r"^unit must be one of spherical, euler, gouraud, schlick, blinn, "
                                         r"conventional, not 'phong'$"):
        rtl_frame("phong")
    with pytest.raises(ValueError, match=r"^backend must be one of amaranth, verilator, verilator-fast, not 'x'$"):
        rtl_frame("euler", backend="x")
    with pytest.raises(ValueError, match=r"^mesh must be one of torus, sphere, not 'cube'$"):
        frame_spans("cube")
    with pytest.raises(ValueError, match=r"^width must be a positive integer, not 0$"):
        frame_spans(width=0)
    with pytest.raises(ValueError, match=r"^polygons must be 2·k² for an integer k >= 2"):
        frame_spans("sphere", polygons=7)
    with pytest.raises(ValueError, match=r"^unit must be one of"):
        run_all("unused", units=("bad",))
