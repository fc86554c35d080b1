import re
import warnings

import numpy as np
import pytest
from numpy.testing import assert_allclose, assert_array_equal

from phongfx.golden.reference import METHODS, specular, specular_all

Z = np.array([0.0, 0.0, 1.0])
SQRT3 = np.sqrt(3.0)


def light_at(alpha):
    """Unit L at angle alpha from Z in the x-z plane: with N = V = Z, R = Z, so R.L = cos(alpha)."""
    alpha = np.asarray(alpha, dtype=np.float64)
    return np.stack([np.sin(alpha), np.zeros_like(alpha), np.cos(alpha)], axis=-1)


def test_method_names_in_figure_9_order():
    assert METHODS == (
        "phong", "lyon-k0", "lyon-k1", "lyon-k2", "blinn", "halfway-hnorm-k2",
        "halfway-proj-k2", "halfway-g2proj-k2", "halfway-g2proj-k1", "halfway-g2-k2",
        "torrance-sparrow", "trowbridge-reitz")
    assert list(specular_all(Z, Z, Z, 4)) == list(METHODS)


@pytest.mark.parametrize("n", [1, 4, 256])
def test_all_aligned_gives_one_everywhere(n):
    # N = L = V = z: R = 2z(1) - z = z, R.L = 1, D = L - R = 0, x = 0.
    # H = z, hl = 1, dl = 0, hv1 = hv2 = z; H.N = 1; every projection/difference is 0.
    # Row 11: acos(1) = 0 -> exp(0) = 1.  Row 12: 1 > 0 -> (1/(1 + 0*n))^2 = 1.
    # So no method departs from 1 here.
    for m, v in specular_all(Z, Z, Z, n).items():
        assert_array_equal(v, 1.0, err_msg=m)


def test_thirty_degrees_n4_by_hand():
    # alpha = 30 deg: R.L = cos 30 = sqrt3/2.  n = 4.
    c15 = (np.sqrt(6) + np.sqrt(2)) / 4                 # cos 15 deg
    dl = (2 - SQRT3) / 4                                # 1 - |H|^2, |H|^2 = cos^2 15 = (2+sqrt3)/4
    g = 1 + 0.5 * (dl + dl * dl)                        # g2 approximate normalizer
    d10 = (g / 4) ** 2 + (g * (2 + SQRT3) / 4 - 1) ** 2  # |H g - N|^2, H = (1/4, 0, (2+sqrt3)/4)
    expected = {
        "phong": 9 / 16,                        # (sqrt3/2)^4
        # |D|^2 = 2 - 2cos30 = 2 - sqrt3 = (2 sin 15)^2, x = (4/2)|D|^2 = 4 - 2sqrt3 ~ 0.536
        "lyon-k0": 2 * SQRT3 - 3,               # 1 - x
        "lyon-k1": 4 - 2 * SQRT3,               # (1 - x/2)^2 = (sqrt3 - 1)^2
        "lyon-k2": 9 / 16,                      # (1 - x/4)^4 = cos^4 30: f_2 is exact at n = 4
        "blinn": c15 ** 16,                     # H* is 15 deg from N; n4 = 16
        "halfway-hnorm-k2": (4 * c15 - 3) ** 4,  # xs = (2 - 2c15)*16/2, 1 - xs/4 = 4c15 - 3
        # D = H - (H.N)N = (1/4, 0, 0): xs = (1/16)*16/2 = 1/2, (1 - 1/8)^4
        "halfway-proj-k2": 2401 / 4096,
        # D = g(1/4, 0, 0): xs = g^2/2
        "halfway-g2proj-k2": (1 - g * g / 8) ** 4,
        "halfway-g2proj-k1": (1 - g * g / 4) ** 2,
        "halfway-g2-k2": (1 - 8 * d10 / 4) ** 4,   # xs = 8 |D|^2
        "torrance-sparrow": np.exp(-np.pi ** 2 / 18),  # exp(-(16/2)(pi/12)^2)
        "trowbridge-reitz": (2 + SQRT3) / 6,    # (1/(1 + 4 sin^2 15))^2 = (1/(3 - sqrt3))^2
    }
    got = specular_all(Z, light_at(np.pi / 6), Z, 4)
    for m in METHODS:
        assert_allclose(got[m], expected[m], rtol=1e-14, err_msg=m)
    assert_allclose(expected["halfway-g2proj-k2"], 0.56218992495, rtol=1e-10)  # sanity of g


