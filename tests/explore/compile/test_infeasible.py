"""When a scene is infeasible: k past the old cap, the best point and why, a computed hint,
no synthesis of a method that cannot be chosen."""

import json

import pytest

from phongfx.cli import main
from phongfx.compiler.compile import compile_scene
from phongfx.compiler.request import CompileRequest
from phongfx.explore.compile.measure import met_at
from phongfx.scene.file import parse_scene

SPHERE = """
name = "wide"
[[lights]]
direction = [1, 1, 1]
[materials.clay]
kd = 0.7
ks = 0.3
n = {n}
[[objects]]
type = "sphere"
material = "clay"
stacks = 16                # fine enough that Lyon's g2 normalizes every span of the domain
slices = 32
[output]
width = 24
height = 24
[requirement]
max_error_levels = 1.0
[domain]
samples = 2000
final_samples = 10000
"""


def _scene(n, size=24):
    return parse_scene(SPHERE.format(n=n).replace("24", str(size)), name="wide")


def test_a_high_shininess_gets_a_k_past_four():
    # n = 1000 wants 2^k near n: at k = 4 (the old cap) even the widest formats miss
    compiled = compile_scene(CompileRequest(_scene(1000, size=48), methods=["fig7"]))
    assert compiled.chosen == "fig7" and compiled.best["params"]["k"] >= 5 and compiled.best["max"] <= 1
    widest = {**compiled.best["params"], "vec_frac": 16, "x2_frac": 20, "shape_t_frac": 24, "coef": 16,
              "order": 2, "k": 4}
    assert compiled.scene.error("fig7", widest)["max"] > 1


@pytest.fixture(scope="module")
def wide():
    return compile_scene(CompileRequest(_scene("[4, 128]"), methods=["fig7"]))


def test_an_infeasible_method_reports_its_best_point_and_why(wide):
    result = wide.results["fig7"]
    assert not result["feasible"]
    measured = [e["max"] for (method, _), e in wide.scene.cache.items() if method == "fig7"]
    assert result["max"] == min(measured) and result["max"] <= result["widest"]["max"]
    assert result["max"] <= result["default"]["max"]
    assert wide.scene.error("fig7", result["params"])["max"] == result["max"]
    assert list(result["k_scan"]) == list(range(0, 11))
    why = " ".join(result["why"])
    assert "its own float form is itself" in why and "scanned over 0..10" in why


def test_a_shininess_range_no_k_serves_gets_a_computed_split(wide):
    hint = wide.hint
    assert hint["best"]["method"] == "fig7" and hint["best"]["max"] == wide.results["fig7"]["max"]
    # the requirement the best point meets, its continuous error on the domain with the guard
    levels = met_at(wide.results["fig7"])
    assert levels >= -(-hint["best"]["max"] // 1) and hint["command"].endswith(f"--max-error {levels}")
    split = hint["split"]
    (low, high), = split["ranges"].values()
    assert low[0] == 4 and high[1] == 128 and low[1] + 1 == high[0]
    k_low, k_high = split["k"]
    scan = wide.results["fig7"]["k_scan"]
    # each part is met at its samples by its own k, and no one k meets them all
    cut = next(i for i, s in enumerate(wide.scene.shininess_variants) if s["clay"] >= high[0])
    assert all(e <= 1 for e in scan[k_low]["per_variant"][:cut])
    assert all(e <= 1 for e in scan[k_high]["per_variant"][cut:])
    assert not any(all(e <= 1 for e in s["per_variant"]) for s in scan.values())


def test_the_cli_prints_the_hint_and_the_relaxed_requirement_is_met(tmp_path, capsys):
    path = tmp_path / "wide.toml"
    path.write_text(SPHERE.format(n="[4, 128]"))
    out, relaxed = tmp_path / "out", tmp_path / "relaxed"
    args = ["--methods", "fig7", "--sampled", "--quiet", "--no-check"]  # the measured hint
    assert main(["compile", str(path), "-o", str(out), *args]) == 1
    err = capsys.readouterr().err
    hint = json.loads((out / "manifest.json").read_text())["hint"]
    assert f"phongfx: hint: {hint['text'][0]}" in err and "split it into two materials" in err
    levels = int(hint["command"].rpartition(" ")[2])
    assert levels >= hint["best"]["witness"]["error_levels"]  # the witness search's worst at the best point
    # a relaxed requirement is met; with twice the margin, as a search of this small a domain sample
    # finds the worst of a wide shininess range only roughly
    assert main(["compile", str(path), "-o", str(relaxed), *args, "--max-error", str(2 * levels)]) == 0
    assert (relaxed / "verilog").is_dir() and (relaxed / "frames" / "sheet.png").is_file()
    # an infeasible rerun into that folder leaves no Verilog or frames of the earlier result
    assert main(["compile", str(path), "-o", str(relaxed), *args]) == 1
    assert sorted(p.name for p in relaxed.iterdir()) == ["manifest.json", "report.html"]
    page = (relaxed / "report.html").read_text(encoding="utf-8")
    assert "no design chosen" in page and "hint: " in page and "<img" not in page
    assert sorted(p.name for p in tmp_path.iterdir() if p.name.startswith(".")) == []


def test_an_infeasible_method_is_not_synthesized(monkeypatch):
    import phongfx.explore.synth.fpga as synth_module
    calls = []
    monkeypatch.setattr(synth_module, "synth", lambda *a, **k: calls.append(a) or {})
    compiled = compile_scene(CompileRequest(_scene("[4, 128]"), methods=["fig7"], synth=True))
    assert calls == [] and compiled.results["fig7"]["default"]["cost"]["model"] == "ecp5-proxy"


def test_an_infeasible_search_steps_aside_and_a_feasible_one_does_not(monkeypatch):
    # once no start passes, what is left of a search (its summary, its price) yields the cores
    # to the searches that go on (phongfx.explore.compile.workers.step_aside)
    from phongfx.explore.compile import search as searches
    from phongfx.explore.compile.measure import SceneEval

    asides = []
    monkeypatch.setattr(searches, "step_aside", lambda: asides.append(True))
    assert not searches.search_widths(SceneEval(_scene("[4, 128]")), "fig7")["feasible"] and asides == [True]
    assert searches.search_widths(SceneEval(_scene(8)), "fig7")["feasible"] and asides == [True]


def test_an_infeasible_method_is_measured_on_the_domain_only_when_a_hint_quotes_it(wide):
    # nothing feasible: the hint measured the best point's domain too, where its frames missed
    result = wide.results["fig7"]
    assert result["domain_max"] is not None and result["frames_max"] > 1.0
    assert result["max"] == max(result["frames_max"], result["domain_max"])
    # another method feasible: no hint, and the frames decided (the domain left unmeasured)
    compiled = compile_scene(CompileRequest(_scene("[4, 128]"), methods=["fig7", "conventional"]))
    assert compiled.chosen == "conventional" and compiled.hint is None
    missed = compiled.results["fig7"]
    assert missed["domain_max"] is None and missed["max"] == missed["frames_max"] == result["frames_max"]
