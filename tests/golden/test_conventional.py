import math
from fractions import Fraction

import numpy as np
import pytest

from phongfx.config import BlinnConfig, ConventionalConfig
from phongfx.core.format import Format
from phongfx.core.registry import get_block
from phongfx.golden.conventional import conventional, reflection, unit_length
from phongfx.golden.fixed import Fixed
from phongfx.sim.stimulus import codes, rng, unit_vectors
from phongfx.sim.stimulus.blinn import edge_n
from phongfx.sim.stimulus.conventional import directed, highlights
from tests.golden.test_blinn import EXP, LOG, RSQRT

CONFIG = ConventionalConfig()
LOCAL = ConventionalConfig(local_light=True, local_viewer=True)
VEC = CONFIG.fmt("vec")

# -- error bounds derived from the defaults (see phongfx.golden.conventional) ---------
# a cosine in cos = S1.17: Blinn's relative 1/sqrt bound and m's rounding, the scaled dot
# product's half LSB (2^-18) times y1 < 2, cos's half LSB (2^-18)
COSINE = 1.0001 * (RSQRT + 2.0 ** -18 * 1.0001) + 2.0 ** -17 + 2.0 ** -18
# R·V = 2·c_L·c_V - L·V with |c| <= 1: each cosine's error twice, their product, t's half LSB
RV = 4 * COSINE + 2 * COSINE ** 2 + 2.0 ** -16
HALF = 2.0 ** -16  # half an LSB of out = 1.15
# a unit vector's component in vec = S1.15: the cosine bound with vec's half LSB (2^-16)
UNIT = COSINE - 2.0 ** -18 + 2.0 ** -16


def vec(values):
    return Fixed(codes(np.asarray(values, dtype=float), VEC), VEC)


def run(normal, light, view, n, config=CONFIG):
    normal = normal if isinstance(normal, Fixed) else vec(normal)
    count = len(normal.raw)
    light = light if isinstance(light, Fixed) else vec(np.broadcast_to(light, (count, 3)))
    view = view if isinstance(view, Fixed) else vec(np.broadcast_to(view, (count, 3)))
    n = Fixed(np.broadcast_to(np.asarray(n, dtype=np.int64), (count,)), config.n)
    out = conventional(config, normal, light, view, n)
    return out["diffuse"], out["specular"]


def phong(normal, light, view, local=False):
    """Float ``(N̂·L, R·V)`` of the codes, ``R = 2(N̂·L)N̂ - L`` built as a vector; ``L``, ``V``
    as coded (the unit takes them as unit) unless ``local``."""
    n, l, v = normal.to_float(), light.to_float(), view.to_float()
    n = n / np.linalg.norm(n, axis=-1, keepdims=True)
    if local:
        l, v = (x / np.linalg.norm(x, axis=-1, keepdims=True) for x in (l, v))
    nl = np.sum(n * l, -1)
    r = 2 * nl[:, None] * n - l
    return nl, np.sum(r * v, -1)


def within_bounds(spec, nl, rv, n):
    """``spec`` against Phong's ``clamp(R·V, 0, 1)^n`` (0 where ``N̂·L <= 0``): ``R·V`` within
    RV, ``log2`` within LOG (scaled by ``n``), ``2^f`` within EXP, then half an LSB."""
    lit = nl > COSINE  # within a cosine of 0 either side may hold
    low = np.clip(rv - RV, 0, 1) ** n * 2.0 ** (-n * LOG) * (1 - EXP) - HALF
    high = np.clip(rv + RV, 0, 1) ** n * 2.0 ** (n * LOG) * (1 + EXP) + HALF
    return np.where(lit, (spec >= low) & (spec <= high), (spec == 0) | (nl > -COSINE) & (spec <= high))


def sample(config, count, seed, n):
    """:func:`~phongfx.sim.stimulus.conventional.highlights` at shininess ``n``, as Fixed."""
    rows = highlights(config, count, rng(seed), n)
    return {k: Fixed(v, config.n if k == "n" else VEC) for k, v in rows.items()}


def test_reflection_identity_is_exact_algebra():
    # R·V = 2(N̂·L)(N̂·V) - L·V for any unit N̂ and any L, V: the form the unit computes
    g = rng(5)
    n, l, v = unit_vectors(1000, g), unit_vectors(1000, g) * 1.7, unit_vectors(1000, g)
    nl, nv, lv = (np.sum(a * b, -1) for a, b in ((n, l), (n, v), (l, v)))
    r = 2 * nl[:, None] * n - l
    np.testing.assert_allclose(np.sum(r * v, -1), 2 * nl * nv - lv, rtol=0, atol=1e-14)


