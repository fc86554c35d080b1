import time

import numpy as np
import pytest

import phongfx.explore.synth.fpga
from phongfx.core.registry import REGISTRY, get_block
from phongfx.core.methods import METHODS
from phongfx.explore.evaluate import COST_KEYS, SCENES, error_metrics, evaluate
from phongfx.explore.synth.fpga import SynthError

NAMES = ("fig7", "fig8", "halfway", "spherical", "euler", "gouraud", "schlick", "blinn", "conventional")
NOT_WIDTHS = ("n", "k", "lights")


def test_method_table_names_and_blocks():
    assert tuple(METHODS) == NAMES
    for name, spec in METHODS.items():
        assert spec.name == name and spec.block in REGISTRY
        assert "n" in spec.params and set(spec.params) == set(spec.ranges)
        for param, default in spec.params.items():
            lo, hi = spec.ranges[param]
            assert lo <= default <= hi, (name, param)


@pytest.mark.parametrize("name", NAMES)
def test_defaults_reproduce_the_registry_config(name):
    spec = METHODS[name]
    registry = get_block(spec.block).config
    assert spec.config({}) == registry
    assert spec.config(dict(spec.params)) == registry


def test_params_map_to_config_fields():
    fig7 = METHODS["fig7"].config({"vec_frac": 8, "x2_frac": 9, "shape_t_frac": 11, "k": 1, "lights": 1})
    assert (fig7.lirp.vec, fig7.normalize.out, fig7.reflect.dot, fig7.difference.dd) == ("S1.8", "S1.8", "S1.10", "2.16")
    assert (fig7.difference.x2, fig7.shape.x2, fig7.shape.t, fig7.shape.k, fig7.lights) == ("13.9", "13.9", "1.11", 1, 1)
    fig8 = METHODS["fig8"].config({"root_frac": 7, "t_frac": 12})
    assert (fig8.root.frac, fig8.root.t) == ("0.7", "1.12")
    half = METHODS["halfway"].config({"vec_frac": 12})
    assert (half.halfway.hvec, half.halfway.normalize.vec, half.difference.vec) == ("S2.13", "S2.13", "S2.12")
    sph = METHODS["spherical"].config({"addr_bits": 5, "rom_bits": 7, "theta_frac": 13})
    assert (sph.addr_bits, sph.rom, sph.theta) == (5, "0.7", "S0.13")
    conv = METHODS["blinn"].config({"vec_frac": 12, "table_addr": 6})
    assert (conv.vec, conv.log_addr, conv.exp_addr) == ("S1.12", 6, 6)
    phong = METHODS["conventional"].config({"vec_frac": 11, "rsqrt_addr": 7, "table_addr": 4})
    assert (phong.vec, phong.rsqrt_addr, phong.log_addr, phong.exp_addr) == ("S1.11", 7, 4, 4)
    assert (phong.local_light, phong.local_viewer) == (False, False)


def test_metric_keys_are_the_contract():
    result = evaluate("schlick", {})
    assert set(result) == {"metrics", "cost"} and result["cost"] is None
    assert set(result["metrics"]) == {f"{scene}.{ref}.{stat}" for scene in ("torus", "sphere")
                                      for ref in ("phong", "self", "pixel-phong", "pixel-self")
                                      for stat in ("max", "mean", "psnr", "pct_over1")}
    # the diffuse-only units have no shader pixel of their own to measure
    assert not any(".pixel-" in key for key in evaluate("euler", {}, scenes=("torus",))["metrics"])
    assert all(isinstance(v, float) for v in result["metrics"].values())
    only = evaluate("schlick", {}, scenes=("sphere",))["metrics"]
    assert {key.split(".")[0] for key in only} == {"sphere"}


def test_pixel_metrics_are_display_codes_through_the_hardware_blend():
    from phongfx.core.format import Format
    from phongfx.explore.evaluate import pixel_metrics
    from phongfx.render.mesh import AMBIENT, KD, KS

    scene = SCENES["torus"]
    d = scene.data
    cosine = d["normal"] @ d["light"]
    spec = np.clip(d["normal"] @ d["h"], 0, 1) ** 8
    fmt = Format(1, 12)
    terms = {"diff": (np.round(np.maximum(cosine, 0) * fmt.one).astype(np.int64), fmt),
             "spec": (np.round(spec * fmt.one).astype(np.int64), fmt)}
    exact = pixel_metrics(terms, spec, scene)
    assert exact["max"] <= 1.0 and exact["mean"] < 0.1  # 12-bit terms: within a code
    # a specular 24 levels high everywhere: KS·24/255·... shows as whole codes off the reference
    high = {**terms, "spec": (np.minimum(terms["spec"][0] + round(24 / 255 / KS * fmt.one), fmt.max_raw), fmt)}
    off = pixel_metrics(high, spec, scene)
    assert off["max"] >= 23 and float(off["max"]).is_integer()
    assert AMBIENT + KD + KS == pytest.approx(1.0)


