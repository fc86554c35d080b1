"""Scene files as evaluation scenes: a user's own geometry beside the built-in torus and sphere.

A sweep measures every method on the pixels of a reference scene
(:data:`phongfx.explore.methods.SCENES`).  A scene file (README "Scene files",
:func:`phongfx.scene.file.load_scene`) gives its own: every frame of its meshes, placed and
rotated as the scene compiler sees them, lit by each of its lights in turn (the units are
evaluated on one light; the lights are independent copies), all pooled into one set of
metrics named after the file (``my.toml`` -> ``my.phong.max``).  The sweep's units see the
viewer at infinity down -z and lights at infinity, so a scene with a local camera or a
point light, or Lyon's analytic spheres (no mesh spans), is refused with the reason;
``phongfx compile`` takes those.  The shininess is the point's ``n``, not the file's.
"""

import functools
import hashlib
import os
from dataclasses import dataclass

import numpy as np

__all__ = ["is_scene_file", "scene_label", "FileView", "file_views", "file_digest", "check_scene_file"]


def is_scene_file(entry):
    """Whether a sweep's ``scenes`` entry names a file (``.toml``) rather than a built-in scene."""
    return isinstance(entry, str) and entry.endswith(".toml")


def scene_label(entry):
    """The name a file scene's metrics carry: the file's stem (``scenes/my.toml`` -> ``my``)."""
    return os.path.splitext(os.path.basename(entry))[0]


@dataclass(frozen=True)
class FileView:
    """One frame of a scene file under one of its lights, in the shape the methods'
    runs read (:class:`phongfx.explore.methods.Scene`'s ``data``)."""

    path: str
    frame: int
    light: int

    @functools.cached_property
    def data(self):
        from phongfx.scene.geometry import rotation, scene_mesh
        from phongfx.scene.mesh import rasterize
        from phongfx.scene.span_inputs import halfway

        spec = _spec(self.path)
        mesh, _ = scene_mesh(spec)
        turn = rotation(spec.frames.axis, self.frame * spec.frames.degrees / spec.frames.count)
        spans = rasterize(mesh, turn, spec.output.width, spec.output.height)
        light = np.asarray(spec.lights[self.light].vector, dtype=np.float64)
        light = light / np.linalg.norm(light)
        normals = spans.interpolated_normals()
        unit = normals / np.maximum(np.linalg.norm(normals, axis=-1, keepdims=True), 1e-300)
        return {"spans": spans, "light": light, "h": halfway(light), "normal": unit, "visible": spans.visible}


@functools.lru_cache(maxsize=16)
def _spec(path):
    from phongfx.scene.file import load_scene

    return load_scene(path)


def check_scene_file(path):
    """The :class:`~phongfx.scene.file.SceneSpec` of ``path`` if a sweep can use it; else
    ``ValueError`` saying why (a bad file: :class:`~phongfx.scene.file.SceneError`'s line)."""
    spec = _spec(os.path.abspath(path))
    for i, obj in enumerate(spec.objects):
        if obj.kind == "lyon_spheres":
            raise ValueError(f"objects[{i}] is lyon_spheres, which has no mesh spans; sweeps take "
                             f"sphere, torus and mesh objects (phongfx compile takes this scene)")
    if spec.camera.kind != "infinity" or not np.allclose(spec.camera.vector, (0.0, 0.0, 1.0)):
        raise ValueError(f"camera must be at infinity with direction [0, 0, 1] (the sweep's units see "
                         f"V = (0, 0, 1)), not {spec.camera.kind} {list(spec.camera.vector)}; "
                         f"phongfx compile takes this scene")
    for i, light in enumerate(spec.lights):
        if light.kind != "directional":
            raise ValueError(f"lights[{i}] is a point light; sweeps take lights at infinity (direction), "
                             f"phongfx compile takes this scene")
    return spec


def file_views(path):
    """``(label, views)`` of a scene file: a :class:`FileView` per frame and light."""
    path = os.path.abspath(path)
    spec = check_scene_file(path)
    return scene_label(path), tuple(FileView(path, frame, light) for frame in range(spec.frames.count)
                                    for light in range(len(spec.lights)))


def file_digest(path):
    """16 hex digits of the file's bytes: a point's identity changes with its scene file."""
    with open(path, "rb") as file:
        return hashlib.sha256(file.read()).hexdigest()[:16]
