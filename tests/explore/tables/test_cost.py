import json
import sys

import pytest

from phongfx.explore.tables import cost as cost_table
from phongfx.explore.report import DSP_LUT_WEIGHT
from phongfx.explore.synth.fpga import SynthError

FAKE = {"difference": (150, 5, 90.0, 4), "shape": (20, 2, 110.0, 3), "root": (160, 7, 70.0, 5),
        "fig7": (1000, 39, 45.0, 17), "fig8": (1100, 39, 46.0, 15)}


def fake_synth(name, *, target, freq, workdir, progress=None, **kwargs):
    for stage in ("yosys", "nextpnr") if progress else ():
        progress(stage)
    if name == "blinn":
        raise SynthError("design does not fit on LFE5U-45F: needs MULT18X18D 80/72\nlog tail")
    lut, dsp, fmax, latency = FAKE[name]
    return {"lut4": lut, "ff": 2 * lut, "carry": lut // 10, "dsp": dsp, "bram_bits": 0, "fmax_mhz": fmax,
            "met": fmax >= freq, "pixels_per_second": fmax * 1e6, "latency": latency, "cached": True}


@pytest.fixture
def fake(monkeypatch):
    monkeypatch.setattr(cost_table, "synth", fake_synth)


def row(text, block):
    return next(line for line in text.splitlines() if line.startswith(f"| {block} |"))


def test_progress_names_each_candidate_and_its_stages_in_order(fake, capsys):
    import re
    cost_table.run_table("cost", blocks=("difference", "shape", "blinn"))  # blinn fails: still counted
    lines = [re.sub(r" \d+ s$", "", line) for line in capsys.readouterr().err.splitlines()]
    assert lines == [f"cost: synthesizing candidate {i} of 3 ({block}){stage}"
                     for i, block in enumerate(("difference", "shape", "blinn"), 1)
                     for stage in ("", ": yosys", ": nextpnr")] + [
        # the loop goes on, but the failure is on the progress line, not only in the table
        "cost: synthesizing candidate 3 of 3 (blinn) FAILED: design does not fit on LFE5U-45F: needs MULT18X18D 80/72"]


def test_side_by_side_with_claim(fake):
    result = cost_table.run_table("cost", blocks=("difference", "shape", "root"))
    text = cost_table.markdown(result)
    assert "six 7×11 and 9×9 multipliers" in text and "three 12×12 and one 14×22" in text
    assert [r["block"] for r in result["rows"]] == ["difference", "shape", "difference+shape", "root"]
    # difference: 150 LUT4, 300 FF, 15 carry, 5 DSP, 90 MHz, latency 4
    assert f"| 150 | 300 | 15 | 5 | 0 | {150 + 5 * DSP_LUT_WEIGHT} | 90.0 | 90.0 | 4 | no |" in row(text, "difference")
    # in series: resources and latency add, the slower clock rules
    assert f"| 170 | 340 | 17 | 7 | 0 | {170 + 7 * DSP_LUT_WEIGHT} | 90.0 | 90.0 | 7 | no |" in \
        row(text, "difference+shape")
    assert "root vs difference: LUT-eq 6866 vs 4940 (**larger**; 1.39×)" in text
    assert "root vs difference+shape: LUT-eq 6866 vs 6876 (about the same (±2%); 1.00×)" in text
    assert "Fmax 70.0 vs 90.0 MHz (**slower**)" in text
    assert result["accuracy"] == {}  # neither fig7 nor fig8 asked for
    assert json.loads(cost_table.to_json(result))["rows"][0]["lut4"] == 150


def test_failed_synthesis_is_a_row_not_a_crash(fake):
    result = cost_table.run_table("cost", blocks=("blinn",))
    assert result["rows"] == [{"block": "blinn", "what": cost_table.WHAT["blinn"],
                               "error": "design does not fit on LFE5U-45F: needs MULT18X18D 80/72"}]
    assert "synthesis failed: design does not fit" in row(cost_table.markdown(result), "blinn")