def test_error_metrics_hand_made():
    levels = np.array([0.0, 0.5, 2.0, 4.0, 100.0])
    visible = np.array([True, True, True, True, False])
    got = error_metrics(levels / 255 + 0.25, np.full(5, 0.25), visible)
    mse = (0 + 0.25 + 4 + 16) / 4
    assert got["max"] == pytest.approx(4.0)
    assert got["mean"] == pytest.approx(6.5 / 4)
    assert got["psnr"] == pytest.approx(10 * np.log10(255 ** 2 / mse))
    assert got["pct_over1"] == pytest.approx(50.0)
    # exactly one level is not "more than one level"; no error is infinite PSNR
    exact = error_metrics(np.array([1.0, 3.0]) / 255, np.zeros(2))
    assert exact["pct_over1"] == 50.0 and exact["max"] == 3.0
    assert error_metrics(np.ones(3), np.ones(3))["psnr"] == float("inf")
    with pytest.raises(ValueError, match=r"^visible must select at least one pixel, not 0$"):
        error_metrics(np.ones(2), np.ones(2), np.zeros(2, dtype=bool))


def test_scenes_are_deterministic_and_occluded():
    torus, sphere = SCENES["torus"].data, SCENES["sphere"].data
    assert 0 < torus["visible"].sum() < len(torus["visible"])  # part of the ring is hidden
    assert sphere["visible"].sum() > 4000
    # both frames show a highlight: some visible N̂ within 10° of H
    for data in (torus, sphere):
        assert np.max(data["normal"][data["visible"]] @ data["h"]) > np.cos(np.radians(10))
    assert evaluate("fig7", {"vec_frac": 7}) == evaluate("fig7", {"vec_frac": 7})


def _self_mean(name, params):
    metrics = evaluate(name, params, scenes=("torus",))["metrics"]
    return metrics["torus.self.mean"]


@pytest.mark.parametrize("name", NAMES)
def test_widening_a_width_never_makes_self_error_worse(name):
    spec = METHODS[name]
    widths = [p for p in spec.params if p not in NOT_WIDTHS]
    wide = _self_mean(name, {})
    for width in widths:
        narrow = {width: spec.params[width] - 2}
        try:
            spec.config(narrow)
        except ValueError:  # a chained width (Euler's t <= p): narrow them all together
            narrow = {w: spec.params[w] - 2 for w in widths}
        assert wide <= _self_mean(name, narrow) + 0.005, (name, width)


def test_fig7_vec_frac_6_is_clearly_worse_than_10():
    at = {f: evaluate("fig7", {"vec_frac": f}, scenes=("torus",))["metrics"] for f in (6, 10)}
    assert at[6]["torus.self.mean"] > 5 * at[10]["torus.self.mean"]
    assert at[6]["torus.self.max"] > at[10]["torus.self.max"] + 10
    assert at[10]["torus.self.max"] < 2  # the default datapath is within ~1 level of its float


def test_references_behave_as_their_papers_say():
    # Hast: the corrected Euler unit at 30 fraction bits tracks its float curve exactly,
    # and that curve is Phong's N·L within a fraction of a level; Gouraud's chord is not
    euler = evaluate("euler", {})["metrics"]
    assert euler["torus.self.max"] < 0.01 and euler["torus.phong.max"] < 1
    gouraud = evaluate("gouraud", {}, scenes=("torus",))["metrics"]
    assert gouraud["torus.self.max"] < 0.01 and gouraud["torus.phong.max"] > 3
    # Blinn–Phong's own float form is Phong
    blinn = evaluate("blinn", {})["metrics"]
    assert all(blinn[k.replace(".self.", ".phong.")] == v for k, v in blinn.items()
               if ".self." in k)
    # the conventional unit's own float form is Phong with its backside test, which on these
    # frames (lights in front of the viewer) is Phong
    conventional = evaluate("conventional", {})["metrics"]
    assert all(conventional[k.replace(".self.", ".phong.")] == v for k, v in conventional.items()
               if ".self." in k)
    # n is a parameter of every method, but the diffuse curve does not depend on it
    assert evaluate("gouraud", {"n": 3}, scenes=("torus",)) == evaluate("gouraud", {}, scenes=("torus",))