def test_n1_edges():
    # R = -L (alpha = 180): R.L = -1 -> phong 0.  |D|^2 = 4, x = (1/2)*4 = 2.
    got = specular_all(Z, -Z, Z, 1)
    assert_array_equal(got["phong"], 0.0)
    assert_array_equal(got["lyon-k0"], 0.0)       # 2 > 1
    assert_array_equal(got["lyon-k1"], 0.0)       # 2 > 2 false -> (1 - 2/2)^2 = 0
    assert_array_equal(got["lyon-k2"], 0.0625)    # (1 - 2/4)^4 = 1/16: never zero at n = 1

    # alpha = 90: R.L = 0 exactly, |D|^2 = |(1,0,-1)|^2 = 2, x = 1 exactly.
    got = specular_all(Z, [1.0, 0, 0], Z, 1)
    assert_array_equal(got["lyon-k0"], 0.0)       # 1 > 1 false -> 1 - 1 = 0
    assert_array_equal(got["lyon-k1"], 0.25)      # (1 - 1/2)^2
    assert_array_equal(got["phong"], 0.0)
    # `dot > 0` is false at 0, so even n = 0 gives 0 there, not 0**0 = 1.
    assert_array_equal(specular("phong", Z, [1.0, 0, 0], Z, 0), 0.0)
    assert_array_equal(specular("phong", Z, light_at(1.0), Z, 0), 1.0)

    # alpha = 120: R.L = -1/2 -> phong 0 (the abrupt cut); |D|^2 = 2 + 1 = 3, x = 1.5.
    got = specular_all(Z, light_at(2 * np.pi / 3), Z, 1)
    assert_array_equal(got["phong"], 0.0)
    assert_array_equal(got["lyon-k0"], 0.0)                            # 1.5 > 1
    assert_allclose(got["lyon-k1"], 0.0625, rtol=1e-14)                 # (1 - 0.75)^2
    assert_allclose(got["lyon-k2"], 0.152587890625, rtol=1e-14)         # (1 - 0.375)^4 = 0.625^4

    # Just either side of x = 1 for k0: alpha = 90 -/+ 0.01 rad, x = 1 -/+ sin(0.01).
    below, above = specular("lyon-k0", Z, light_at([np.pi / 2 - 0.01, np.pi / 2 + 0.01]), Z, 1)
    assert_allclose(below, np.sin(0.01), rtol=1e-10)
    assert above == 0.0

    # Over all angles at n = 1, f_2 stays >= 1/16 while phong is 0 past 90 degrees.
    alphas = np.linspace(0, np.pi, 181)
    got = specular_all(Z, light_at(alphas), Z, 1)
    assert np.all(got["lyon-k2"] >= 0.0625 - 1e-15)
    assert np.all(got["phong"][alphas > np.pi / 2 + 1e-9] == 0)


def test_lyon_k2_n4_zero_from_90_degrees():
    # n = 4: x = 2(2 - 2cos a) = 4 - 4cos a, so x > 4 iff cos a < 0; at 90, x = 4 -> (1-1)^4 = 0.
    got = specular("lyon-k2", Z, light_at(np.array([np.pi / 3, np.pi / 2, 2.0])), Z, 4)
    assert_allclose(got, [0.0625, 0.0, 0.0], atol=1e-15)  # cos^4 60 = 1/16


def test_blinn_and_hnorm_agree_for_small_angles_large_n():
    # With H* at angle t from N (t = alpha/2) and s = n(1 - cos t):
    # blinn = cos^(4n) t = (1 - s/n)^(4n) ~ exp(-4s); hnorm: |H*-N|^2 = 2(1 - cos t),
    # xs = 2(1 - cos t)*4n/2 = 4s, so hnorm = (1 - s)^4 = 1 - 4s + ... : same first-order falloff.
    n = 1024
    t = np.linspace(0, np.arccos(1 - 0.05 / n), 50)     # s from 0 to 0.05
    got = specular_all(Z, light_at(2 * t), Z, n)
    s = n * (1 - np.cos(t))
    assert_allclose(got["blinn"], np.cos(t) ** (4 * n), rtol=1e-9)
    assert_allclose(got["halfway-hnorm-k2"], (1 - s) ** 4, rtol=1e-9)
    # exp(-0.2) = 0.8187 vs 0.95^4 = 0.8145 at the far end: within 0.005
    assert np.max(np.abs(got["blinn"] - got["halfway-hnorm-k2"])) < 0.005


