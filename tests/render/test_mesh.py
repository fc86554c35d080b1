import os

import numpy as np
import pytest
from PIL import Image

from phongfx.golden import spherical_setup
from phongfx.render import mesh as mesh_render
from phongfx.render.figure import MARGIN, scale_for
from phongfx.render.mesh import LIGHT, SHADED, error_8bit, figure14, figure15, run, shade, write_png
from phongfx.scene import mesh as meshes
from phongfx.scene.span_inputs import halfway

H = halfway(LIGHT)
L = np.asarray(LIGHT) / np.linalg.norm(LIGHT)


@pytest.fixture(scope="module")
def torus_spans():
    return meshes.rasterize(meshes.torus(288), meshes.rotation(37), 128, 128)


@pytest.fixture(scope="module")
def sphere_spans():
    return meshes.rasterize(meshes.uv_sphere(8, 16), meshes.rotation(20), 72, 72)


@pytest.mark.parametrize("method", SHADED)
def test_each_method_writes_a_frame_on_black(method, tmp_path):
    summary = run(method, mesh="torus", polygons=288, width=48, height=40, frame=37, out_dir=str(tmp_path))
    # the frame inside its figure: 8 PNG pixels a frame pixel, MARGIN from the bottom left
    scale = scale_for((40, 48))
    figure = np.asarray(Image.open(summary["path"]).convert("L"))
    picture = figure[-MARGIN - 40 * scale:-MARGIN, MARGIN:MARGIN + 48 * scale][::scale, ::scale]
    assert picture.shape == (40, 48) and picture.dtype == np.uint8
    assert os.path.dirname(summary["path"]) == str(tmp_path) and summary["path"].endswith(".png")
    # every visible pixel has at least the ambient 0.1 (26 levels); the rest is background 0
    assert (picture > 0).sum() == summary["pixels"] > 300
    assert picture[0, 0] == 0 and picture[-1, -1] == 0
    errors = summary["error_8bit"]["total"]
    assert 0 <= errors["mean"] <= errors["max"] <= 255
    assert (errors["max"] == 0) == (method == "phong")


def test_phong_is_the_normalized_interpolated_normal(torus_spans):
    normals = torus_spans.interpolated_normals()
    normals /= np.linalg.norm(normals, axis=1, keepdims=True)
    diffuse, specular = shade(torus_spans, "phong", n=20)
    np.testing.assert_allclose(diffuse, np.maximum(normals @ L, 0), atol=1e-12)
    np.testing.assert_allclose(specular, np.maximum(normals @ H, 0) ** 20, atol=1e-12)


def _slerp(spans):
    """Independent spherical interpolation of N from N_a to N_b, uniform in angle."""
    span, t = spans.pixel_span(), spans.pixel_t()[:, None]
    na, nb = spans.na[span], spans.nb[span]
    omega = np.arccos(np.clip(np.einsum("ij,ij->i", na, nb), -1, 1))[:, None]
    sin = np.sin(omega)
    safe = np.where(sin > 1e-9, sin, 1.0)
    mixed = (np.sin((1 - t) * omega) * na + np.sin(t * omega) * nb) / safe
    return np.where(sin > 1e-9, mixed, na + t * (nb - na))


def test_cosn_is_the_exact_power_of_the_slerped_normal(torus_spans):
    normals = _slerp(torus_spans)
    diffuse, specular = shade(torus_spans, "cosn", n=20)
    np.testing.assert_allclose(diffuse, np.maximum(normals @ L, 0), atol=1e-9)
    np.testing.assert_allclose(specular, np.maximum(normals @ H, 0) ** 20, atol=1e-9)


def test_vectorized_angles_match_the_scalar_setup(torus_spans):
    big_a, phi, gamma = mesh_render.span_angles(torus_spans, H)
    for i in np.random.default_rng(4).choice(len(big_a), 20, replace=False):
        want = spherical_setup.span_setup(torus_spans.na[i], torus_spans.nb[i], H, H, 20,
                                          int(torus_spans.length[i]))
        assert (big_a[i], phi[i], gamma[i]) == pytest.approx((want["A"], want["phi"], want["gamma"]),
                                                             abs=1e-12)


