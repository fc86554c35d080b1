import numpy as np
import pytest

from phongfx.config import (DatapathConfig, DifferenceConfig, RootConfig, ShapeConfig, fig7_config,
                            fig8_config, halfway_config)
from phongfx.core.registry import get_block
from phongfx.golden.reference import specular

LSB = 2.0 ** -10


def test_matches_float_lyon_k2_on_physical_vectors():
    # exact normals (a = 0): the datapath computes Lyon's k = 2 shape, so against the
    # float form it differs only by quantization; 10-bit vectors and n up to 8000
    block = get_block("fig7")
    raw = block.stimulus(count=2000, seed=5)
    keep = raw["a"] == 0
    raw = {name: value[keep] for name, value in raw.items()}
    out = block.golden(raw)
    N, V = raw["n0"] * LSB, raw["v"] * LSB
    N = N / np.maximum(np.linalg.norm(N, axis=-1, keepdims=True), 1e-9)
    for index in range(2):
        L = raw[f"l{index}"] * LSB
        ref = specular("lyon-k2", N, L, V, raw["n"].astype(float))
        err = np.abs(out[f"spec{index}"] * 2.0 ** -15 - ref) * 255
        small_n = raw["n"] <= 64
        assert err[small_n].max() < 2.0
        diff = np.maximum(np.sum(N * L, axis=-1), 0)
        assert np.max(np.abs(out[f"diff{index}"] * LSB - diff)) < 3 * LSB


def test_mirror_direction_gives_full_specular():
    # N halfway between L and V reflects V onto L: x = 0 up to 10-bit rounding
    block = get_block("fig7")
    raw = block.stimulus(count=0, seed=0)
    out = block.golden(raw)
    assert out["spec0"][0] >= 0.99 * 2 ** 15 and out["spec1"][1] >= 0.99 * 2 ** 15


def test_k_changes_the_shape():
    block = get_block("fig7", shape=ShapeConfig(k=1))
    raw = block.stimulus(count=200, seed=1)
    assert not np.array_equal(block.golden(raw)["spec0"], get_block("fig7").golden(raw)["spec0"])


def test_connected_formats_must_agree():
    from phongfx.config import NormalizeConfig
    with pytest.raises(ValueError, match=r"^lirp\.out \(S1\.10\) must equal normalize\.vec \(S1\.8\): they are connected$"):
        DatapathConfig(normalize=NormalizeConfig(vec="S1.8"))
    with pytest.raises(ValueError, match=r"^lights must be an integer in 1\.\.8, not 0$"):
        DatapathConfig(lights=0)


def _levels(block, raw, other_block, other_raw):
    a, b = block.golden(raw), other_block.golden(other_raw)
    lsb = block.config.outputs["spec0"][0].lsb
    return max(np.max(np.abs(a[k] - b[k])) * lsb * 255 for k in a if k.startswith("spec"))


def test_local_light_held_constant_matches_the_light_at_infinity():
    # L interpolated between two equal ends, then g2-normalized: the same light up to
    # one 10-bit rounding, so the specular amounts agree to a fraction of a level
    infinite = get_block("fig7", lights=1)
    local = get_block("fig7", lights=1, local_lights=True, local_viewer=True)
    raw = infinite.stimulus(count=400, seed=8)
    raw_local = dict(raw, l0_0=raw["l0"], l0_1=raw["l0"], v0=raw["v"], v1=raw["v"])
    del raw_local["l0"], raw_local["v"]
    assert _levels(infinite, raw, local, raw_local) < 0.5  # measured 0.023


def test_figure8_follows_figure7_k1_at_equal_shininess():
    fig7 = get_block("fig7", shape=ShapeConfig(k=1), lights=1)
    fig8 = get_block("fig8", lights=1)
    raw = fig7.stimulus(count=600, seed=9)
    m = np.clip(np.round(np.sqrt(raw["n"])), 1, 63).astype(np.int64)
    raw7 = dict(raw, n=m * m)
    raw8 = dict(raw, m=m)
    del raw8["n"]
    # both compute f_1((m²/2)|R-L|²); Figure 8 truncates each m|D_i|/2 to 9 fraction bits
    assert _levels(fig7, raw7, fig8, raw8) < 2  # measured 0.85