def test_conventional_is_within_a_level_of_phong_at_n_16():
    # Phong's (R·V)^n on the torus: 0.12 levels at the defaults (16-bit vectors, 512-word seed,
    # 256-word log/exp tables); the cheapest widths within a level, by the tool-free cost
    # proxy: 11-bit vectors, a 128-word seed, 16-word log/exp tables (0.92 levels)
    def error(**params):
        return evaluate("conventional", {"n": 16, **params}, scenes=("torus",))["metrics"]["torus.phong.max"]
    assert error() <= 0.15
    assert error(vec_frac=11, rsqrt_addr=7, table_addr=4) <= 1.0
    # one bit fewer anywhere misses it
    for fewer in (dict(vec_frac=10), dict(rsqrt_addr=6), dict(table_addr=3)):
        assert error(**{"vec_frac": 11, "rsqrt_addr": 7, "table_addr": 4, **fewer}) > 1.0, fewer


def test_bad_method_and_params():
    with pytest.raises(ValueError, match=r"^method must be one of fig7, fig8, halfway, spherical, euler, "
                                         r"gouraud, schlick, blinn, conventional, not 'fig9'$"):
        evaluate("fig9", {})
    with pytest.raises(ValueError, match=r"^vec_frac must be an integer in 4\.\.16, not 3$"):
        evaluate("fig7", {"vec_frac": 3})
    with pytest.raises(ValueError, match=r"^k must be an integer in 0\.\.10, not 2\.0$"):
        evaluate("fig7", {"k": 2.0})
    with pytest.raises(ValueError, match=r"^bogus is not a parameter of schlick; "
                                         r"parameters: t_frac, out_frac, n$"):
        evaluate("schlick", {"bogus": 1})
    with pytest.raises(ValueError, match=r"^t_frac must be an integer in 8\.\.20, not 30$"):
        evaluate("euler", {"p_frac": 20})
    with pytest.raises(ValueError, match=r"^addr_bits must be an integer in 2\.\.9, not 10$"):
        METHODS["spherical"].config({"theta_frac": 8, "addr_bits": 10})
    with pytest.raises(ValueError, match=r"^scene must be one of torus, sphere or a scene file \(\.toml\), not 'cube'$"):
        evaluate("schlick", {}, scenes=("cube",))
    with pytest.raises(ValueError, match=r"^synth option 'speed' is not one of target, freq, device, "
                                         r"seed, workdir$"):
        evaluate("schlick", {}, scenes=(), synth={"speed": 1})


def test_synth_path_maps_the_result(monkeypatch):
    calls = []

    def fake(name, *, config=None, **options):
        calls.append((name, config, options))
        return {"lut4": 1234, "ff": 567, "carry": 89, "dsp": 6, "bram_bits": 0, "fmax_mhz": 151.5,
                "pixels_per_second": 151.5e6, "latency": 17, "cells": {}, "cached": True}

    monkeypatch.setattr(phongfx.explore.synth.fpga, "synth", fake)
    params = {"vec_frac": 8, "lights": 1}
    result = evaluate("halfway", params, scenes=(), synth={"target": "ecp5", "freq": 150})
    assert result["metrics"] == {}
    assert result["cost"] == {"lut4": 1234, "ff": 567, "carry": 89, "dsp": 6, "bram_bits": 0,
                              "fmax_mhz": 151.5, "mpixels_per_s": pytest.approx(151.5), "latency": 17}
    assert list(result["cost"]) == list(COST_KEYS)
    (name, config, options), = calls
    assert name == "halfway_datapath" and config == METHODS["halfway"].config(params)
    assert options == {"target": "ecp5", "freq": 150}

    def broken(name, **options):
        raise SynthError("nextpnr failed (exit code 1)")

    monkeypatch.setattr(phongfx.explore.synth.fpga, "synth", broken)
    with pytest.raises(SynthError, match=r"^nextpnr failed"):
        evaluate("euler", {}, scenes=(), synth={"target": "ecp5"})


@pytest.mark.slow
@pytest.mark.parametrize("name", NAMES)
def test_one_point_takes_under_three_seconds(name):
    evaluate(name, {})  # imports and scene caches
    start = time.perf_counter()
    evaluate(name, {})
    assert time.perf_counter() - start < 3
