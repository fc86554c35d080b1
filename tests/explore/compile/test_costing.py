"""Costing a compiled design: a close margin is a tie, a tool failure names its log, a
synthesized cost carries its part, seed and utilisation, and synthesis says where it is."""

import pytest

from phongfx.compiler.compile import compile_scene
from phongfx.compiler.request import CompileRequest
from phongfx.explore.compile.costing import TIE_MARGIN, costed, tie, utilisation
from phongfx.explore.compile.run import build
from phongfx.scene.file import parse_scene
from tests.compiler.test_compile import TORUS as TINY

TORUS = TINY.format(error=1.0, against="phong")


def _result(method, value, max_error=1.0, mean=0.1):
    return {"method": method, "cost": {"cost": value, "model": "ecp5-synth"}, "max": max_error, "mean": mean}


def test_a_margin_below_the_model_resolution_is_a_tie():
    found = tie([_result("fig7", 1000), _result("fig8", 1001.5, 0.0, 0.05)])
    assert found["chosen"] == "fig7" and found["runner_up"] == "fig8"
    assert found["margin"] == pytest.approx(0.0015) and found["within"] == TIE_MARGIN
    assert "0.15% apart" in found["decided_by"] and found["runner_up_max"] == 0.0
    assert tie([_result("fig7", 1000), _result("fig8", 1000 * (1 + TIE_MARGIN) + 1)]) is None
    assert tie([_result("fig7", 1000)]) is None and tie([_result("a", 1), _result("b", None)]) is None


def test_a_failed_synthesis_names_its_log_without_a_dangling_colon(monkeypatch):
    import phongfx.explore.synth.fpga as synth_module

    def broken(name, **options):
        raise synth_module.SynthError("nextpnr failed (exit code 1); log build/x/nextpnr.log:\nERROR: ...")
    monkeypatch.setattr(synth_module, "synth", broken)
    scene = compile_scene(CompileRequest(parse_scene(TORUS, name="tiny"), methods=["fig7"])).scene
    got = costed("fig7", build("fig7", {"k": 4}, scene.analysis), True)
    assert got == {"cost": None, "why": "nextpnr failed (exit code 1)", "log": "build/x/nextpnr.log"}


def test_utilisation_is_a_share_of_the_device():
    assert utilisation({"TRELLIS_COMB": [1200, 24288], "MULT18X18D": [28, 28]}) == {
        "TRELLIS_COMB": {"used": 1200, "available": 24288, "percent": 4.94},
        "MULT18X18D": {"used": 28, "available": 28, "percent": 100.0}}


def test_synthesis_reports_each_candidate_and_the_manifest_keys(monkeypatch):
    import phongfx.explore.synth.fpga as synth_module
    seen = []

    def fake(name, *, config=None, progress=None, seed=1, **options):
        progress("yosys")
        seen.append(seed)
        return {"lut4": 500, "ff": 1, "carry": 1, "dsp": 2, "bram_bits": 0, "fmax_mhz": 80.0, "latency": 9,
                "part": "LFE5U-25F", "placed": {"MULT18X18D": [2, 28]}}
    monkeypatch.setattr(synth_module, "synth", fake)
    lines = []
    compiled = compile_scene(CompileRequest(parse_scene(TORUS, name="tiny"), methods=["fig7", "conventional"],
                                            synth=True, seed=3, progress=lines.append, workers=1))
    # both methods' searched and default widths, at the one architecture of no speed asked,
    # synthesized together
    synth_lines = [line for line in lines if line.startswith("candidate")]
    assert synth_lines[0].startswith("candidate 1 of 4 (fig7, depth 0, interval 1, shared inputs, vec_frac=")
    assert any(line.startswith("candidate 1 of 4 (fig7,") and ": yosys" in line for line in synth_lines)
    first = [line for line in synth_lines if " of 4 " in line]
    assert first[-1].startswith("candidate 4 of 4 (conventional,") and seen[:4] == [3] * 4
    # a method searched again after its witness (hard points) is priced again (started, yosys,
    # done), alone, with the same seed
    again = [s["method"] for s in compiled.rounds if s["action"] == "searched again"]
    assert len(synth_lines) == 3 * (4 + len(again)) and len(seen) == 4 + len(again) and set(seen) == {3}
    cost = compiled.best["cost"]
    assert cost["part"] == "LFE5U-25F" and cost["seed"] == 3 and cost["freq"] == 150
    assert cost["clock_source"] == "synthesis" and cost["fmax_mhz"] == 80 and cost["pixel_rate_mpx"] == 80
    assert cost["met"] is True and cost["architecture"] == {"pipeline": 0, "interval": 1, "share": True}
    assert cost["utilisation"]["MULT18X18D"]["percent"] == pytest.approx(7.14)
    # the same fake cost for both: a tie, flagged
    assert compiled.tie["runner_up"] in ("fig7", "conventional") and compiled.tie["margin"] == 0