def test_accuracy_at_equal_n(fake, monkeypatch):
    import phongfx.explore.evaluate

    calls = []

    def evaluate(method, params, *, scenes, synth=None):
        calls.append((method, params, scenes))
        err = {"fig7": 3.25, "fig8": 4.5}[method]
        return {"metrics": {"torus.phong.max": err, "torus.self.max": err / 5}, "cost": None}

    monkeypatch.setattr(phongfx.explore.evaluate, "evaluate", evaluate)
    result = cost_table.run_table("cost", blocks=("fig7", "fig8"), n=25)
    assert calls == [("fig7", {"n": 25}, ("torus",)), ("fig8", {"n": 25}, ("torus",))]
    text = cost_table.markdown(result)
    assert "n = 25" in text and "| fig7 | 3.25 | 0.65 |" in text and "| fig8 | 4.50 | 0.90 |" in text
    assert "fig8 vs fig7: LUT-eq" in text


def test_accuracy_left_out_without_evaluate(fake, monkeypatch):
    monkeypatch.setitem(sys.modules, "phongfx.explore.evaluate", None)  # import fails
    result = cost_table.run_table("cost", blocks=("fig7",))
    assert result["accuracy"] is None
    assert "Accuracy column left out" in cost_table.markdown(result)


def test_multiplier_sizes_of_default_formats():
    # d = S1.10 (12 bits), dd = 2.20 (22), n = 13.0 (13); m = 6.0 (6), |d| = 1.10 (11), frac = 0.9 (9)
    assert cost_table.multipliers() == {"fig7c": [(12, 12)] * 3 + [(13, 22)],
                                        "fig8": [(6, 11)] * 3 + [(9, 9)] * 3}


def test_bad_arguments():
    with pytest.raises(ValueError, match=r"^unknown table 'lyon'; valid tables: cost$"):
        cost_table.run_table("lyon")
    with pytest.raises(ValueError, match=r"^blocks must be among difference, .*, not 'fig9'$"):
        cost_table.run_table("cost", blocks=("shape", "fig9"))


@pytest.mark.slow
@pytest.mark.needs_yosys
def test_real_synthesis_of_shape():
    result = cost_table.run_table("cost", blocks=("shape",))
    (r,) = result["rows"]
    assert r["block"] == "shape" and r["lut4"] > 0 and r["dsp"] >= 1 and r["fmax_mhz"] > 10
    assert r["lut_eq"] == r["lut4"] + DSP_LUT_WEIGHT * r["dsp"]
    assert "| shape | Figure 7d" in cost_table.markdown(result)


AREAS = {"difference": (171941.0, 131.4, 4), "shape": (85690.0, 173.1, 3), "root": (132401.0, 126.8, 5)}


def fake_asic(name, *, target, device, freq, workdir, **kwargs):
    assert target == "asic" and device == "osu035"
    area, fmax, latency = AREAS[name]
    return {"area_um2": area, "cell_count": int(area // 30), "ff": 100, "fmax_mhz": fmax,
            "area_delay": area * 1000 / fmax, "met": fmax >= freq, "pixels_per_second": fmax * 1e6,
            "latency": latency, "cached": True}


def test_asic_rows_are_priced_in_square_microns(monkeypatch):
    monkeypatch.setattr(cost_table, "synth", fake_asic)
    result = cost_table.run_table("cost", blocks=("difference", "shape", "root"), target="asic", device="osu035")
    text = cost_table.markdown(result)
    assert "(asic osu035, 150 MHz constraint)" in text and "| area µm² |" in text
    # in series: areas add, the slower clock rules
    series = row(text, "difference+shape")
    assert "| 257,631 |" in series and "| 131.4 |" in series
    assert "root vs difference+shape: area µm² 132,401 vs 257,631 (smaller; 0.51×)" in text
    assert "Fmax 126.8 vs 131.4 MHz (**slower**)" in text
    assert "grows with the product of its operand widths" in text and "MULT18X18D" not in text
