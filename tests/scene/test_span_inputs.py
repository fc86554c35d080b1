import math

import numpy as np
import pytest

from phongfx.core.registry import get_block
from phongfx.golden.spherical import rom_bound
from phongfx.golden.spherical_setup import solve_a
from phongfx.scene import span_inputs as si
from phongfx.scene.mesh import Spans, rasterize, rotation, torus

LIGHT = np.array([-0.4, 0.5, 0.77]) / np.linalg.norm([-0.4, 0.5, 0.77])


def _unit(v):
    v = np.asarray(v, dtype=np.float64)
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def hand_spans():
    """Three spans of lengths 1, 2 and 7 on two rows, normals up to ~50° apart."""
    length = np.array([1, 2, 7])
    na = _unit([[0.1, 0.2, 1.0], [0.5, -0.1, 0.8], [-0.6, 0.3, 0.7]])
    nb = _unit([[0.1, 0.2, 1.0], [0.6, 0.0, 0.7], [0.4, 0.5, 0.8]])
    return Spans(16, 4, np.array([0, 1, 1]), np.array([3, 0, 5]), length, na, nb,
                 np.arange(3), np.ones(10, dtype=bool))


@pytest.fixture(scope="module")
def frame():
    """A real rasterized frame: the 800-polygon torus, tilted so surfaces overlap."""
    return rasterize(torus(800), rotation(30), 48, 48)


def _ends(spans):
    first = np.cumsum(spans.length) - spans.length
    return first, first + spans.length - 1


def _in_format(raw, fmt):
    return bool(np.all((raw >= fmt.min_raw) & (raw <= fmt.max_raw)))


@pytest.mark.parametrize("make", [hand_spans, "frame"])
def test_euler_ends_on_p_b_and_starts_on_p_a(make, request):
    spans = make() if callable(make) else request.getfixturevalue(make)
    block = get_block("euler")
    raw = si.euler_inputs(spans, LIGHT)
    assert set(raw) == set(block.config.inputs)
    first, last = _ends(spans)
    assert np.flatnonzero(raw["init"]).tolist() == first.tolist()
    for name in ("p0", "t0", "ds"):  # junk-free: loads only on first pixels
        assert not np.any(np.delete(raw[name], first))
    p = block.golden(raw)["p"] * block.config.fmt("p").lsb
    # each of p0, t0, ds is rounded half up (at most 2^-31 off), and the end takes
    # p0 + n·t0 + n(n-1)/2·ds: the end error is at most that many half LSBs
    n = spans.length - 1
    bound = 2.0 ** -31 * (1 + n + n * (n - 1) / 2) + 1e-12
    assert np.all(np.abs(p[first] - spans.na @ LIGHT) <= 2.0 ** -31)
    assert np.all(np.abs(p[last] - spans.nb @ LIGHT) <= bound)


def test_gouraud_is_the_chord_with_one_init_per_span(frame):
    block = get_block("gouraud")
    raw = si.gouraud_inputs(frame, LIGHT)
    assert int(raw["init"].sum()) == len(frame.length)
    for name, (fmt, lanes) in block.config.inputs.items():
        assert raw[name].shape == (int(frame.length.sum()),) and _in_format(raw[name], fmt)
    p = block.golden(raw)["p"] * block.config.fmt("p").lsb
    first, last = _ends(frame)
    t = frame.pixel_t()
    span = frame.pixel_span()
    chord = (1 - t) * (frame.na @ LIGHT)[span] + t * (frame.nb @ LIGHT)[span]
    n = np.repeat(frame.length - 1, frame.length)
    assert np.all(np.abs(p - chord) <= 2.0 ** -31 * (1 + n) + 1e-12)


def _cos2_vs_cosn(n):
    """max over x of |cos²(a·x) - cos^n x|, both zero past their quarter turns (§4)."""
    x = np.linspace(-math.pi, math.pi, 200001)
    a = solve_a(n)
    fit = np.where(np.abs(a * x) <= math.pi / 2, np.cos(a * x) ** 2, 0.0)
    return float(np.max(np.abs(fit - np.maximum(np.cos(x), 0.0) ** n)))


