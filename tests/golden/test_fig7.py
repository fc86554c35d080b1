import numpy as np
import pytest

from phongfx.blocks import get_block
from phongfx.config import Fig7Config, ShapeConfig
from phongfx.golden.reference import specular

LSB = 2.0 ** -10


def test_matches_float_lyon_k2_on_physical_vectors():
    # exact normals (a = 0): the datapath computes Lyon's k = 2 shape, so against the
    # float form it differs only by quantization; 10-bit vectors and n up to 8000
    block = get_block("fig7")
    raw = block.vectors(count=2000, seed=5)
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
    raw = block.vectors(count=0, seed=0)
    out = block.golden(raw)
    assert out["spec0"][0] >= 0.99 * 2 ** 15 and out["spec1"][1] >= 0.99 * 2 ** 15


def test_k_changes_the_shape():
    block = get_block("fig7", shape=ShapeConfig(k=1))
    raw = block.vectors(count=200, seed=1)
    assert not np.array_equal(block.golden(raw)["spec0"], get_block("fig7").golden(raw)["spec0"])


def test_connected_formats_must_agree():
    from phongfx.config import NormalizeConfig
    with pytest.raises(ValueError, match=r"^lirp\.out \(S1\.10\) must equal normalize\.vec \(S1\.8\): they are connected$"):
        Fig7Config(normalize=NormalizeConfig(vec="S1.8"))
    with pytest.raises(ValueError, match=r"^lights must be an integer in 1\.\.8, not 0$"):
        Fig7Config(lights=0)
