"""``phongfx tables lyon``: Lyon's numeric claims, measured in float and fixed point.

Each paper claim is asserted against the paper's number within the tolerance the table
states, where it holds; the one that does not hold (the "factor of two") is asserted to
be reported as such, with its measured value checked against the closed form.
"""

import json
import math
import re
import time

import pytest

from phongfx.cli import main
from phongfx.papers.lyon.tables import PLOTS, lyon, to_json

PNG = b"\x89PNG\r\n\x1a\n"
H = 1 / math.sqrt(2)


@pytest.fixture(scope="module")
def result():
    return lyon(plots=False)


def row(result, section, prefix):
    rows = next(s for s in result["sections"] if s["id"] == section)["rows"]
    found = [r for r in rows if r["claim"].startswith(prefix)]
    assert len(found) == 1, [r["claim"] for r in rows]
    return found[0]


# -- Figure 3 ---------------------------------------------------------------------------

def test_nominal_radius(result):
    r = row(result, "figure3", "cos^n α at the nominal radius")
    assert r["float"] == pytest.approx(math.exp(-0.5), abs=0.002)
    r = row(result, "figure3", "f0 at the nominal radius")
    assert r["float"] == pytest.approx(0.5, abs=0.002)
    assert r["fixed"] == pytest.approx(0.5, abs=0.01)


def test_half_heights_order_and_fixed_point(result):
    stats = {s["shape"]: s for s in next(s for s in result["sections"] if s["id"] == "figure3")["stats"]}
    widths = [stats[name]["half_alpha_deg_float"] for name in ("f0", "f1", "f2", "cos^n")]
    assert widths == sorted(widths)  # each k widens the peak towards cos^n's
    for k in ("f0", "f1", "f2"):
        assert stats[k]["half_alpha_deg_fixed"] == pytest.approx(stats[k]["half_alpha_deg_float"], abs=0.1)
        # 10-bit vectors and a 1.15 shape: the datapath is within a few 8-bit levels of float f_k
        assert stats[k]["fixed_max_abs_error_vs_float_fk"] < 4 / 255
    # f2 is the closest to cos^n (Lyon: "visually indistinguishable")
    assert stats["f2"]["max_abs_error_vs_cos_n"] < stats["f1"]["max_abs_error_vs_cos_n"] \
        < stats["f0"]["max_abs_error_vs_cos_n"]


@pytest.mark.parametrize("prefix, degrees", [("n = 4: f1", 60), ("n = 4: f2", 90), ("n = 1: f1", 180)])
def test_low_n_zero_crossings(result, prefix, degrees):
    r = row(result, "figure3", prefix)
    assert r["float"] == pytest.approx(degrees, abs=0.01)
    assert r["fixed"] == pytest.approx(degrees, abs=1.0 if degrees < 180 else 4.7)
    assert r["verdict"] == "holds"


def test_f2_never_reaches_zero_at_n_1(result):
    r = row(result, "figure3", "n = 1: f2")
    assert r["float"] is None and r["fixed"] is None and r["verdict"] == "holds"


# -- Figure 4 ---------------------------------------------------------------------------

@pytest.mark.parametrize("order, gain", [(1, 1.25), (2, 1.375)])
def test_lengths_at_one_over_root_two(result, order, gain):
    r = row(result, "figure4", f"length after g{order} at")
    assert r["float"] == pytest.approx(gain * H, abs=0.002)
    assert r["fixed"] == pytest.approx(gain * H, abs=0.002)
    r = row(result, "figure4", f"g{order} at y = 1/2")
    assert r["float"] == pytest.approx(gain, abs=1e-12)
    assert r["fixed"] == pytest.approx(gain, abs=0.003)


@pytest.mark.parametrize("order, lo, hi", [(1, 0.11, 0.12), (2, 0.02, 0.03)])
def test_errors_just_under_12_and_3_percent(result, order, lo, hi):
    r = row(result, "figure4", f"g{order} error at y = 1/2")
    assert lo <= r["float"] < hi and lo <= r["fixed"] < hi


def test_g2_within_half_percent_from_0_8(result):
    r = row(result, "figure4", "g2: worst length error for |N'| ≥ 0.8")
    assert r["float"] < 0.005 and r["fixed"] < 0.005
    assert row(result, "figure4", "span angle θ giving")["float"] > 60


def test_g2_over_corrects_to_1_002_near_0_9(result):
    peak = row(result, "figure4", "g2 over-correction: largest")
    where = row(result, "figure4", "g2 over-correction: at input")
    assert peak["float"] == pytest.approx(1.002, abs=0.0005)
    assert peak["fixed"] == pytest.approx(1.002, abs=0.0005)
    assert 0.85 <= where["float"] <= 0.95 and 0.85 <= where["fixed"] <= 0.95


