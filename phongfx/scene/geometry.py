"""Per-frame pixels of a scene file: what every shading datapath of the scene is fed.

Meshes (spheres, tori, OBJ files) are placed (``scale``, ``offset``), concatenated,
rotated for each frame about ``frames.axis`` by ``frame·degrees/count`` and rasterized
by :func:`phongfx.scene.mesh.rasterize` (orthographic view down -z, fitted to the image);
positions are in the scene's units after the rotation, the units of light and camera
positions.  Lyon's spheres come from :func:`phongfx.scene.lyon.pixels` (unit spheres, the
k-th centred at ``(k, 0, 0)``); they ignore the frame rotation (every frame is the
same image), as Lyon's test scene has none.

Toward a point light or a local viewer the unit vector changes per pixel (Lyon §"local
viewer"); ``l0``/``l1`` (``v0``/``v1``) are the exact unit vectors at the span's end
points, what an L (V) interpolator is loaded with, and ``light`` (``viewer``) the
exact one at the pixel.  Directional lights and a camera at infinity give one vector
everywhere.

The reference a shader is measured against is shaded with one formula, exact, in
float (:func:`shade`, :func:`levels`), per channel ``c`` of r, g, b::

    I_c = clip(ka · M_c + sum_i L_ic · M_c · (kd · diff_i + ks · spec_i · [diff_i > 0]), 0, 1)
    level = floor(I_c · (2^bits - 1) + 0.5)

``M`` the material's colour, ``L_i`` light i's RGB intensity; the specular term counts
only where the light is in front of the surface (``diff_i = max(N·L, 0) > 0``), the
backside test the hardware blend (:mod:`phongfx.golden.blend`) applies as well.
"""

from dataclasses import dataclass

import numpy as np

from .lyon import Scene, pixels
from .mesh import Mesh, rasterize, unit

__all__ = ["FrameGeometry", "frames", "rotation", "scene_mesh", "shade", "levels", "error_levels", "pixel_error",
           "terminator_lit"]


@dataclass
class FrameGeometry:
    """The visible covered pixels of one frame, in scanline order (P of them)."""
    width: int
    height: int
    row: np.ndarray       # (P,) int64
    col: np.ndarray       # (P,) int64
    span: np.ndarray      # (P,) int64 span id (index into spans.length for meshes)
    a: np.ndarray         # (P,) position in the span, 0 at its first pixel, 1 at its last
    n0: np.ndarray        # (P, 3) span-start unit normal
    n1: np.ndarray        # (P, 3) span-end unit normal
    normal: np.ndarray    # (P, 3) exact unit normal at the pixel (normalized interpolation)
    position: np.ndarray  # (P, 3) surface point
    l0: np.ndarray        # (lights, P, 3) unit vectors toward each light at the span start
    l1: np.ndarray        # (lights, P, 3) ... at the span end
    light: np.ndarray     # (lights, P, 3) ... at the pixel
    v0: np.ndarray        # (P, 3) unit vector toward the viewer at the span start
    v1: np.ndarray        # (P, 3) ... at the span end
    viewer: np.ndarray    # (P, 3) ... at the pixel
    rgb: np.ndarray       # (lights, 3) each light's RGB intensity
    n: np.ndarray         # (P,) shininess (a material's n_lo for a range)
    kd: np.ndarray        # (P,)
    ks: np.ndarray        # (P,)
    ka: np.ndarray        # (P,)
    colour: np.ndarray    # (P, 3) the material's RGB colour
    material: np.ndarray  # (P,) int64 index into list(spec.materials)
    spans: object         # phongfx.scene.mesh.Spans, None for lyon_spheres
    frame: int
    bits: int

    @property
    def index(self):
        return self.frame

    @property
    def interpolated(self):
        """(P, 3) ``(1-a)·n0 + a·n1``: the normal as the LIRP gives it, not normalized."""
        a = np.asarray(self.a, dtype=np.float64)[:, None]
        return (1 - a) * self.n0 + a * self.n1

    def __len__(self):
        return len(self.row)


