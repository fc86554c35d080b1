import math

import numpy as np
import pytest

from phongfx.config import BlinnConfig
from phongfx.core.format import Format
from phongfx.core.registry import get_block
from phongfx.golden.blinn import (blinn, even_shift, exp2_tables, log2_t, log2_tables, pow2, reciprocal_sqrt,
                                  rsqrt_table)
from phongfx.golden.fixed import Fixed
from phongfx.sim.stimulus import at_angle, codes, rng, unit_vectors
from phongfx.sim.stimulus.blinn import directed, edge_n

CONFIG = BlinnConfig()
VEC = CONFIG.fmt("vec")

# -- error bounds derived from the defaults (see phongfx.golden.blinn) ---------------
# seed: cell balance 2^-A (A = 9) plus the table's half LSB (2^-18 over y0 >= 1)
SEED = 2.0 ** -9 + 2.0 ** -18
# Newton–Raphson 3e²/2 + e³/2, the roundings of y0² and p (2^-21 each, halved by (3-p)/2,
# relative to p ~ 1), and of y1 (2^-18 over y1 >= 1)
RSQRT = 1.5 * SEED ** 2 + 0.5 * SEED ** 3 + 2.0 ** -21 + 2.0 ** -18
# cosine: relative RSQRT and m's rounding (2^-19 on m >= 1/4 is 2^-17, half of it through
# 1/sqrt), the dot product's half LSB (2^-18) times y1 < 2, the output's half LSB
COSINE = 1.0001 * (RSQRT + 2.0 ** -18 * 1.0001) + 2.0 ** -17 + 2.0 ** -16
# log2: chord sag h²/8·max|f''| (h = 2^-8, f'' = -1/((1+u)² ln 2)), node and step roundings
LOG = 2.0 ** -16 / (8 * math.log(2)) + 2.0 ** -21 + 2.0 ** -21
# 2^f: chord sag h²/8·(ln 2)²·2, node and step roundings (1.18), relative to 2^f >= 1
EXP = 2.0 ** -16 / 8 * math.log(2) ** 2 * 2 + 2.0 ** -19 + 2.0 ** -19
HALF = 2.0 ** -16  # half an LSB of out = 1.15


def vec(values):
    return Fixed(codes(np.asarray(values, dtype=float), VEC), VEC)


def run(normal, light, half, n, config=CONFIG):
    normal = normal if isinstance(normal, Fixed) else vec(normal)
    count = len(normal.raw)
    light = light if isinstance(light, Fixed) else vec(np.broadcast_to(light, (count, 3)))
    half = half if isinstance(half, Fixed) else vec(np.broadcast_to(half, (count, 3)))
    n = Fixed(np.broadcast_to(np.asarray(n, dtype=np.int64), (count,)), config.n)
    out = blinn(config, normal, light, half, n)
    return out["diffuse"], out["specular"]


def cosines(normal, other):
    """Float ``max(N·X, 0)/|N|`` of the codes, clamped to 1 (a cosine)."""
    n, x = normal.to_float(), other.to_float()
    return np.clip((n * x).sum(-1) / np.sqrt((n * n).sum(-1)), 0, 1)


def test_rsqrt_every_m_code_within_the_newton_bound():
    m = Fixed(np.arange(1 << 16, 1 << 18), CONFIG.m)  # every m in [1/4, 1)
    error = reciprocal_sqrt(CONFIG, m).to_float() * np.sqrt(m.to_float()) - 1
    assert np.max(np.abs(error)) <= RSQRT < 2.0 ** -16.5
    # the seed alone is only good to 2^-9: one step squares its error
    seed = Fixed(rsqrt_table(CONFIG)[m.raw >> 9], CONFIG.y).to_float() * np.sqrt(m.to_float()) - 1
    assert 2.0 ** -10 < np.max(np.abs(seed)) <= SEED


def test_even_shift_brings_q_to_a_quarter_to_one():
    g = rng(3)
    q = Fixed(np.concatenate([g.integers(1, 3 << 32, 5000), 1 << np.arange(34), [0]]), CONFIG.q)
    j, m = even_shift(CONFIG, q)
    nonzero = q.raw > 0
    assert np.all(m.to_float()[nonzero] >= 0.25) and np.all(m.to_float() < 1)
    h = CONFIG.q.int_bits // 2
    np.testing.assert_allclose(m.to_float()[nonzero] * 4.0 ** (h - j[nonzero]), q.to_float()[nonzero],
                               rtol=2.0 ** -17)
    assert m.raw[-1] == 0 and j[-1] == 16  # q = 0: every pair is zero