# -- length error sensitivity -----------------------------------------------------------

def test_epsilon_for_five_percent(result):
    r = row(result, "sensitivity", "(R·L)^n: ε for a 5 %")
    assert r["float"] == pytest.approx(0.00005, rel=0.1)
    assert row(result, "sensitivity", "(R·L)^n: bits")["float"] > 14
    for k in (0, 1, 2):
        r = row(result, "sensitivity", f"f{k}: ε for a 5 %")
        assert r["float"] == pytest.approx(0.01, rel=0.1)
        assert r["fixed"] == pytest.approx(0.01, rel=0.1)
    assert row(result, "sensitivity", "f_k: bits")["float"] < 7


# -- span angle and normalizer order -----------------------------------------------------

def test_factor_of_two_does_not_hold_and_says_so(result):
    r = row(result, "spans", "g2, θ = 90°, n = 1000: specular height")
    # closed form: N = g2·N' = 1.375/√2 · M, R = 2(N·V)N − V, L the mirror of V about M
    length = 1.375 * H
    d = 2 * math.cos(math.radians(45)) * (1 - length ** 2)
    expected = max(1 - 1000 / 2 * d * d / 4, 0) ** 4
    assert r["float"] == pytest.approx(expected, abs=1e-9)
    assert r["fixed"] == pytest.approx(expected, abs=0.01)
    assert r["verdict"] == "does NOT hold"
    assert result["not_holding"] == ["spans: " + r["claim"]]


def test_span_errors_grow_with_angle_and_g2_wins_on_wide_spans(result):
    table = {t["theta_deg"]: t for t in next(s for s in result["sections"] if s["id"] == "spans")["table"]}
    for n in (10, 100, 1000):
        assert table[90][f"n{n}_g1_fixed"] > table[10][f"n{n}_g1_fixed"]
        for theta in range(40, 91, 5):
            assert table[theta][f"n{n}_g2_fixed"] <= table[theta][f"n{n}_g1_fixed"]
        # at 10° only the 10-bit quantization is left
        assert table[10][f"n{n}_g2_float"] < 1
        assert table[10][f"n{n}_g2_fixed"] < 20


def test_deterministic(result):
    assert to_json(lyon(plots=False)) == to_json(result)


# -- command line -----------------------------------------------------------------------

def test_cli_markdown_and_plots(tmp_path, capsys):
    start = time.perf_counter()
    assert main(["tables", "lyon", "--out", str(tmp_path)]) == 0
    assert time.perf_counter() - start < 15
    out = capsys.readouterr().out
    assert out.startswith("# Lyon's numeric claims, measured")
    for heading in ("## Figure 3", "## Figure 4", "## Length error sensitivity", "## Span angle"):
        assert f"\n{heading}" in out
    assert "| claim | paper | float | fixed point | criterion | verdict | note |" in out
    assert re.search(r"^\| length after g2 at \\\|N'\\\| = 1/√2 \| 0\.9723 \| 0\.9723 \| 0\.972\d \| .* \| holds \|",
                     out, re.M)
    assert re.search(r"^\| \(R·L\)\^n: ε for a 5 % peak error, n = 1000 \| 0\.00005 \| 5\.13e-05 \|", out, re.M)
    assert re.search(r"^\| f2: ε for a 5 % peak error, n = 1000 \| 0\.01 \| 0\.0101 \| 0\.01\d* \|", out, re.M)
    assert re.search(r"^\| g2, θ = 90°, n = 1000: .*\*\*does NOT hold\*\*", out, re.M)
    assert "## Claims that do NOT hold as measured" in out
    for name in PLOTS.values():
        assert (tmp_path / name).read_bytes()[:8] == PNG
    assert not [p for p in tmp_path.iterdir() if p.name not in PLOTS.values()]  # no temp files left


def test_cli_json_parses(tmp_path, capsys):
    assert main(["tables", "lyon", "--json", "--out", str(tmp_path)]) == 0
    data = json.loads(capsys.readouterr().out)
    assert [s["id"] for s in data["sections"]] == ["figure3", "figure4", "sensitivity", "spans"]
    for section in data["sections"]:
        for r in section["rows"]:
            assert {"claim", "paper", "float", "fixed", "verdict"} <= set(r)
    assert sorted(data["plots"]) == sorted(str(tmp_path / name) for name in PLOTS.values())


def test_cli_unknown_table_exits_2(tmp_path, capsys):
    out = tmp_path / "out"
    assert main(["tables", "nope", "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert re.fullmatch(r"phongfx: error: unknown table 'nope'; valid tables: lyon, szirmay, schlick, hast, cost, proxy, pipeline, clock, extremes\n", err), err
    assert not out.exists()