def test_end_pixels_agree_where_the_method_is_exact_there(torus_spans):
    step, span = torus_spans.pixel_step(), torus_spans.pixel_span()
    ends = (step == 0) | (step == torus_spans.length[span] - 1)
    phong = shade(torus_spans, "phong")
    for method in ("gouraud-float", "corrected-euler", "cosn"):  # all interpolate from exact ends
        for got, want in zip(shade(torus_spans, method), phong):
            np.testing.assert_allclose(got[ends], want[ends], atol=1e-9)
    # uncorrected Euler misses the far end (Hast Figure 2)
    euler = shade(torus_spans, "euler-float")[0]
    last = (step == torus_spans.length[span] - 1) & (torus_spans.length[span] > 4)
    assert np.max(np.abs(euler[last] - phong[0][last])) > 1e-3


def test_fixed_point_units_track_their_float_curves(torus_spans):
    euler = shade(torus_spans, "euler")
    for got, want in zip(euler, shade(torus_spans, "corrected-euler")):
        assert error_8bit(got, want, torus_spans.visible)["max"] < 0.01  # S1.30 registers
    span, t = torus_spans.pixel_span(), torus_spans.pixel_t()
    chord = [(1 - t) * (torus_spans.na @ v)[span] + t * (torus_spans.nb @ v)[span] for v in (L, H)]
    diffuse, specular = shade(torus_spans, "gouraud")
    np.testing.assert_allclose(diffuse, np.maximum(chord[0], 0), atol=1e-7)
    np.testing.assert_allclose(specular, np.maximum(chord[1], 0) ** 20, atol=1e-6)


def test_the_blinn_baseline_is_within_a_level_of_phong(torus_spans):
    phong = shade(torus_spans, "phong")
    got = shade(torus_spans, "blinn")  # n = 20: 16-bit t, ×n in t^n
    errors = [error_8bit(a, b, torus_spans.visible) for a, b in zip(got, phong)]
    assert errors[0]["max"] < 0.1 and errors[1]["max"] < 1


def test_the_conventional_unit_is_phongs_reflection_lobe(torus_spans):
    phong = shade(torus_spans, "phong")  # (N·H)^n, Hast's form
    got = shade(torus_spans, "conventional")  # n = 20, Phong's own (R·V)^n
    normal = torus_spans.interpolated_normals()
    normal = normal / np.linalg.norm(normal, axis=-1, keepdims=True)
    nl = normal @ L
    rv = (2 * nl[:, None] * normal - L) @ np.array([0.0, 0, 1])
    want = np.where(nl > 0, np.maximum(rv, 0) ** 20, 0)
    visible = torus_spans.visible
    assert error_8bit(got[0], phong[0], visible)["max"] < 0.1  # the same N·L
    assert error_8bit(got[1], want, visible)["max"] < 1
    # the reflection lobe is narrower than (N·H)^n: about (N·H)^(4n)
    assert error_8bit(got[1], phong[1], visible)["max"] > 20
    assert error_8bit(got[1], np.maximum(normal @ H, 0) ** 80, visible)["max"] < 20


def test_corrected_euler_beats_euler_and_gouraud(torus_spans):
    phong = shade(torus_spans, "phong")[0]
    mean = {m: error_8bit(shade(torus_spans, m)[0], phong, torus_spans.visible)["mean"]
            for m in ("gouraud-float", "euler-float", "corrected-euler")}
    # Hast Table 2, 288 polygons: Gouraud 1.08, Euler 0.75, corrected Euler 0.081
    assert mean["corrected-euler"] < mean["euler-float"] < mean["gouraud-float"]
    assert mean["corrected-euler"] < mean["gouraud-float"] / 5


def test_spherical_rom_error_falls_with_bits(sphere_spans):
    cosn = shade(sphere_spans, "cosn")
    errors = [error_8bit(shade(sphere_spans, "spherical", addr_bits=b, rom_bits=b)[1], cosn[1],
                         sphere_spans.visible) for b in (4, 6)]
    assert errors[1]["mean"] < errors[0]["mean"] and errors[1]["max"] < errors[0]["max"]