def test_reflection_rounds_the_exact_difference_once():
    g = rng(6)
    cos = CONFIG.fmt("cos")
    c = [Fixed(g.integers(-cos.one, cos.one, 4000, endpoint=True), cos) for _ in range(2)]
    lv = Fixed(g.integers(-(1 << 30), 1 << 30, 4000, endpoint=True), Format(5, 30, True))
    t = reflection(CONFIG, c[0], c[1], lv)
    for a, b, e, got in zip(c[0].raw[:400], c[1].raw[:400], lv.raw[:400], t.raw[:400]):
        exact = 2 * Fraction(int(a) * int(b), 1 << 34) - Fraction(int(e), 1 << 30)
        want = min(max(math.floor(exact * (1 << 15) + Fraction(1, 2)), 0), 1 << 15)
        assert got == want
    assert t.fmt == CONFIG.fmt("t") and t.raw.max() == 1 << 15 and t.raw.min() == 0


def test_unit_length_of_local_vectors():
    g = rng(2)
    x = vec(unit_vectors(20000, g) * g.uniform(0.05, 1.7, (20000, 1)))
    got = unit_length(LOCAL, x).to_float()
    exact = x.to_float() / np.linalg.norm(x.to_float(), axis=-1, keepdims=True)
    assert np.max(np.abs(got - exact)) <= UNIT < 2.0 ** -14.7
    assert not np.any(unit_length(LOCAL, vec(np.zeros((2, 3)))).raw)  # X = 0 gives 0
    axes = unit_length(LOCAL, vec(np.concatenate([np.eye(3), -np.eye(3)]) * 0.3))
    np.testing.assert_array_equal(axes.raw, codes(np.concatenate([np.eye(3), -np.eye(3)]), VEC))


def test_diffuse_is_within_the_cosine_bound():
    s = sample(CONFIG, 20000, 1, 1)
    diffuse, _ = run(s["normal"], s["light"], s["view"], 1)
    nl, _ = phong(s["normal"], s["light"], s["view"])
    # cos's bound, then out's half LSB
    assert np.max(np.abs(diffuse.to_float() - np.clip(nl, 0, 1))) <= COSINE + HALF < 2.0 ** -14.5


@pytest.mark.parametrize("n", [1, 16, 64, 500, 8000])
def test_specular_error_against_float_phong(n):
    s = sample(CONFIG, 20000, n, n)
    _, spec = run(s["normal"], s["light"], s["view"], n)
    nl, rv = phong(s["normal"], s["light"], s["view"])
    spec = spec.to_float()
    assert np.all(within_bounds(spec, nl, rv, n))
    want = np.where(nl > 0, np.clip(rv, 0, 1) ** n, 0.0)
    levels = np.abs(spec - want) * 255
    print(f"n = {n}: max {levels.max():.3f}, mean {levels.mean():.4f} 8-bit levels")
    # Lyon's error magnification: R·V's 16-bit error costs about n·RV of the peak
    assert levels.max() <= 255 * (n * RV + 2 * HALF) and np.mean(spec > 0.5) > 0.1


@pytest.mark.parametrize("n", [16, 500])
def test_local_light_and_viewer_are_normalized(n):
    s = sample(LOCAL, 20000, 10 + n, n)
    assert np.ptp(np.linalg.norm(s["light"].to_float(), axis=-1)) > 1  # really not unit
    diffuse, spec = run(s["normal"], s["light"], s["view"], n, LOCAL)
    nl, rv = phong(s["normal"], s["light"], s["view"], local=True)
    # the unit vectors' rounding to vec adds at most UNIT per component to each dot product
    slack = 3 * UNIT * 2
    assert np.max(np.abs(diffuse.to_float() - np.clip(nl, 0, 1))) <= COSINE + HALF + slack / 2
    low = np.clip(rv - RV - slack, 0, 1) ** n * 2.0 ** (-n * LOG) * (1 - EXP) - HALF
    high = np.clip(rv + RV + slack, 0, 1) ** n * 2.0 ** (n * LOG) * (1 + EXP) + HALF
    spec = spec.to_float()
    assert np.all((spec >= low) & (spec <= high))


def test_without_local_the_input_is_taken_as_unit():
    # L of length 1/2 along N: the unit does not normalize it, so N̂·L = 1/2
    diffuse, _ = run([[0, 0, 1]], [0, 0, 0.5], [0, 0, 1], 1)
    assert diffuse.raw[0] == 1 << 14
    diffuse, spec = run([[0, 0, 1]], [0, 0, 0.5], [0, 0, 1], 1, LOCAL)
    assert diffuse.raw[0] == 1 << 15 and spec.raw[0] == 1 << 15


