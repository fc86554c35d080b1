"""The spherical unit's certificate: sound on the scenes' frames, on random poses and on spans
drawn to be hard (through the highlight, as wide and as long as the domain allows), with teeth."""

import math
from dataclasses import replace

import numpy as np
import pytest

from phongfx.certify import certify
from phongfx.certify.bound import shader_config
from phongfx.certify.lobe import cell_errors, diffuse_rom, lobe_range, rom_table, psi_max, wrap_error
from phongfx.certify.span import max_pixels, slerp_gap
from phongfx.explore.compile.measure import SceneEval
from phongfx.explore.compile.points import pose_frames
from phongfx.golden.spherical_setup import solve_a
from phongfx.scene.domain import domain
from phongfx.scene.geometry import FrameGeometry, frames
from phongfx.scene.mesh import Spans, unit
from phongfx.scene.file import load_scene, parse_scene
from phongfx.scene.span_inputs import VIEWER, halfway

#: The widest point of the compiler's spherical search on torus (its manifest's "widest").
WIDEST = {"addr_bits": 16, "coef": 16, "rom_bits": 16, "theta_frac": 20}


def _scene(name):
    spec = load_scene(f"scenes/{name}.toml")
    return spec, domain(spec)


def _measured(spec, shader, params, geometries=None):
    """Largest ``|out - (2^bits - 1)·I_ref|`` of the whole shader over the frames (or
    ``geometries``), as the compiler measures it."""
    scene = SceneEval(spec, geometries)
    scale = (1 << spec.output.bits) - 1
    worst = 0.0
    for index in range(len(scene.renders)):
        codes, ref = scene.render("spherical", shader, params, index)[:2]
        worst = max(worst, float(np.max(np.abs(codes - ref * scale), initial=0.0)))
    return worst


