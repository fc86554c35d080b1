"""What a scene makes a datapath do: the analysis decisions."""

from types import SimpleNamespace

import numpy as np
import pytest

from phongfx.explore.compile.analysis import analyse, highlight_in_span, shortest_normal, span_ends_angle
from phongfx.scene.file import parse_scene
from phongfx.scene.geometry import frames


def _spec(lights=({"direction": [1, 2, 2]},), camera=None, n=16, size=32, **extra):
    data = {"lights": list(lights), "output": {"width": size, "height": size},
            "materials": {"a": {"kd": 0.6, "ks": 0.4, "n": n}},
            "objects": [{"type": "torus", "material": "a", "polygons": 72}], **extra}
    if camera:
        data["camera"] = camera
    return parse_scene(data, name="t")


def _analyse(spec):
    return analyse(spec, frames(spec))


def test_directional_light_and_viewer_at_infinity_vary_nothing_but_n():
    a = _analyse(_spec())
    assert (a.local_lights, a.local_viewer, a.lights) == (False, False, 1)


def test_point_light_and_local_camera_vary_l_and_v():
    a = _analyse(_spec(lights=[{"position": [2, 2, 3]}, {"direction": [0, 0, 1]}],
                       camera={"position": [0, 0, 4]}))
    assert (a.local_lights, a.local_viewer, a.lights) == (True, True, 2)


def test_a_single_n_against_a_range():
    single = _analyse(_spec(n=16))
    assert (single.single_n, single.n_lo, single.n_hi, single.n_values) == (True, 16, 16, (16,))
    ranged = _analyse(_spec(n=[8, 40]))
    assert (ranged.single_n, ranged.n_lo, ranged.n_hi) == (False, 8, 40)


def test_span_angle_and_shortest_normal_of_a_torus_frame():
    spec = _spec()
    (g,) = frames(spec)
    a = analyse(spec, [g])
    # recomputed here per pixel from the span ends
    cos = np.sum(g.n0 * g.n1, -1) / np.linalg.norm(g.n0, axis=-1) / np.linalg.norm(g.n1, axis=-1)
    assert a.max_span_angle_deg == pytest.approx(np.degrees(np.arccos(cos.min())))
    assert 0 < a.max_span_angle_deg < 90
    lengths = np.linalg.norm((1 - g.a[:, None]) * g.n0 + g.a[:, None] * g.n1, axis=-1)
    assert a.min_normal_length == pytest.approx(lengths.min()) and a.min_normal_length < 1
    # a shorter |N'| is where g1 falls behind g2 (Lyon's "Approximate Normalization")
    assert 0 < a.g2_error < a.g1_error


def _frame(n0, n1, a, span, n=64.0, light=(0.0, 0.0, 1.0)):
    count = len(a)
    n0, n1, a = np.asarray(n0, float), np.asarray(n1, float), np.asarray(a, float)
    lerp = (1 - a[:, None]) * n0 + a[:, None] * n1
    return SimpleNamespace(n0=n0, n1=n1, a=a, interpolated=lerp,
                           normal=lerp / np.linalg.norm(lerp, axis=1, keepdims=True),
                           span=np.asarray(span), n=np.full(count, n),
                           viewer=np.broadcast_to([0.0, 0, 1], (count, 3)),
                           light=np.broadcast_to(light, (1, count, 3)))


def _sweep(start, end, count):
    """``count`` pixels of a span whose normals tilt from ``start`` to ``end`` degrees about y."""
    t = np.radians([start, end])
    ends = [np.array([np.sin(x), 0, np.cos(x)]) for x in t]
    return [ends[0]] * count, [ends[1]] * count, np.linspace(0, 1, count)


def test_a_highlight_inside_a_span_on_a_hand_made_frame():
    # light and viewer along z: the peak is where N = z.  Span 0 crosses it (inside), span 1
    # ends at it (on the end), span 2 crosses it with n so high that a pixel misses it by
    # more than half a level (below the threshold).
    spans = [_sweep(-20, 20, 5), _sweep(-20, 0, 5), _sweep(-40, 40, 4)]
    n0, n1, a = (np.concatenate([s[i] for s in spans]) for i in range(3))
    frame = _frame(n0, n1, a, np.repeat([0, 1, 2], [5, 5, 4]), n=np.repeat([64.0, 64, 8000], [5, 5, 4]))
    assert highlight_in_span(frame, 255) == (1, 3)
    assert span_ends_angle(frame) == pytest.approx(80)
    # shortest at a = 1/3 (and 2/3) of the 80° span: |(2/3)·N0 + (1/3)·N1|
    assert shortest_normal(frame) == pytest.approx(np.sqrt(5 / 9 + 4 / 9 * np.cos(np.radians(80))))
