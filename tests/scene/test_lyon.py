import numpy as np
import pytest

from phongfx.scene.lyon import Scene, pixels


def test_exact_normals_are_unit_and_cover_the_spheres():
    scene = Scene(radius=16)
    px = pixels(scene)
    np.testing.assert_allclose(np.linalg.norm(px.normal, axis=-1), 1.0, atol=1e-12)
    assert np.all(px.a == 0) and np.array_equal(px.n0, px.normal) and np.array_equal(px.n1, px.normal)
    # the first sphere is whole (nothing hides it): about pi r^2 pixels
    first = np.count_nonzero(px.sphere == 0)
    assert abs(first - np.pi * 16 ** 2) < 2 * np.pi * 16
    assert set(np.unique(px.n)) == {1, 4, 16, 64, 256}
    assert px.row.max() < scene.height and px.col.max() < scene.width


def test_spans_start_at_zero_and_end_at_one():
    px = pixels(Scene(radius=16, span=4))
    assert px.a.min() == 0.0 and px.a.max() == 1.0
    # a pixel with a = 0 has its own exact normal as span start
    start = px.a == 0
    np.testing.assert_allclose(px.n0[start], px.normal[start], atol=1e-12)
    end = px.a == 1
    np.testing.assert_allclose(px.n1[end], px.normal[end], atol=1e-12)
    # the interpolated normal is a convex combination: never longer than 1
    lerp = (1 - px.a[:, None]) * px.n0 + px.a[:, None] * px.n1
    assert np.linalg.norm(lerp, axis=-1).max() <= 1 + 1e-12


@pytest.mark.parametrize("field, value, message", [
    ("radius", 2, r"^radius must be an integer in 4\.\.4096, not 2$"),
    ("span", -1, r"^span must be an integer in 0\.\.2048 \(0: exact normals\), not -1$"),
    ("shininess", (0,), r"^shininess must be positive integers, not \(0,\)$"),
])
def test_bad_scene_is_refused(field, value, message):
    with pytest.raises(ValueError, match=message):
        Scene(**{field: value})