def test_axis_normals_give_exactly_one_and_zero():
    ns = edge_n(CONFIG)
    for axis in np.concatenate([np.eye(3), -np.eye(3)]):
        for scale in (1.0, 0.5, 2.0 ** -15):  # unit, half, the shortest nonzero N
            normal = np.tile(axis * scale, (len(ns), 1))
            diffuse, spec = run(normal, axis, axis, ns)  # N = L = V: R·V = 1 exactly
            assert np.all(diffuse.raw == 1 << 15) and np.all(spec.raw == 1 << 15)
            diffuse, spec = run(normal, axis, -axis, ns)  # V = -L = -N: R·V = -1
            assert np.all(diffuse.raw == 1 << 15) and not np.any(spec.raw)
            side = np.roll(axis, 1)
            for light, view in ((-axis, -axis), (side, -side), (side, side)):
                # behind (R·V = 1), grazing seen along the reflection (R·V = 1), grazing
                diffuse, spec = run(normal, light, view, ns)
                assert not np.any(diffuse.raw) and not np.any(spec.raw)


def test_the_light_behind_gives_no_specular_even_where_r_reaches_v():
    g = rng(8)
    n = unit_vectors(5000, g)
    light = unit_vectors(5000, g)
    light = np.where(np.sum(light * n, -1, keepdims=True) > 0, -light, light)
    view = 2 * np.sum(light * n, -1, keepdims=True) * n - light  # R·V = 1: the mirror direction
    diffuse, spec = run(n, light, view, 8)
    nl, rv = phong(vec(n), vec(light), vec(view))
    assert np.all(nl < 0) and np.min(rv) > 0.99
    assert not np.any(diffuse.raw) and not np.any(spec.raw)
    # the same rows with L in front: a bright highlight
    _, lit = run(n, -light, -view, 8)
    assert np.min(lit.to_float()) > 0.9


def test_zero_normal_gives_zero():
    diffuse, spec = run(np.zeros((7, 3)), [1, 0, 0], [1, 0, 0], edge_n(CONFIG))
    assert not np.any(diffuse.raw) and not np.any(spec.raw)
    diffuse, spec = run(np.tile([0, 0, 1.0], (2, 1)), [0, 0, 0], [0, 0, 0], [1, 8000], LOCAL)
    assert not np.any(diffuse.raw) and not np.any(spec.raw)


def test_inputs_are_validated():
    with pytest.raises(ValueError, match=r"^n must be in 1\.\.8000; 2 value\(s\) are not, "
                                         r"first 0 \(raw 0\)$"):
        run(np.eye(3), [1, 0, 0], [1, 0, 0], [0, 8001, 5])


def test_config_errors_name_the_field():
    cases = [
        (dict(cos="1.17"), r"^cos must be a signed format \(Sn\.m\), not 1\.17$"),
        (dict(cos="S0.17"), r"^cos must hold exactly 1\.0 \(at least 1 integer bit\), not S0\.17$"),
        (dict(local_light="true"), r"^local_light must be True or False, not 'true'$"),
        (dict(local_viewer=1), r"^local_viewer must be True or False, not 1$"),
        (dict(vec="1.15"), r"^vec must be a signed format \(Sn\.m\), not 1\.15$"),  # Blinn's own checks
    ]
    for changes, message in cases:
        with pytest.raises(ValueError, match=message):
            ConventionalConfig(**changes)
    # the shared fields are Blinn's, at Blinn's defaults
    blinn = BlinnConfig()
    assert all(getattr(CONFIG, f) == getattr(blinn, f) for f in blinn.as_dict())
    assert set(CONFIG.inputs) == {"normal", "light", "view", "n"}


def test_vectors_start_with_the_directed_set():
    for config, changes in ((CONFIG, {}), (LOCAL, dict(local_light=True, local_viewer=True))):
        raw = get_block("conventional", **changes).stimulus(count=40, seed=0)
        d = directed(config)
        for name in d:
            np.testing.assert_array_equal(raw[name][:len(d[name])], d[name])
        assert len(raw["n"]) == len(d["n"]) + 40
    assert len(directed(LOCAL)["n"]) == len(directed(CONFIG)["n"]) + 2 * len(edge_n(CONFIG))
    lengths = np.linalg.norm(highlights(LOCAL, 200, rng(0))["light"] * VEC.lsb, axis=-1)
    assert lengths.min() < 0.2 and lengths.max() > 1.5
