import numpy as np
import pytest

from phongfx.config import HALFWAY_VARIANTS, HalfwayConfig, NormalizeConfig
from phongfx.core.registry import get_block
from phongfx.golden.fixed import Fixed
from phongfx.golden.halfway import halfway
from phongfx.golden.reference import specular
from phongfx.sim.stimulus import AXES, codes, rng, unit_vectors
from phongfx.sim.stimulus.halfway import GRAZING_DEGREES, grazing

LSB = 2.0 ** -10
VEC = HalfwayConfig().fmt("vec")
HS = ["mean", "sum"]
#: Figure 9 row of each variant with h = "mean" and 4n (d1, d2: D1 = (R - L)/2, so row 4)
ROWS = {"d1": "lyon-k2", "d2": "lyon-k2", "d3": "halfway-proj-k2", "g2proj": "halfway-g2proj-k2",
        "g2": "halfway-g2-k2"}


def config(variant, h="mean", rounding="round_half_up"):
    return HalfwayConfig(variant=variant, h=h, rounding=rounding,
                         normalize=HalfwayConfig().normalize.replace(rounding=rounding))


def run(cfg, n, l, v):
    """Fixed p, q and D = p - q (floats) of float inputs, quantized to ``cfg.vec``."""
    out = halfway(cfg, *(Fixed(codes(x, VEC), VEC) for x in (n, l, v)))
    p, q = out["p"].to_float(), out["q"].to_float()
    return p, q, p - q


def exact(raw, cfg):
    """float64 p, q of the same (quantized) inputs; g2 of z clamped at 2, as z saturates."""
    n, l, v = (raw[name] * LSB for name in "nlv")
    h = v + l if cfg.h == "sum" else (v + l) / 2
    if cfg.variant in ("g2proj", "g2"):
        y = 1 - np.minimum(np.sum(h * h, axis=-1), 2.0)
        h = (1 + (y + y * y) / 2)[:, None] * h
    if cfg.variant == "g2":
        return n, h
    w = {"d1": v, "d2": l}.get(cfg.variant, h)
    dot = np.sum(w * n, axis=-1) * (2 if cfg.variant in ("d1", "d2") and cfg.h == "sum" else 1)
    return dot[:, None] * n, h


def unit_part(raw):
    """The vectors whose N, L, V are all unit codes (within 2 LSB), not junk."""
    keep = np.all([np.abs(np.linalg.norm(raw[name], axis=-1) - VEC.one) < 2 for name in "nlv"], axis=0)
    return {name: column[keep] for name, column in raw.items()}


def bounds(variant, h, rounding):
    """Per-component error of (p, q) against :func:`exact`, in out LSBs.

    ``r``: one rounding (1/2 of its LSB, 1 truncating).  The dot's LSB is 1/4 of out's,
    through ``|N_i| <= 1`` (doubled for d1/d2 with "sum"); p adds its own ``r``.  ``H``
    (S2.11) to out drops one bit with "mean": 1/2 either way; it is exact with "sum".
    ``H*``: z, y², g each err by ``r`` of 1.12 through ``|H|·|dg/dy| <= 0.71``, ``|H|/2``
    and ``|H_i|`` (0.28 LSB; with "sum" ``|H|`` up to √2 below saturation: 0.35), plus
    ``r/2`` of its S2.11 rounding; ``H*·N`` carries ``|ΔH*| <= √3·ΔH*`` into p.
    """
    r = 1.0 if rounding == "truncate" else 0.5
    hq = 0.5 if h == "mean" else 0.0
    if variant in ("d1", "d2", "d3"):
        double = 2 if variant != "d3" and h == "sum" else 1
        return double * r / 4 + r, hq
    hstar = 2 * r * (0.28 if h == "mean" else 0.35) + r / 2
    if variant == "g2proj":
        return np.sqrt(3) * hstar + r / 4 + r, hstar + 0.5
    return 0.0, hstar + 0.5


def f_k(x, k):
    return np.where(x > 2 ** k, 0.0, (1 - np.minimum(x, 2 ** k) / 2 ** k) ** (2 ** k))