@pytest.mark.parametrize("n", [1, 32])
def test_spherical_diffuse_and_specular_against_float_phong(frame, n):
    block = get_block("spherical")
    config = block.config
    raw = si.spherical_inputs(frame, LIGHT, n)
    assert int(raw["init"].sum()) == len(frame.length)
    for name, (fmt, lanes) in config.inputs.items():
        assert raw[name].shape == ((int(frame.length.sum()), 3) if lanes == 3 else (int(frame.length.sum()),))
        assert _in_format(raw[name], fmt)
    out = block.golden(raw)
    spec, diff = si.decode(out, config), si.decode(out, config, "diff")
    first, last = _ends(frame)
    h = si.halfway(LIGHT)
    # θ: b and s each rounded to half an LSB (π·2^-12), s added length-1 times; then the
    # ROM's cell bound; then C and the product each rounded to half an LSB of 1.11
    theta = math.pi * 2.0 ** -12 * int(frame.length.max())
    diff_bound = rom_bound(config.addr_bits, config.rom) + theta + 2.0 ** -11
    for index, normal in ((first, frame.na), (last, frame.nb)):
        assert np.all(np.abs(diff[index] - np.maximum(normal @ LIGHT, 0)[:, None]) <= diff_bound)
        # specular: cos²(aθ) stands for cos^n θ (Szirmay-Kalos equation 19)
        spec_bound = _cos2_vs_cosn(n) + solve_a(n) * (theta + rom_bound(config.addr_bits, config.rom))
        assert np.all(np.abs(spec[index] - np.maximum(normal @ h, 0) ** n) <= spec_bound + 2.0 ** -11)


def test_spherical_colour_scales_the_diffuse_channels():
    spans = hand_spans()
    raw = si.spherical_inputs(spans, LIGHT, 8, colour=(1.0, 0.5, 0.0))
    first, _ = _ends(spans)
    cd = raw["cd"][first] * get_block("spherical").config.fmt("c").lsb
    amplitude = cd[:, 0]
    assert np.all(amplitude > 0.3)
    assert np.allclose(cd[:, 1], amplitude / 2, atol=2.0 ** -11) and not np.any(cd[:, 2])


def test_schlick_is_rational_specular_of_the_renormalized_normal(frame):
    block = get_block("schlick")
    n = 32
    raw = si.schlick_inputs(frame, LIGHT, n)
    assert set(raw) == set(block.config.inputs) and np.all(raw["n"] == n)
    assert _in_format(raw["t"], block.config.fmt("t"))
    normals = _unit(frame.interpolated_normals())
    t = np.clip(normals @ si.halfway(LIGHT), 0, 1)
    spec = si.decode(block.golden(raw), block.config)
    # t is rounded by half an LSB (2^-16) and dS/dt = n/D² <= n; the divider floors (1 LSB)
    assert np.all(np.abs(spec - t / (n - n * t + t)) <= n * 2.0 ** -16 + 2.0 ** -15)


def test_blinn_is_exact_phong_to_sixteen_bits(frame):
    block = get_block("blinn")
    raw = si.blinn_inputs(frame, LIGHT, 8)
    assert set(raw) == set(block.config.inputs) and np.all(raw["n"] == 8)
    assert _in_format(raw["normal"], block.config.fmt("vec"))
    out = block.golden(raw)
    normals = _unit(frame.interpolated_normals())
    diffuse = si.decode(out, block.config, "diff")
    specular = si.decode(out, block.config)
    # S1.15 inputs (half an LSB per component), a 16-bit unit: a few LSB of 1.15, ×n for t^n
    assert np.max(np.abs(diffuse - np.maximum(normals @ LIGHT, 0))) < 8 * 2.0 ** -15
    assert np.max(np.abs(specular - np.maximum(normals @ si.halfway(LIGHT), 0) ** 8)) < 8 * 8 * 2.0 ** -15