def test_log2_every_t_code():
    t = Fixed(np.arange(1, (1 << 15) + 1), CONFIG.t)
    lam = log2_t(CONFIG, t)
    assert lam.fmt == Format(4, 20, True)
    assert np.max(np.abs(lam.to_float() - np.log2(t.to_float()))) <= LOG
    powers = 1 << np.arange(16)  # t = 2^-s: the table's node 0 is exactly 0
    np.testing.assert_array_equal(log2_t(CONFIG, Fixed(powers, CONFIG.t)).to_float(), np.arange(-15, 1))


def test_pow2_every_fraction():
    f = np.arange(1 << 20)
    for floor in (-1, -4, -16):
        x = Fixed(((floor << 20) + f), Format(17, 20, True))
        exact = 2.0 ** x.to_float()
        got = pow2(CONFIG, x).to_float()
        assert np.all(np.abs(got - exact) <= exact * EXP + HALF)
    assert pow2(CONFIG, Fixed([0], Format(17, 20, True))).raw[0] == 1 << 15  # 2^0 = 1 exactly
    # past the flush shift 2^x < 2^-17 rounds to 0 anyway; just before it, it need not
    assert CONFIG.flush == 17
    x = Fixed([-(18 << 20), -(17 << 20) - 1, -(15 << 20)], Format(17, 20, True))
    np.testing.assert_array_equal(pow2(CONFIG, x).raw, [0, 0, 1])


def sample(count, seed, n):
    """Unit and shortened normals (|N| in 0.5..1); H near N (within 4/sqrt(n)), L random."""
    g = rng(seed)
    alpha = g.uniform(0, 1, count) * min(4 / math.sqrt(n), math.pi)
    h, u = at_angle(alpha, g)
    length = np.where(np.arange(count) % 2, 1.0, g.uniform(0.5, 1.0, count))
    return vec(u * length[:, None]), vec(unit_vectors(count, g)), vec(h)


def within_bounds(spec, t, n):
    """``spec`` against ``t^n``: ``t`` within COSINE, ``log2`` within LOG (scaled by ``n``),
    ``2^f`` within EXP, then half an LSB."""
    low = np.clip(t - COSINE, 0, 1) ** n * 2.0 ** (-n * LOG) * (1 - EXP) - HALF
    high = np.minimum(t + COSINE, 1) ** n * 2.0 ** (n * LOG) * (1 + EXP) + HALF
    return (spec >= low) & (spec <= high)


def test_diffuse_is_within_the_cosine_bound():
    normal, light, _ = sample(20000, 1, 1)
    diffuse, _ = run(normal, light, light, 1)
    error = np.abs(diffuse.to_float() - cosines(normal, light))
    assert np.max(error) <= COSINE < 2.0 ** -15 * 1.25


@pytest.mark.parametrize("n", [1, 8, 64, 500, 8000])
def test_specular_error_against_float_phong(n):
    normal, light, half = sample(20000, n, n)
    _, spec = run(normal, light, half, n)
    t = cosines(normal, half)
    spec = spec.to_float()
    assert np.all(within_bounds(spec, t, n))
    levels = np.abs(spec - t ** n) * 255
    print(f"n = {n}: max {levels.max():.3f}, mean {levels.mean():.4f} 8-bit levels")
    # Lyon's error magnification: a 16-bit cosine costs about n·2^-16 of the peak
    assert levels.max() <= 255 * (n * COSINE + 2 * HALF) * 1.05


def test_axis_normals_give_exactly_one_and_zero():
    ns = edge_n(CONFIG)
    for axis in np.concatenate([np.eye(3), -np.eye(3)]):
        for scale in (1.0, 0.5, 2.0 ** -15):  # unit, half, the shortest nonzero N
            normal = np.tile(axis * scale, (len(ns), 1))
            diffuse, spec = run(normal, axis, axis, ns)  # t = 1 exactly
            assert np.all(diffuse.raw == 1 << 15) and np.all(spec.raw == 1 << 15)
            for other in (-axis, np.roll(axis, 1)):  # N·H = -1 and N·H = 0
                diffuse, spec = run(normal, other, other, ns)
                assert not np.any(diffuse.raw) and not np.any(spec.raw)


def test_zero_normal_gives_zero():
    diffuse, spec = run(np.zeros((7, 3)), [1, 0, 0], [1, 0, 0], edge_n(CONFIG))
    assert not np.any(diffuse.raw) and not np.any(spec.raw)