def rotation(axis, degrees):
    """Rotation by ``degrees`` about the unit ``axis`` (Rodrigues' formula)."""
    u = np.asarray(axis, dtype=np.float64)
    u = u / np.linalg.norm(u)
    angle = np.radians(degrees)
    cross = np.array([[0, -u[2], u[1]], [u[2], 0, -u[0]], [-u[1], u[0], 0]])
    return np.cos(angle) * np.eye(3) + np.sin(angle) * cross + (1 - np.cos(angle)) * np.outer(u, u)


def scene_mesh(spec):
    """(one :class:`~phongfx.scene.mesh.Mesh` of every placed object, (F,) object index per face)."""
    parts, owner, base = [], [], 0
    for index, obj in enumerate(spec.objects):
        mesh = obj.params["mesh"]
        parts.append((mesh.vertices * obj.params["scale"] + obj.params["offset"], mesh.normals,
                      mesh.faces + base, mesh.polygons))
        owner.append(np.full(len(mesh.faces), index))
        base += len(mesh.vertices)
    vertices, normals, faces, polygons = zip(*parts)
    return (Mesh(np.concatenate(vertices), np.concatenate(normals), np.concatenate(faces),
                 sum(polygons)), np.concatenate(owner))


def _toward(kind, vector, points, what, frame):
    """(3 arrays (P, 3)) unit vectors toward a light or viewer from each of ``points``."""
    if kind in ("directional", "infinity"):
        return [np.broadcast_to(np.asarray(vector), p.shape) for p in points]
    out = []
    for p in points:
        d = np.asarray(vector) - p
        if len(d) and np.min(np.linalg.norm(d, axis=-1)) < 1e-9:
            raise ValueError(f"{what} lies on the surface in frame {frame}, not in front of it")
        out.append(unit(d))
    return out


def _mesh_frame(spec, mesh, owner, frame):
    r = rotation(spec.frames.axis, frame * spec.frames.degrees / spec.frames.count)
    spans = rasterize(mesh, r, spec.output.width, spec.output.height)
    visible = spans.visible
    span = spans.pixel_span()[visible]
    xy = spans.pixel_xy()[visible]
    obj = owner[spans.face[span]]
    return dict(row=xy[:, 1], col=xy[:, 0], span=span, a=spans.pixel_t()[visible],
                n0=spans.na[span], n1=spans.nb[span],
                normal=unit(spans.interpolated_normals()[visible]),
                position=spans.interpolated_positions()[visible],
                ends=(spans.pa[span], spans.pb[span]), obj=obj, spans=spans)


def _lyon_frame(spec):
    params = spec.objects[0].params
    px = pixels(Scene(params["radius"], params["shininess"], span=params["span"]))
    centre = np.stack([px.sphere, np.zeros(len(px)), np.zeros(len(px))], -1)
    a = px.a[:, None]
    # a new span starts exactly where a = 0 (one pixel per span for exact normals); Phong's
    # normal is the interpolated one, normalized (with spans it is not the sphere's own)
    return dict(row=px.row.astype(np.int64), col=px.col.astype(np.int64),
                span=np.cumsum(px.a == 0) - 1, a=px.a, n0=px.n0, n1=px.n1,
                normal=unit((1 - a) * px.n0 + a * px.n1),
                position=px.normal + centre, ends=(px.n0 + centre, px.n1 + centre),
                obj=np.zeros(len(px), dtype=np.int64), spans=None, n=px.n.astype(np.float64))