@pytest.mark.parametrize("h", HS)
@pytest.mark.parametrize("variant", HALFWAY_VARIANTS)
@pytest.mark.parametrize("rounding", ["round_half_up", "truncate"])
def test_unit_inputs_match_float_within_stated_lsbs(variant, h, rounding):
    cfg = config(variant, h, rounding)
    raw = unit_part(get_block("halfway", config=cfg).stimulus(count=3000, seed=3))
    assert len(raw["n"]) > 3500
    out = halfway(cfg, *(Fixed(raw[name], cfg.vec) for name in "nlv"))
    p, q = exact(raw, cfg)
    err_p = np.abs(out["p"].to_float() - p) / LSB
    err_q = np.abs(out["q"].to_float() - q) / LSB
    bound_p, bound_q = bounds(variant, h, rounding)
    assert err_p.max() <= bound_p
    assert err_q.max() <= bound_q
    if rounding == "round_half_up":
        # the length of D's error, measured <= 1.83 LSB: test_mean_with_4n_... builds on it
        d = (out["p"].to_float() - out["q"].to_float()) - (p - q)
        assert np.linalg.norm(d, axis=-1).max() <= 2 * LSB


@pytest.mark.parametrize("h", HS)
@pytest.mark.parametrize("variant", ["d1", "d2", "d3", "g2proj"])
def test_peak_gives_a_short_difference(variant, h):
    # N along H: D is 0 but for N's codes, which miss H/|H| by up to √3/2 LSB in direction
    # and length (scaled by |H| <= 2 with "sum"), and the roundings; measured 2.45 / 3.61
    g = rng(1)
    v, l = unit_vectors(2000, g), unit_vectors(2000, g)
    h_vec = v + l
    keep = np.linalg.norm(h_vec, axis=-1) > 0.1
    n = h_vec[keep] / np.linalg.norm(h_vec[keep], axis=-1, keepdims=True)
    _, _, d = run(config(variant, h), n, l[keep], v[keep])
    assert np.linalg.norm(d, axis=-1).max() <= (3 if h == "mean" else 4) * LSB


@pytest.mark.parametrize("h", HS)
@pytest.mark.parametrize("variant", HALFWAY_VARIANTS)
def test_zero_halfway_vector_is_defined(variant, h):
    # V = -L: H = 0, z = 0 saturates g2 to 2 - 2^-12, H* = 0; no exception, every code defined
    n = np.concatenate([AXES, unit_vectors(20, rng(2))])
    v = codes(unit_vectors(len(n), rng(3)), VEC)
    cfg = config(variant, h)
    out = halfway(cfg, Fixed(codes(n, VEC), VEC), Fixed(-v, VEC), Fixed(v, VEC))
    p, q = out["p"].to_float(), out["q"].to_float()
    np.testing.assert_equal(q, 0)
    if variant in ("d3", "g2proj"):
        np.testing.assert_equal(p, 0)  # D = 0: the full highlight of a vanishing H
    elif variant == "g2":
        np.testing.assert_equal(p, codes(n, VEC) * LSB)  # D = N
    else:
        # R - L = 2(V·N)N (halved with "mean"), d2 its negative
        vn = np.sum(v * LSB * codes(n, VEC) * LSB, axis=-1)[:, None] * codes(n, VEC) * LSB
        want = (1 if variant == "d1" else -1) * (2 if h == "sum" else 1) * vn
        assert np.abs(p - want).max() <= 0.75 * LSB