def test_shortest_normals_off_axis():
    # one LSB on every axis: |N| = sqrt(3)·2^-15, t = 1 towards (1,1,1)/sqrt(3)
    normal = Fixed(np.array([[1, 1, 1], [1, -1, 0]]), VEC)
    light = vec([[1, 1, 1], [1, -1, 0]] / np.array([[3 ** .5], [2 ** .5]]))
    diffuse, spec = run(normal, light, light, [1, 8000])
    t = cosines(normal, light)
    assert np.all(np.abs(diffuse.to_float() - t) <= COSINE)
    assert np.all(within_bounds(spec.to_float(), t, np.array([1, 8000])))


def test_n_1_is_the_cosine_and_n_8000_just_below_one():
    t = 1 - 2.0 ** -15  # the largest cosine below 1: (1 - 2^-15)^8000 = e^-0.2441...
    x = Fixed([(1 << 15) - 1, 1 << 14], CONFIG.t)
    lam = log2_t(CONFIG, x)
    spec = pow2(CONFIG, Fixed(np.array([8000, 1]), CONFIG.n) * lam).to_float()
    assert abs(spec[0] - t ** 8000) <= t ** 8000 * (2.0 ** (8000 * LOG) * (1 + EXP) - 1) + HALF
    assert spec[1] == 0.5  # 2^-1 is a node of both tables


def test_inputs_are_validated():
    with pytest.raises(ValueError, match=r"^n must be in 1\.\.8000; 2 value\(s\) are not, "
                                         r"first 0 \(raw 0\)$"):
        run(np.eye(3), [1, 0, 0], [1, 0, 0], [0, 8001, 5])


def test_tables_hold_exact_ends():
    lt, ld, ld_fmt = log2_tables(CONFIG)
    et, ed, ed_fmt = exp2_tables(CONFIG)
    assert lt[0] == 0 and lt[-1] + ld[-1] == 1 << 20  # log2 1 = 0, log2 2 = 1
    assert et[0] == 1 << 18 and et[-1] + ed[-1] == 2 << 18  # 2^0 = 1, 2^1 = 2
    # the steps times 2^A are below 1/ln 2 and 2 ln 2: one integer bit each
    assert (ld_fmt, ed_fmt) == (Format(1, 12), Format(1, 10))
    seeds = rsqrt_table(CONFIG)
    assert not np.any(seeds[:128]) and np.all(seeds[128:] > 1 << 17)  # 1 < y0 < 2 where read


def test_config_errors_name_the_field():
    cases = [
        (dict(vec="1.15"), r"^vec must be a signed format \(Sn\.m\), not 1\.15$"),
        (dict(n="6.0", n_max=64), r"^n_max must be an integer in 1\.\.63, not 64$"),
        (dict(m="1.18"), r"^m must be a fraction-only format \(0\.m\), not 1\.18$"),
        (dict(rsqrt_addr=19), r"^rsqrt_addr must be an integer in 2\.\.16, not 19$"),
        (dict(nr="1.20"), r"^nr must have at least 2 integer bits \(y0² < 4\), not 1\.20$"),
        (dict(dot="S0.17"), r"^dot must hold exactly 1\.0 \(at least 1 integer bit\), not S0\.17$"),
        (dict(t="2.15"), r"^t must be 1\.m with m >= 2 \(a cosine in 0\.\.1, 1\.0 exact\), not 2\.15$"),
        (dict(log_addr=15), r"^log_addr must be an integer in 1\.\.14, not 15$"),
        (dict(exp_addr=0), r"^exp_addr must be an integer in 1\.\.16, not 0$"),
        (dict(out="0.16"), r"^out must hold exactly 1\.0 \(at least 1 integer bit\), not 0\.16$"),
        (dict(rounding="nearest"), r"^rounding must be one of truncate, round_half_up, "
                                   r"round_half_even, not 'nearest'$"),
        (dict(vec="S8.15"), r"^vec \(S8\.15\) is too wide: N·N scaled by its even shift "
                            r"exceeds 62 bits$"),
    ]
    for changes, message in cases:
        with pytest.raises(ValueError, match=message):
            BlinnConfig(**changes)
    assert CONFIG.q == Format(4, 30) and BlinnConfig(vec="S2.10").q == Format(6, 20)


def test_vectors_start_with_the_directed_set():
    raw = get_block("blinn").stimulus(count=40, seed=0)
    d = directed(CONFIG)
    for name in d:
        np.testing.assert_array_equal(raw[name][:len(d[name])], d[name])
    assert set(edge_n(CONFIG).tolist()) == {1, 2, 8, 64, 500, 7999, 8000}
    assert len(raw["n"]) == len(d["n"]) + 40
    assert np.any(np.all(d["normal"] == 0, axis=-1)) and np.any(np.all(d["normal"] == [1, 0, 0], axis=-1))