def test_halfway_datapath_follows_lyon_row_8():
    block = get_block("halfway_datapath", lights=1)
    raw = block.stimulus(count=600, seed=10)
    keep = raw["a"] == 0
    raw = {k: v[keep] for k, v in raw.items()}
    N = raw["n0"] * LSB
    ref = specular("halfway-g2proj-k2", N, raw["l0"] * LSB, raw["v"] * LSB, raw["n"].astype(float))
    got = block.golden(raw)["spec0"] * 2.0 ** -15
    assert np.max(np.abs(got - ref)[raw["n"] <= 256]) * 255 < 1  # measured 0.15


def test_halfway_conventions_agree_on_x():
    # without normalization of H (d3), H = V + L doubles D and the mean convention takes
    # 4n instead: the same x, the same shape (g2 variants differ: g2 cannot shorten a
    # V + L longer than √2, Lyon's reason for the code's H = (L+V)/2)
    from phongfx.config import HalfwayConfig
    mean = get_block("halfway_datapath", lights=1, halfway=HalfwayConfig(variant="d3"))
    total = get_block("halfway_datapath", lights=1, halfway=HalfwayConfig(variant="d3", h="sum"))
    assert (mean.config.shininess[2], total.config.shininess[2]) == (8000, 32000)
    raw = mean.stimulus(count=400, seed=12)
    # measured 2.75: the mean convention's D has half the resolution, seen at n up to 8000
    assert _levels(mean, raw, total, raw) < 4


def _halfway_difference(n_const=0):
    return DifferenceConfig(vec="S2.10", n="15.0", n_max=32000, n_const=n_const)


@pytest.mark.parametrize("name, unit, port, value", [
    ("fig7", dict(difference=DifferenceConfig(n_const=16)), "n", 16),
    ("fig7", dict(difference=DifferenceConfig(n_const=8000)), "n", 8000),
    ("fig8", dict(root=RootConfig(m_const=4)), "m", 4),
    ("fig8", dict(root=RootConfig(m_const=1)), "m", 1),
    # the halfway unit's difference block multiplies by n·2^2: its n_const 64 is n = 16
    ("halfway_datapath", dict(difference=_halfway_difference(64)), "n", 16),
])
def test_constant_shininess_gives_the_codes_of_the_port(name, unit, port, value):
    fixed, fed = get_block(name, **unit), get_block(name)
    assert fixed.config.shininess is None and fixed.config.shininess_const == value
    assert fed.config.shininess[0] == port and fed.config.shininess_const == 0
    assert set(fed.config.inputs) - set(fixed.config.inputs) == {port}
    raw = fixed.stimulus(count=300, seed=6)
    assert port not in raw
    a, b = fixed.golden(raw), fed.golden(dict(raw, **{port: np.full(len(raw["a"]), value)}))
    assert a.keys() == b.keys()
    for key in a:
        assert np.array_equal(a[key], b[key]), key
    assert len(np.unique(a["spec0"])) > 20  # compared on varied amounts, not on all 0


def test_constant_shininess_keeps_the_latency():
    assert get_block("fig7", difference=DifferenceConfig(n_const=16)).latency == get_block("fig7").latency
    assert get_block("fig8", root=RootConfig(m_const=4)).latency == get_block("fig8").latency
    for depth in range(4):
        assert (get_block("difference", n_const=7, pipeline=depth).latency
                == get_block("difference", pipeline=depth).latency)
        assert (get_block("root", m_const=7, pipeline=depth).latency
                == get_block("root", pipeline=depth).latency)


def test_halfway_constant_must_be_a_multiple_of_the_scale():
    with pytest.raises(ValueError, match=r"^difference\.n_const must be a multiple of 4 "
                                         r"\(it is n·2\^2\), not 66$"):
        halfway_config(difference=_halfway_difference(66))
    # H = V + L takes n unscaled: any constant
    from phongfx.config import HalfwayConfig
    total = halfway_config(difference=_halfway_difference(66), halfway=HalfwayConfig(h="sum"))
    assert total.shininess_const == 66 and total.shininess is None


def test_constant_of_the_other_unit_is_ignored():
    # Figure 8 has no difference block, Figure 7 no root unit: their constants change nothing
    assert fig8_config(difference=DifferenceConfig(n_const=16)).shininess[0] == "m"
    assert fig7_config(root=RootConfig(m_const=4)).shininess[0] == "n"