def test_conventional_is_exact_phong_to_sixteen_bits(frame):
    block = get_block("conventional")
    raw = si.conventional_inputs(frame, LIGHT, 8)
    assert list(raw) == ["normal", "light", "view", "n"] and np.all(raw["n"] == 8)
    assert _in_format(raw["normal"], block.config.fmt("vec"))
    assert np.all(raw["view"] == [0, 0, 1 << 15])  # V = (0, 0, 1): 1.0 exactly in S1.15
    out = block.golden(raw)
    normals = _unit(frame.interpolated_normals())
    diffuse = si.decode(out, block.config, "diff")
    specular = si.decode(out, block.config)
    nl = normals @ LIGHT
    r = 2 * nl[:, None] * normals - LIGHT
    phong = np.where(nl > 0, np.maximum(r @ si.VIEWER, 0) ** 8, 0)
    # as Blinn's, with R·V taking two cosines: twice the error, ×n for t^n
    assert np.max(np.abs(diffuse - np.maximum(nl, 0))) < 8 * 2.0 ** -15
    assert np.max(np.abs(specular - phong)) < 2 * 8 * 8 * 2.0 ** -15
    assert np.max(specular) > 0.95  # the frame has a highlight
    codes = si.conventional_codes(normals[:3], np.tile(LIGHT, (3, 1)), np.tile(si.VIEWER, (3, 1)),
                                  [1, 2, 3], block.config)
    np.testing.assert_array_equal(codes["light"], raw["light"][:3])
    assert codes["n"].tolist() == [1, 2, 3]


def test_halfway_is_blinns_bisector():
    assert np.allclose(si.halfway([0, 0, 5]), [0, 0, 1])
    assert np.allclose(si.halfway([1, 0, 0]), np.array([1, 0, 1]) / math.sqrt(2))


def test_decode_clamps_negative_intensity():
    config = get_block("euler").config
    p = np.array([-(1 << 29), 1 << 29])
    assert si.decode({"p": p}, config).tolist() == [0.0, 0.5]


def test_bad_arguments_are_refused():
    spans = hand_spans()
    with pytest.raises(ValueError, match=r"^light must be a finite nonzero 3-vector, not \[0, 0, 0\]$"):
        si.euler_inputs(spans, [0, 0, 0])
    with pytest.raises(ValueError, match=r"^light must not point straight away from the viewer"):
        si.halfway([0, 0, -1])
    with pytest.raises(ValueError, match=r"^n must be an integer in 1\.\.8000, not 0$"):
        si.schlick_inputs(spans, LIGHT, 0)
    with pytest.raises(ValueError, match=r"^n must be a positive number, not -1$"):
        si.spherical_inputs(spans, LIGHT, -1)
    with pytest.raises(ValueError, match=r"^n must be an integer in 1\.\.8000, not 8001$"):
        si.conventional_inputs(spans, LIGHT, 8001)
    with pytest.raises(ValueError, match=r"^unit must be one of spherical, euler, gouraud, schlick, blinn, "
                                         r"conventional, not 'x'$"):
        si.inputs("x", spans, LIGHT)
    with pytest.raises(ValueError, match=r"^part must be one of diff, spec, not 'x'$"):
        si.decode({}, get_block("euler").config, "x")
    with pytest.raises(ValueError, match=r"^part must be one of spec, not 'diff'$"):
        si.decode({}, get_block("schlick").config, "diff")
    empty = Spans(4, 4, *(np.zeros(0, dtype=np.int64),) * 3, np.zeros((0, 3)), np.zeros((0, 3)),
                  np.zeros(0, dtype=np.int64), np.zeros(0, dtype=bool))
    with pytest.raises(ValueError, match=r"^spans must hold at least one span, not 0$"):
        si.gouraud_inputs(empty, LIGHT)