@pytest.mark.parametrize("h", HS)
def test_d1_and_d2_have_equal_lengths(h):
    # |D1|² - |D2|² = 4(|N|² - 1)((V·N)² - (L·N)²) (quartered with "mean"): zero for unit N,
    # a few LSB for N's codes, which the float gap of the same codes holds; beyond it
    # only the roundings of p and q, per component 3/4 ("sum") or 5/8 + 1/2 ("mean")
    block = get_block("halfway", variant="d1", h=h)
    raw = unit_part(block.stimulus(count=3000, seed=8))
    lengths = []
    for variant in ("d1", "d2"):
        cfg = config(variant, h)
        out = halfway(cfg, *(Fixed(raw[name], cfg.vec) for name in "nlv"))
        p, q = exact(raw, cfg)
        lengths.append((np.linalg.norm(out["p"].to_float() - out["q"].to_float(), axis=-1),
                        np.linalg.norm(p - q, axis=-1)))
    (fixed1, float1), (fixed2, float2) = lengths
    rounding = np.sqrt(3) * (0.75 if h == "sum" else 1.125) * LSB
    assert np.all(np.abs(fixed1 - fixed2) <= np.abs(float1 - float2) + 2 * rounding)
    axis = np.all(np.abs(raw["n"]) % VEC.one == 0, axis=-1)  # N exactly unit: float gap 0
    assert np.count_nonzero(axis) >= 200
    assert np.abs(fixed1 - fixed2)[axis].max() <= 2 * rounding


@pytest.mark.parametrize("variant, method, k", [(*item, 2) for item in ROWS.items()]
                         + [("g2proj", "halfway-g2proj-k1", 1)])
def test_mean_with_4n_reproduces_appendix_rows(variant, method, k):
    # x = (4n/2)|D|² from the fixed-point D, f_k in float, against specfuns.m on the same
    # codes (row 9 is row 8's D with k = 1).  A |D| error δ moves f_k by at most
    # 2√2·δ·√n·max √x|f_k'(x)| = C_k·δ·√n (C_2 = 1.35, C_1 = 1.54), δ <= 2 LSB (asserted above)
    cfg = config(variant)
    raw = unit_part(get_block("halfway", config=cfg).stimulus(count=3000, seed=5))
    out = halfway(cfg, *(Fixed(raw[name], cfg.vec) for name in "nlv"))
    d = out["p"].to_float() - out["q"].to_float()
    normal, l, v = (raw[name] * LSB for name in "nlv")
    for n in (1, 4, 16, 64, 256):
        amount = f_k(2 * n * np.sum(d * d, axis=-1), k)
        err = np.abs(amount - specular(method, normal, l, v, n))
        assert err.max() <= (1.35 if k == 2 else 1.54) * 2 * LSB * np.sqrt(n)


@pytest.mark.parametrize("n", [64, 256])
def test_row_10_loses_the_glancing_highlight_row_8_keeps_it(n):
    # at the peak N = H/|H| with H short: Lyon's light 1 ([1, 1, -1], 125° from V = z, |H| =
    # 0.46) and L, V opening from 120° to 180° (|H| = cos φ down to 0).  H* = g2(z)·H stays
    # short, so row 10's D = H* - N never gets short; row 8 projects the length error away
    light = np.array([[1.0, 1.0, -1.0]]) / np.sqrt(3)
    view = np.array([[0.0, 0.0, 1.0]])
    peak = (light + view) / np.linalg.norm(light + view)
    normal, l, v = grazing(8, rng(4))
    wide = np.repeat(np.array(GRAZING_DEGREES) >= 60, 8)
    normal, l, v = (np.concatenate([a, b[wide]]) for a, b in ((peak, normal), (light, l), (view, v)))
    refs = {name: specular(ROWS[name], normal, l, v, n) for name in ("g2proj", "g2")}
    assert np.all(refs["g2proj"] > 0.999) and np.all(refs["g2"] < 1e-3)
    for variant, keeps in (("g2proj", True), ("g2", False)):
        _, _, d = run(config(variant), normal, l, v)
        amount = f_k(2 * n * np.sum(d * d, axis=-1), 2)
        assert np.all(amount > 0.99) if keeps else np.all(amount < 1e-3)