@pytest.mark.parametrize("n", [16, 64, 256])
def test_row10_loses_glancing_highlight(n):
    # Grazing mirror configuration, 10 deg above the surface: V = (-cos, 0, sin), L = (cos, 0, sin).
    # R = 2N sin10 - V = L exactly, so phong peaks.  H = (0, 0, sin10): |H|^2 = 0.0302,
    # dl = 0.9698, g = 1 + (0.9698 + 0.9406)/2 = 1.9552, H g = (0, 0, 0.3395): still far too short.
    # Row 10: |Hg - N|^2 = 0.6605^2 = 0.4362, xs = 0.4362*4n/2 >= 13.96 > 4 -> 0.
    # Row 8: Hg is parallel to N, so D = Hg - (Hg.N)N = 0 -> xs = 0 -> 1.
    phi = np.radians(10)
    V = [-np.cos(phi), 0, np.sin(phi)]
    L = [np.cos(phi), 0, np.sin(phi)]
    got = specular_all(Z, L, V, n)
    assert_allclose(got["phong"], 1.0, rtol=1e-12)
    assert_array_equal(got["halfway-g2-k2"], 0.0)
    assert_array_equal(got["halfway-g2proj-k2"], 1.0)
    assert_array_equal(got["halfway-proj-k2"], 1.0)


def random_unit(rng, shape):
    v = rng.normal(size=shape + (3,))
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def test_torrance_and_trowbridge_use_blinn_dot():
    rng = np.random.default_rng(43)
    N, L, V = (random_unit(rng, (200,)) for _ in range(3))
    n = rng.uniform(1, 100, size=200)
    H = (L + V) / 2
    c = np.sum(H / np.linalg.norm(H, axis=-1, keepdims=True) * N, axis=-1)  # hv2 . N
    got = specular_all(N, L, V, n)
    assert np.any(c <= 0) and np.any(c > 0)
    assert_allclose(got["blinn"], np.where(c > 0, np.abs(c) ** (4 * n), 0), rtol=1e-10, atol=1e-300)
    # Row 11: Gaussian in the H*-N angle with n4 = 4n; row 12 uses n itself, not n4.
    assert_allclose(got["torrance-sparrow"], np.exp(-2 * n * np.arccos(c) ** 2),
                    rtol=1e-10, atol=1e-300)
    assert_allclose(got["trowbridge-reitz"],
                    np.where(c > 0, 1 / (1 + (1 - c * c) * n) ** 2, 1 / (1 + n) ** 2), rtol=1e-12)


def test_trowbridge_floor_when_h_faces_away():
    # V = L = -z, N = z: hv2 = -z, dot = -1 <= 0 -> (1/(1+4))^2 = 1/25, not n4 = 16 (1/289).
    assert_allclose(specular("trowbridge-reitz", Z, -Z, -Z, 4), 0.04, rtol=1e-15)
    assert_allclose(specular("torrance-sparrow", Z, -Z, -Z, 1), np.exp(-2 * np.pi ** 2), rtol=1e-12)


