"""Domain points: poses of each pose set, faces by area, caps, span ends."""

import dataclasses
import os

import numpy as np
import pytest

from phongfx.scene.domain import domain
from phongfx.scene.file import load_scene
from phongfx.scene.geometry import rotation
from phongfx.scene.sampling import cap, face_table, random_poses, random_rotations, span_end

SCENES = os.path.join(os.path.dirname(__file__), "..", "..", "scenes")
TOL = 1e-9


def _scene(name):
    return load_scene(os.path.join(SCENES, f"{name}.toml"))


def test_sampled_span_ends_stay_in_the_ball_and_within_the_span_length():
    d = domain(_scene("local-mesh"))
    rng = np.random.default_rng(2)
    x0 = np.asarray(d.ball[0]) + rng.uniform(-1, 1, (5000, 3)) * d.ball[1] / 3 ** 0.5
    x1 = span_end(d, x0, rng)
    assert np.max(np.linalg.norm(x1, axis=-1)) <= d.ball[1] * (1 + TOL)
    assert np.max(np.linalg.norm(x1 - x0, axis=-1)) <= d.max_span_length * (1 + TOL)
    assert np.max(np.abs(x1[:, 1] - x0[:, 1])) == 0.0  # spans are horizontal: no eye-space y


def test_faces_are_drawn_by_area():
    areas = np.array([1.0, 2.0, 3.0, 4.0, 0.5])
    table = face_table(np.zeros((3, 3)), np.zeros((3, 3)), np.zeros((5, 3), dtype=np.int64), np.zeros((5, 3)), areas)
    drawn = np.bincount(table.draw(400000, np.random.default_rng(3)), minlength=5) / 400000
    assert np.allclose(drawn, areas / areas.sum(), atol=0.004)


@pytest.mark.parametrize("pose", ["motion", "any", "still"])
def test_poses(pose):
    d = dataclasses.replace(domain(_scene("torus")), pose=pose, wobble_degrees=10.0, degrees=(0.0, 90.0),
                            still_degrees=(0.0,))
    q = random_poses(d, 20000, np.random.default_rng(1))
    assert np.allclose(np.linalg.norm(q, axis=-1), 1.0)
    matrices = random_rotations(d, 20000, np.random.default_rng(1))  # the same poses as matrices
    assert np.allclose(matrices @ matrices.transpose(0, 2, 1), np.eye(3)) and np.allclose(np.linalg.det(matrices), 1)
    turned = matrices @ np.asarray(d.axis)
    angle = np.degrees(2 * np.arccos(np.clip(np.abs(q[:, 0]), 0, 1)))
    if pose == "motion":  # the axis stays put and the angle covers [0°, 90°], as geometry.rotation turns
        assert np.allclose(turned, d.axis) and 89 < angle.max() <= 90 + 1e-9 and angle.min() < 1
        signed = np.degrees(2 * np.arctan2(q[0, 1:] @ np.asarray(d.axis), q[0, 0]))
        assert np.allclose(matrices[0], rotation(d.axis, signed))
    elif pose == "still":  # one frame: a wobble of at most 10°
        assert angle.max() <= 10 + 1e-9 and angle.max() > 9.5
    else:  # Haar: a turned vector is uniform on the sphere
        assert abs(np.mean(turned[:, 2])) < 0.02 and abs(np.mean(turned[:, 2] ** 2) - 1 / 3) < 0.01


def test_caps_are_uniform_and_bounded():
    rng = np.random.default_rng(4)
    centre = rng.standard_normal((200000, 3))
    centre[:4] = [[0, 0, 1], [0, 0, -1], [1, 0, 0], [1e-12, 0, -1]]
    centre /= np.linalg.norm(centre, axis=-1, keepdims=True)
    got = cap(centre, 30.0, rng)
    cos = np.sum(got * centre, -1)
    assert np.allclose(np.linalg.norm(got, axis=-1), 1.0) and np.degrees(np.arccos(cos.min())) <= 30 + 1e-6
    # uniform by area: cos θ uniform in [cos 30°, 1]; the direction about the centre without bias
    assert abs(np.mean(cos) - (1 + np.cos(np.radians(30))) / 2) < 1e-3
    assert np.abs(np.mean(got - cos[:, None] * centre, axis=0)).max() < 2e-3
