"""The area proxy's calibration (phongfx.explore.tables.proxy): the fit, the table's rows and
verdicts on stand-in synthesis, and the stored coefficients against the real flow."""

import numpy as np
import pytest

from phongfx.core.registry import get_block
from phongfx.explore.tables import proxy as proxy_table
from phongfx.explore.synth.proxy import AREA_COEFFICIENTS, FEATURES, proxy_area, rtlil_features, rtlil_of


def test_fit_recovers_known_coefficients():
    rng = np.random.default_rng(5)
    truth = np.array([240.0, 60.0, 35.0, 40.0, 20.0, 9.0, 110.0])
    features = rng.integers(0, 2000, size=(30, len(FEATURES))).astype(float)
    fitted = proxy_table.fit(features, features @ truth)
    assert list(fitted) == list(FEATURES)
    assert np.allclose([fitted[k] for k in FEATURES], truth, rtol=1e-6)


def test_fit_keeps_coefficients_non_negative():
    # areas that a negative register price would fit best: the fit clamps it at 0
    features = np.array([[100.0, 0, 0, 0, 0, 0, 10], [100, 0, 0, 0, 0, 0, 100], [50, 0, 0, 0, 0, 0, 0]])
    areas = np.array([24000.0, 23000, 12000])
    fitted = proxy_table.fit(features, areas)
    assert all(v >= 0 for v in fitted.values()) and fitted["ff_bits"] == 0
    assert fitted["mul_bits"] == pytest.approx(240, rel=0.05)


def test_features_count_bits_by_kind():
    shape = get_block("shape", k=1)
    f = rtlil_features(rtlil_of(shape))
    # one 16-bit squarer of t (1.15): 16 × 16 partial products
    assert f["mul_bits"] == 16 * 16
    assert f["ff_bits"] > 0 and f["rom_bits"] == 0
    narrow = rtlil_features(rtlil_of(get_block("shape", k=1, t="1.7")))
    assert narrow["mul_bits"] == 8 * 8


def test_rom_bits_are_words_times_bits():
    spherical = get_block("spherical")
    f = rtlil_features(rtlil_of(spherical))
    config = spherical.config
    # two channels (spec and diff), each a ROM of 2^addr_bits words of rom (0.6: 6 bits)
    assert f["rom_bits"] == 2 * 2 ** config.addr_bits * config.fmt("rom").width == 2 * 64 * 6


def _fake_synth(name, *, config, target, device, workdir):
    area = proxy_area(get_block(name, config), device) * (1.1 if name == "fig8" else 1.0)
    return {"area_um2": area, "fmax_mhz": 100.0}


def test_table_rows_errors_and_ranking(monkeypatch):
    monkeypatch.setattr(proxy_table, "synth", _fake_synth)
    points = (("shape", "shape", None), ("fig7", "fig7", None), ("fig8", "fig8", None))
    result = proxy_table.proxy_table(points, refit=True)
    errors = {r["label"]: r["error"] for r in result["rows"]}
    assert errors["shape"] == pytest.approx(0) and errors["fig8"] == pytest.approx(1 / 1.1 - 1)
    assert result["max_error_datapaths"] == pytest.approx(1 - 1 / 1.1)
    assert result["coefficients"] == AREA_COEFFICIENTS["osu018"]
    assert set(result["refit"]) == set(FEATURES)
    text = proxy_table.markdown(result)
    assert "| fig8 |" in text and "-9.1%" in text and "over the datapaths" in text


def test_unknown_library():
    with pytest.raises(ValueError, match=r"^library must be one of 'osu018', 'osu035', 'sg13g2_stdcell_typ_1p20V_25C', "
                                         r"'sg13g2_stdcell_slow_1p08V_125C', 'sg13g2_stdcell_fast_1p32V_m40C', not 'x'$"):
        proxy_area(get_block("shape"), "x")


@pytest.mark.parametrize("name", ["shape", "difference", "root", "lirp"])
def test_stored_coefficients_against_synthesis(name, asic_tools):
    """The proxy within 25% of the real flow on small blocks (the datapaths' 15% target
    is checked over every point in the slow run below)."""
    row = proxy_table.calibration_rows(((name, name, None),))[0]
    assert abs(row["error"]) < 0.25, row


@pytest.mark.slow
@pytest.mark.parametrize("library", ["osu018", "osu035"])
def test_calibration_over_every_point(library, asic_tools):
    result = proxy_table.proxy_table(library=library)
    assert result["max_error_datapaths"] <= 0.15
    agree, pairs = result["ranking_datapaths"]
    assert agree == pairs


def test_a_library_without_coefficients_is_fitted(monkeypatch, tmp_path):
    """A Liberty file the proxy knows nothing of: the table refuses to run without --refit,
    and with it prices the points by the fitted coefficients."""
    lib = tmp_path / "new.lib"
    lib.write_text('library (new_cells) {\n  time_unit : "1ns";\n  nom_process : 1;\n  nom_voltage : 1.0;\n'
                   '  nom_temperature : 25;\n  cell (DF) {\n    area : 2;\n    ff (IQ, IQN) { next_state : "D"; }\n'
                   '  }\n}\n')

    def fake(name, *, config, target, device, workdir):
        return {"area_um2": 0.5 * proxy_area(get_block(name, config), "osu018"), "fmax_mhz": 100.0}

    monkeypatch.setattr(proxy_table, "synth", fake)
    points = (("shape", "shape", None), ("difference", "difference", None), ("root", "root", None))
    with pytest.raises(ValueError, match=r"^library 'new_cells' has no stored area proxy coefficients \(calibrated: "
                                         r"osu018, osu035, .*\): ask for refit \(--refit\) to fit them$"):
        proxy_table.proxy_table(points, library=str(lib))
    result = proxy_table.proxy_table(points, library=str(lib), refit=True)
    assert result["library"] == "new_cells" and result["stored"] is False
    assert result["coefficients"] == result["refit"] and result["max_error"] < 1e-6
    text = proxy_table.markdown(result)
    assert "fitted now: none stored for this library" in text and "no datapath (fig7, fig8, halfway_datapath) among the points" in text