def test_zero_length_halfway_vector():
    # L = -V = -z, N = z, n = 1.  hv = 0, hl = 0: hv2 is taken as the zero vector, dot = 0.
    expected = {
        "phong": 0.0,                # R = z, R.L = -1
        "lyon-k0": 0.0,              # |D|^2 = 4, x = 2 > 1
        "lyon-k1": 0.0,              # 2 > 2 false: (1 - 1)^2
        "lyon-k2": 0.0625,           # (1 - 1/2)^4
        "blinn": 0.0,                # dot = 0, not > 0
        "halfway-hnorm-k2": 0.0625,  # D = 0 - N, |D|^2 = 1, xs = 1*4/2 = 2, (1 - 2/4)^4
        "halfway-proj-k2": 1.0,      # D = 0 - 0
        "halfway-g2proj-k2": 1.0,    # hv1 = (1 + (1 + 1)/2)*0 = 0, D = 0
        "halfway-g2proj-k1": 1.0,
        "halfway-g2-k2": 0.0625,     # D = 0 - N, as row 6
        "torrance-sparrow": np.exp(-np.pi ** 2 / 2),  # acos(0) = pi/2: exp(-(4/2)(pi/2)^2)
        "trowbridge-reitz": 0.25,    # dot = 0 -> (1/(1+1))^2
    }
    # A batch mixing the degenerate case with an ordinary one; nothing may warn or trap.
    L = np.stack([-Z, light_at(0.3)])
    with warnings.catch_warnings(), np.errstate(divide="raise", invalid="raise", over="raise"):
        warnings.simplefilter("error")
        got = specular_all(Z, L, Z, 1)
    for m in METHODS:
        assert np.all(np.isfinite(got[m])), m
        assert_allclose(got[m][0], expected[m], rtol=1e-15, err_msg=m)


def test_vectorized_matches_scalar_calls():
    rng = np.random.default_rng(1993)
    N = random_unit(rng, (4, 5))
    L = random_unit(rng, (5,))     # broadcast over the first axis
    V = random_unit(rng, (4, 5))
    n = rng.choice([1.0, 4.0, 16.0, 64.0, 256.0], size=5)
    got = specular_all(N, L, V, n)
    for m in METHODS:
        assert got[m].shape == (4, 5) and got[m].dtype == np.float64
        one = np.array([[specular(m, N[i, j], L[j], V[i, j], n[j]) for j in range(5)]
                        for i in range(4)])
        assert_allclose(got[m], one, rtol=1e-13, atol=1e-300, err_msg=m)
        assert_array_equal(specular(m, N, L, V, n), got[m])


def test_rotation_invariance():
    # The same 30-degree configuration, rotated: every method depends only on angles.
    rng = np.random.default_rng(7)
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    base = specular_all(Z, light_at(np.pi / 6), Z, 4)
    rot = specular_all(q @ Z, q @ light_at(np.pi / 6), q @ Z, 4)
    for m in METHODS:
        assert_allclose(rot[m], base[m], rtol=1e-12, err_msg=m)


def test_unknown_method():
    with pytest.raises(ValueError, match=r"^unknown specular method 'foo'; valid methods: phong, "):
        specular("foo", Z, Z, Z, 1)
    with pytest.raises(ValueError, match=re.escape(", ".join(METHODS)) + "$"):
        specular("Phong", Z, Z, Z, 1)


def test_rejects_non_3_vectors():
    with pytest.raises(ValueError, match=r"^L must have shape \(\.\.\., 3\)"):
        specular_all(Z, [1.0, 0.0], Z, 1)


def test_shape_rows_at_any_k():
    # the datapaths' float form at their own k: row 2 (lyon) and row 8 (halfway-g2proj)
    rng = np.random.default_rng(11)
    N = rng.normal(size=(200, 3))
    N /= np.linalg.norm(N, axis=1)[:, None]
    L, V = np.array([0.36, 0.48, 0.8]), np.array([0.0, 0.0, 1.0])
    # at 2^k = n, f_k(n/2·|L-R|²) = (R·L)^n wherever R·L > 0 (x = n(1 - R·L) <= 2^k)
    phong = specular("phong", N, L, V, 16)
    lit = phong > 0
    np.testing.assert_allclose(specular("lyon-k4", N, L, V, 16)[lit], phong[lit], atol=1e-12)
    R = 2 * N * (N @ V)[:, None] - V
    x = 40 / 2 * np.sum((L - R) ** 2, axis=1)
    np.testing.assert_allclose(specular("lyon-k7", N, L, V, 40), np.where(x > 128, 0, 1 - x / 128) ** 128)
    # the printed rows come out of the same formula
    for k in (1, 2):
        np.testing.assert_array_equal(specular(f"halfway-g2proj-k{k}", N, L, V, 9),
                                      specular_all(N, L, V, 9)[f"halfway-g2proj-k{k}"])
    with pytest.raises(ValueError, match="unknown specular method 'lyon-kx'"):
        specular("lyon-kx", N, L, V, 16)