def _hard_spans(spec, dom, count, seed):
    """A frame of ``count`` spans of the domain drawn to be hard: each starts at a random
    front normal, ends up to the domain's span angle away (half of them on the great circle
    toward the first light's ``H``, through the highlight), and holds 1 to the most pixels a
    span can (:func:`~phongfx.certify.span.max_pixels`)."""
    rng = np.random.default_rng(seed)
    gamma = np.radians(dom.max_span_angle_deg) * np.sqrt(rng.uniform(0, 1, count))
    # start normals within 50° of the viewer: every normal of the span stays in front of it
    na = unit(rng.normal(size=(count, 3)) * [1, 1, 0] + [0, 0, 1.2])
    h = halfway(np.asarray(dom.lights[0][1]))
    toward = rng.uniform(size=count) < 0.5
    side = np.where(toward[:, None], h - (na @ h)[:, None] * na, rng.normal(size=(count, 3)))
    side = unit(side - (side * na).sum(-1, keepdims=True) * na)
    nb = np.cos(gamma)[:, None] * na + np.sin(gamma)[:, None] * side
    length = rng.integers(1, max_pixels(spec, dom) + 1, count)
    length[: count // 4] = max_pixels(spec, dom)
    spans = Spans(spec.output.width, spec.output.height, np.zeros(count, np.int64), np.zeros(count, np.int64),
                  length, na, nb, np.zeros(count, np.int64), np.ones(int(length.sum()), bool))
    span, t = spans.pixel_span(), spans.pixel_t()
    normal = unit(spans.interpolated_normals())
    template = frames(spec)[0]
    p = len(span)
    lights = np.stack([np.broadcast_to(np.asarray(v, dtype=np.float64), (p, 3)) for _, v, _ in dom.lights])
    view = np.broadcast_to(VIEWER, (p, 3))

    def one(field):
        return np.full(p, getattr(template, field)[0]) if getattr(template, field).ndim == 1 else \
            np.broadcast_to(getattr(template, field)[0], (p,) + getattr(template, field).shape[1:])

    return FrameGeometry(spec.output.width, spec.output.height, np.zeros(p, np.int64), np.arange(p), span, t,
                         na[span], nb[span], normal, np.zeros((p, 3)), lights, lights, lights, view, view, view,
                         template.rgb, one("n"), one("kd"), one("ks"), one("ka"), one("colour"), one("material"),
                         spans, 0, spec.output.bits)


def test_the_lobe_tables_hold_the_float_form():
    """lobe_range and rom_table against the float form and the ROM at random (ψ, x)."""
    rng = np.random.default_rng(3)
    n_fed = 64.0
    a = solve_a(n_fed)
    psi = rng.uniform(0, np.pi / 2, 200_000)
    x = psi * rng.uniform(0, 1, len(psi))
    big_a = np.cos(psi) / np.cos(x)
    u = big_a ** n_fed * np.where(a * x <= np.pi / 2, np.cos(np.minimum(a * x, np.pi / 2)) ** 2, 0.0)
    h = (np.cos(psi), np.cos(psi))
    lo, hi = lobe_range(n_fed, h)
    assert np.all(lo <= u) and np.all(u <= hi)
    assert np.max(hi - lo) < 0.08  # Szirmay-Kalos's fit: spans through H and across it differ this much
    delta = 0.004
    table, top = rom_table(6, "0.6", n_fed, delta)
    lo_c, hi_c, err = cell_errors(6, "0.6", "cos2", delta)
    theta_hw = np.clip(a * x + rng.uniform(-delta, delta, len(x)), 0, None)
    cell = np.clip(np.searchsorted(lo_c, theta_hw, side="right") - 1, 0, len(err) - 1)
    word = np.floor(np.cos((lo_c[cell] + hi_c[cell]) / 2) ** 2 * 64 + 0.5) / 64
    word = np.where((lo_c[cell] + hi_c[cell]) / 2 <= np.pi / 2, np.minimum(word, 63 / 64), 0.0)
    g = np.maximum(np.cos(a * x), 0.0) ** 2 * (a * x <= 1.5 * np.pi)
    assert np.all(big_a ** n_fed * np.abs(word - g) <= psi_max(table, h) + 1e-12)
    assert top == pytest.approx(math.pi / 64 + delta, abs=1 / 64)


def test_the_diffuse_rom_and_wrap_bounds():
    delta = 0.01
    inside = diffuse_rom(6, "0.6", delta, np.array([0.95, 0.5, -0.1]))
    assert inside[0] < inside[1] < inside[2] <= math.pi / 64 + delta + 1 / 64
    assert wrap_error(64.0, 30.0, delta) == (0.0, -math.inf)  # a·Γ < π: the register cannot wrap
    bound, cut = wrap_error(64.0, 60.0, delta)
    assert 0 < bound <= 1 and 0 < cut < 1


def test_the_slerp_gap_grows_with_the_span_angle():
    gaps = [slerp_gap(d) for d in (0.0, 10.0, 33.2, 90.0)]
    assert gaps[0] < 1e-9 < gaps[1] < gaps[2] < gaps[3] and slerp_gap(180.0) == math.inf
    gamma = math.radians(33.2)
    t = np.linspace(0, 1, 10001)
    exact = np.abs(np.arctan2(t * math.sin(gamma), 1 - t + t * math.cos(gamma)) - t * gamma).max()
    assert exact <= gaps[2] < exact * 1.01


@pytest.mark.parametrize("name, params", [("torus", {}), ("torus", WIDEST), ("two-lights", WIDEST)])
def test_the_bound_holds_on_frames_poses_and_hard_spans(name, params):
    spec, dom = _scene(name)
    shader = shader_config("spherical", params, spec)
    got = certify("spherical", params, spec, dom, shader=shader, max_boxes=100_000)
    poses = [g for _, g in pose_frames(spec, dom, 20_000, 5)]
    measured = max(_measured(spec, shader, params), _measured(spec, shader, params, poses),
                   _measured(spec, shader, params, [_hard_spans(spec, dom, 4000, 7)]))
    assert got.bound_levels is not None and measured <= got.bound_levels < 2.5 * measured
    assert got.parts["max_span_pixels"] == max_pixels(spec, dom) and got.parts["slerp_gap_rad"] > 0


def _worse(shader, drop):
    """Every copy's angle register ``drop`` fraction bits shorter: the hardware made worse, its
    ports toward the blend unchanged."""
    units = tuple(u.replace(theta=f"S0.{u.fmt('theta').frac_bits - drop}") for u in shader.units)
    return replace(shader, units=units)


def test_a_worse_quantize_breaks_the_old_bound_and_raises_the_new_one():
    spec, dom = _scene("torus")
    params = {"addr_bits": 6, "rom_bits": 10, "theta_frac": 14}
    shader = shader_config("spherical", params, spec)
    worse = _worse(shader, 8)
    before = certify("spherical", params, spec, dom, shader=shader, max_boxes=50_000).bound_levels
    hard = [_hard_spans(spec, dom, 4000, 9)]
    measured = max(_measured(spec, worse, params, hard), _measured(spec, worse, params))
    after = certify("spherical", params, spec, dom, shader=worse, max_boxes=50_000).bound_levels
    assert before < measured <= after


def test_the_viewer_must_be_along_z():
    spec, dom = _scene("torus")
    moved = replace(dom, camera=("infinity", (0.0, 0.6, 0.8)))
    got = certify("spherical", {}, spec, moved)
    assert not got.certified and got.why == "the spherical unit's setup takes the viewer along +z"


def test_a_wrapping_register_is_bounded():
    """At n = 40 (fed n' = 160, a = 7.7) a span of the torus that meets the highlight lobe can
    run past 3π/2 and read lit cells again: spans drawn through the highlight show it, far over
    the unit's own error, and the bound counts it."""
    spec = parse_scene(open("scenes/torus.toml").read().replace("n = 16", "n = 40"))
    dom = domain(spec)
    params = {"addr_bits": 12, "rom_bits": 12, "theta_frac": 16}
    shader = shader_config("spherical", params, spec)
    got = certify("spherical", params, spec, dom, shader=shader, max_boxes=50_000)
    hard = _measured(spec, shader, params, [_hard_spans(spec, dom, 20_000, 13)])
    assert 50 < hard <= got.bound_levels
    assert _measured(spec, shader, params) < 20  # the frames never show it


@pytest.mark.slow
@pytest.mark.parametrize("n", [1, 4, 16, 40])
@pytest.mark.parametrize("params", [{}, {"addr_bits": 8, "rom_bits": 8, "theta_frac": 12}, WIDEST])
def test_the_bound_holds_on_many_hard_spans(n, params):
    spec = parse_scene(open("scenes/torus.toml").read().replace("n = 16", f"n = {n}"))
    dom = domain(spec)
    shader = shader_config("spherical", params, spec)
    got = certify("spherical", params, spec, dom, shader=shader)
    poses = [g for _, g in pose_frames(spec, dom, 100_000, 2)]
    measured = max(_measured(spec, shader, params, poses),
                   _measured(spec, shader, params, [_hard_spans(spec, dom, 100_000, 17)]))
    assert measured <= got.bound_levels


def test_against_its_own_float_form_it_certifies():
    """Against the unit's own float form (``against = "self"``) only the hardware's rounding is
    left: at 12 address bits and 16 angle bits the bound certifies 1 level, and holds."""
    spec = parse_scene(open("scenes/torus.toml").read().replace('against = "phong"', 'against = "self"'))
    dom = domain(spec)
    params = {"addr_bits": 12, "rom_bits": 12, "theta_frac": 16}
    shader = shader_config("spherical", params, spec)
    got = certify("spherical", params, spec, dom, shader=shader, max_boxes=50_000)
    measured = max(_measured(spec, shader, params), _measured(spec, shader, params, [_hard_spans(spec, dom, 20_000, 13)]))
    assert 0.8 < measured <= got.bound_levels < 1.5 and got.certified