def frames(spec):
    """One :class:`FrameGeometry` per frame of the :class:`~phongfx.scene.file.SceneSpec`."""
    names = list(spec.materials)
    lyon = spec.objects[0].kind == "lyon_spheres"
    mesh, owner = (None, None) if lyon else scene_mesh(spec)
    material = np.array([names.index(obj.material) for obj in spec.objects])
    kd = np.array([spec.materials[name].kd for name in names])
    ks = np.array([spec.materials[name].ks for name in names])
    ka = np.array([spec.materials[name].ka for name in names])
    colour = np.array([spec.materials[name].colour for name in names], dtype=np.float64).reshape(-1, 3)
    out = []
    for frame in range(spec.frames.count):
        g = _lyon_frame(spec) if lyon else _mesh_frame(spec, mesh, owner, frame)
        m = material[g["obj"]]
        if "n" not in g:
            n_lo = np.array([spec.materials[name].n_lo or 0 for name in names], dtype=np.float64)
            g["n"] = n_lo[m]
        points = (g["ends"][0], g["ends"][1], g["position"])
        lights = [_toward(light.kind, light.vector, points, f"lights[{i}].position", frame)
                  for i, light in enumerate(spec.lights)]
        l0, l1, lit = (np.stack([v[k] for v in lights]) for k in range(3))
        path = spec.frames.camera_path
        v0, v1, viewer = _toward(spec.camera.kind, path[frame] if path else spec.camera.vector, points,
                                 f"frames.camera_path[{frame}]" if path else "camera.position", frame)
        out.append(FrameGeometry(
            spec.output.width, spec.output.height, g["row"], g["col"], g["span"], g["a"],
            g["n0"], g["n1"], g["normal"], g["position"], l0, l1, lit,
            np.ascontiguousarray(v0), np.ascontiguousarray(v1), np.ascontiguousarray(viewer),
            np.array([light.rgb for light in spec.lights], dtype=np.float64).reshape(-1, 3), g["n"],
            kd[m], ks[m], ka[m], colour[m], m, g["spans"], frame, spec.output.bits))
    return out


def shade(geometry, diff, spec, lit=None):
    """(P, 3) RGB intensities of the module docstring's formula, for per-light diffuse and
    specular terms ``diff``, ``spec`` of shape (lights, P), clipped to [0, 1]; ``lit``
    (lights, P) bool, if given, is the backside test instead of ``diff > 0``."""
    diff, spec = np.asarray(diff, dtype=np.float64), np.asarray(spec, dtype=np.float64)
    shape = (len(geometry.rgb), len(geometry))
    if diff.shape != shape or spec.shape != shape:
        raise ValueError(f"diff and spec must have shape (lights, pixels) = {shape}, "
                         f"not {diff.shape} and {spec.shape}")
    lit = diff > 0 if lit is None else np.asarray(lit, dtype=bool)
    terms = geometry.kd * diff + geometry.ks * np.where(lit, spec, 0.0)  # (lights, P)
    light = np.einsum("lp,lc->pc", terms, geometry.rgb)
    return np.clip(geometry.colour * (geometry.ka[:, None] + light), 0.0, 1.0)


def levels(intensity, bits):
    """Displayed code ``floor(I · (2^bits - 1) + 0.5)`` (int64) of intensities in [0, 1]."""
    return np.floor(np.asarray(intensity, dtype=np.float64) * ((1 << bits) - 1) + 0.5).astype(np.int64)


def error_levels(intensity, reference, bits):
    """``|I - I_ref| · (2^bits - 1)``: an error in output levels, before rounding."""
    return np.abs(np.asarray(intensity, np.float64) - np.asarray(reference, np.float64)) * ((1 << bits) - 1)


def pixel_error(codes, reference, bits):
    """``|out - level(I_ref)|``: how many display levels a shader's output codes are from the
    displayed reference (an integer array, the shape of ``codes``)."""
    return np.abs(np.asarray(codes, dtype=np.int64) - levels(reference, bits))


def terminator_lit(cosine, lit, bits):
    """The reference's backside test for exact ``cosine = N·L`` (any shape): ``N·L > 0``,
    except in the terminator band ``|N·L| <= 1/(2^bits - 1)`` (where the diffuse term is
    under one display level), where the shader's own test ``lit`` (same shape) decides.

    The test is a step: for a low ``n`` the specular term is large where a light grazes the
    surface, so a shader whose ``N·L`` is off by a hair on the wrong side of 0 shows a
    jump of tens of levels at that pixel.  Where the whole diffuse term is below one
    level, the terminator's place is within the display's own resolution, and either side
    is Phong's answer.  ``lit`` None (a unit without a diffuse term): the exact test."""
    cosine = np.asarray(cosine, dtype=np.float64)
    exact = cosine > 0
    if lit is None:
        return exact
    return np.where(np.abs(cosine) <= 1.0 / ((1 << bits) - 1), lit, exact)