def test_dark_spans_stay_dark_through_the_wrapping_angle_register(sphere_spans):
    cos2 = shade(sphere_spans, "cos2")[1]
    spherical = shade(sphere_spans, "spherical", addr_bits=10, rom_bits=10)[1]
    # away from H the float cos²(a·x) is 0; a·x past 3π/2 would wrap into the window
    dark = cos2 == 0
    assert dark.sum() > 1000
    assert spherical[dark].max() < 0.02


def test_write_png_is_atomic(tmp_path, monkeypatch):
    path = str(tmp_path / "frame.png")
    write_png(path, np.full((4, 5), 0.5))
    before = (tmp_path / "frame.png").read_bytes()

    def broken(self, fp, *args, **kwargs):
        with open(fp, "wb") as handle:
            handle.write(b"\x89PNG partial")
        raise OSError("disk full")

    monkeypatch.setattr(Image.Image, "save", broken)
    with pytest.raises(OSError, match=r"^disk full$"):
        write_png(path, np.zeros((4, 5)))
    assert (tmp_path / "frame.png").read_bytes() == before
    assert os.listdir(tmp_path) == ["frame.png"]


def test_a_frame_is_written_titled_with_its_error_against_phong(tmp_path):
    """The README promised a PNG and its error against Phong; the PNG was bare 1:1 pixels."""
    summary = run("spherical", polygons=288, width=48, height=48, out_dir=str(tmp_path))
    assert summary["kind"] == "fixed point"
    frame, error = Image.open(summary["path"]), Image.open(summary["error_path"])
    assert summary["error_path"] == str(tmp_path / "torus288-spherical-a6d6-n20-f0_error.png")
    assert min(frame.size) >= 384  # 48 × 48 enlarged 8 times, plus the title
    assert error.size[0] > frame.size[0] + 60  # the colour bar
    bar = np.asarray(error.convert("RGB"))[:, frame.size[0]:].reshape(-1, 3)
    assert len(np.unique(bar, axis=0)) > 50


def test_former_unit_names_still_work_with_a_warning(torus_spans):
    with pytest.warns(DeprecationWarning, match=r"'gouraud-unit' is now called 'gouraud'"):
        old = shade(torus_spans, "gouraud-unit")
    for got, want in zip(old, shade(torus_spans, "gouraud")):
        np.testing.assert_array_equal(got, want)


def test_figures_write_grids_and_report(tmp_path):
    fig15 = figure15(str(tmp_path), size=64)
    assert np.asarray(Image.open(fig15["path"])).shape == (2 * 64 + 4, 3 * 64 + 8)
    err = fig15["errors"]
    assert err["6-bit"]["vs_cosn"]["specular"]["mean"] < err["4-bit"]["vs_cosn"]["specular"]["mean"]
    fig14 = figure14(str(tmp_path), size=48, stacks=12, slices=24)
    assert np.asarray(Image.open(fig14["path"])).shape == (2 * 48 + 4, 3 * 48 + 8)
    diff = fig14["difference"]
    assert [diff[n]["a"] for n in ("5", "10", "20")] == sorted(diff[n]["a"] for n in ("5", "10", "20"))
    assert all(0 < diff[n]["specular"]["max"] < 64 for n in diff)


@pytest.mark.parametrize("call, message", [
    (lambda: run("x"), r"^method must be one of phong, gouraud-float, euler-float, corrected-euler, cosn, "
                       r"cos2, spherical, euler, gouraud, blinn, conventional, not 'x'$"),
    (lambda: shade(None, "halfway"), r"^method must be one of .*, not 'halfway'$"),
    (lambda: run("phong", mesh="cube"), r"^mesh must be one of torus, sphere, not 'cube'$"),
    (lambda: run("phong", n=0), r"^n must be a positive number, not 0$"),
    (lambda: run("phong", polygons=300), r"^polygons must be 2·k² for an integer k >= 3 .*, not 300$"),
])
def test_bad_arguments_raise(call, message):
    with pytest.raises(ValueError, match=message):
        call()