def test_g2_leaves_a_long_sum_unnormalized():
    # h = "sum", V·L >= 0: |H| >= √2, z = H·H saturates just below 2, where g2 rounds to 1,
    # so H* = H, up to 2 long; between 1 and √2 g2 shrinks it by 1/8 at most.  The code's
    # (L + V)/2 keeps z <= 1, where g2 is good to 0.5 % for |H| >= 0.8 (Figure 4)
    g = rng(6)
    v, l = unit_vectors(3000, g), unit_vectors(3000, g)
    near = np.sum(v * l, axis=-1) >= 0.05
    n = unit_vectors(int(np.count_nonzero(near)), g)
    _, q_g2, _ = run(config("g2", "sum"), n, l[near], v[near])
    _, q_h, _ = run(config("d3", "sum"), n, l[near], v[near])
    np.testing.assert_equal(q_g2, q_h)
    assert np.linalg.norm(q_g2, axis=-1).min() >= np.sqrt(2) - 2 * LSB
    _, q_mean, _ = run(config("g2", "mean"), n, l[near], v[near])
    long = np.linalg.norm(l[near] + v[near], axis=-1) >= 1.6
    assert np.abs(np.linalg.norm(q_mean[long], axis=-1) - 1).max() < 0.005 + 2 * LSB


@pytest.mark.parametrize("variant", HALFWAY_VARIANTS)
def test_junk_codes_saturate_instead_of_wrapping(variant):
    # every component at the top (bottom) of S1.10, "sum": H = 4 - 2^-9 (-4), which S2.10
    # holds, so q = H (z saturates, g2 = 1: H* = H too); the dot (24) saturates near 4 and
    # p (up to 16) clamps to the end of S2.10, but for g2, whose p is N itself
    cfg = config(variant, "sum")
    for raw, end in ((VEC.max_raw, 4095), (VEC.min_raw, -4096)):
        x = Fixed(np.full((1, 3), raw), VEC)
        out = halfway(cfg, x, x, x)
        np.testing.assert_equal(out["q"].raw, [[2 * raw] * 3])
        np.testing.assert_equal(out["p"].raw, [[raw] * 3] if variant == "g2" else [[end] * 3])


def test_vectors_are_seeded_and_start_with_axis_triples():
    block = get_block("halfway")
    a, b, c = (block.stimulus(count=50, seed=s) for s in (1, 1, 2))
    for name in "nlv":
        np.testing.assert_equal(a[name], b[name])
    assert not np.array_equal(a["n"], c["n"])
    triples = {tuple(map(tuple, (a["n"][i], a["l"][i], a["v"][i]))) for i in range(216)}
    assert len(triples) == 216 and np.all(np.abs(a["n"][:216]).sum(axis=-1) == 1024)
    assert np.any(np.all(a["l"] + a["v"] == 0, axis=-1) & np.any(a["v"] != 0, axis=-1))  # H = 0


def test_default_formats_hold_both_conventions():
    cfg = HalfwayConfig()
    assert (cfg.hvec, cfg.dot, cfg.out) == ("S2.11", "S2.12", "S2.10")
    assert cfg.normalize.vec == cfg.hvec and cfg.normalize.z == "1.12"
    assert get_block("halfway", h="sum").config.normalize == cfg.normalize


def test_config_errors_name_the_field():
    with pytest.raises(ValueError, match=r"^variant must be one of d1, d2, d3, g2proj, g2, not 'd4'$"):
        HalfwayConfig(variant="d4")
    with pytest.raises(ValueError, match=r"^h must be one of sum, mean, not 'half'$"):
        HalfwayConfig(h="half")
    with pytest.raises(ValueError, match=r"^hvec must be a signed format \(Sn\.m\), not 2\.11$"):
        HalfwayConfig(hvec="2.11")
    with pytest.raises(ValueError, match=r"^dot must hold exactly 1\.0 \(at least 1 integer bit\), not S0\.12$"):
        HalfwayConfig(dot="S0.12")
    with pytest.raises(ValueError, match=r"^out must be a signed format \(Sn\.m\), not 2\.10$"):
        HalfwayConfig(out="2.10")
    with pytest.raises(ValueError, match=r"^normalize\.vec \(S1\.10\) must equal hvec \(S2\.11\): "
                                         r"the normalizer takes H$"):
        HalfwayConfig(normalize=NormalizeConfig())
    with pytest.raises(TypeError, match=r"^normalize must be a NormalizeConfig, not 'g2'$"):
        HalfwayConfig(normalize="g2")
    with pytest.raises(ValueError, match=r"^rounding must be one of truncate, round_half_up, "
                                         r"round_half_even, not 'nearest'$"):
        HalfwayConfig(rounding="nearest")
