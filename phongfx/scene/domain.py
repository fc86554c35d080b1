"""A scene's input domain: every input its shading hardware can receive while the scene plays.

The frames of a scene file (:mod:`phongfx.scene.geometry`) are a sample; a design fitted to
them can fail on the in-between poses.  :func:`domain` derives from the scene a set that holds
every input the rasterizer (:func:`phongfx.scene.mesh.rasterize`) can feed under the scene's
motion, and :meth:`Domain.sample` draws points of it.  Every bound is *sound*, an
over-approximation, for these reasons:

* **Poses.**  Meshes turn about the scene's origin (``frames.axis``, after ``scale`` and
  ``offset``).  ``"motion"`` (default for several frames) is the continuous rotation over
  ``[0, frames.degrees]`` that the frames sample at ``frame·degrees/count``; ``"any"`` every
  rotation; ``"still"`` (default for one frame) each frame's pose turned by up to
  ``wobble_degrees`` about any axis.  The default wobble, 5°, is the smallest round angle
  that holds the normals *between* a still frame's pixels with margin: a pixel step turns a
  normal by about ``1/r`` radian on an object ``r`` pixels across (0.9° at 64, 1.8° at 32),
  so a sub-pixel shift, a re-placed object or camera shake stays inside, while a still scene
  is not held to an animation's requirement.  Lyon's spheres ignore rotation.
* **Normals toward the viewer** (``view_cos_min``, pose-independent).  The rasterizer draws
  the faces whose winding normal ``f`` has eye-space ``z > 0``; every normal it presents
  (span ends ``n0``, ``n1`` and the pixel's ``N``) is a positive combination of the face's
  unit vertex normals, normalized.  With ``β`` the largest angle between a vertex normal and
  ``f`` over the faces, ``N·f >= cos β`` when ``β <= 90°`` (each term's projection is at
  least ``cos β`` and the combination is no longer than its weights' sum), so ``N`` is within
  ``90° + β`` of the view axis ``z``.  A viewer direction ``V`` within ``γ`` of ``z`` (a
  camera at infinity: its direction; a local camera: every direction from the bounding ball
  to it) gives ``N·V >= cos(90° + β + γ) = -sin(β + γ)`` (``-1`` once ``β + γ >= 90°``).  Lyon's
  spheres present front-hemisphere normals (``β = 0``).
* **Span angle** (``max_span_angle_deg``).  A span is one triangle's run on one scanline
  (:func:`~phongfx.scene.mesh.rasterize_screen`); its end normals are the triangle's vertex
  normals ``n_i`` interpolated along its edges, then between them at pixel centres inside the
  triangle (the fill rule keeps every centre inside), normalized: normalized convex
  combinations of the ``n_i``.  For ``u = Σα_i n_i``,
  ``w = Σβ_j n_j``: ``u·w >= min n_i·n_j = c`` and ``|u|, |w| <= 1``, so when ``c >= 0`` the
  angle is at most the triangle's largest pairwise vertex-normal angle, for every pose; a
  triangle with a pair over 90° gives 180°.  Lyon's spheres: the widest span of their fixed
  image.  A ``[domain] max_span_angle_deg`` (a narrower rasterizer) replaces the derived
  value and is then the user's claim (:meth:`Domain.as_dict` says so).
  ``min_normal_length = cos(angle/2)``: ``|(1-a)n0 + a·n1|`` is shortest at ``a = 1/2``.
* **Positions.**  A rotation about the origin keeps every placed vertex within ``max|v|``, and
  span ends lie on their triangle: the ball about the origin of that radius holds every
  surface point under every pose; ``|x1 - x0|`` is at most the longest triangle edge, and
  spans are horizontal on the screen (``x1 - x0`` has no eye-space ``y``).  Lyon's spheres:
  unit spheres at ``(k, 0, 0)``, span chords from the image.
* **Light and viewer directions.**  Directional lights and a camera at infinity: their one
  vector.  A point light or a local camera at ``P``: ``unit(P - x)`` for ``x`` in the ball,
  within ``asin(radius/|P - centre|)`` of ``unit(P - centre)`` (:meth:`Domain.cone`).
* **n**: every integer of a material's range ``[lo, hi]``, its single ``n``, or the
  ``shininess`` list of ``lyon_spheres``; materials no object uses admit none (``()``).

:meth:`Domain.sample` draws (:mod:`phongfx.scene.sampling`): a material uniformly among the
used ones; ``n`` uniformly among its admissible values (Lyon: a uniform sphere and its ``n``); a
pose of the pose set, shared by 16 points (``"motion"`` a uniform angle, ``"any"`` a uniform (Haar)
rotation, ``"still"`` a uniform frame and a wobble about a uniform axis with the Haar density
``∝ 1 - cos θ`` of its angle up to ``wobble_degrees``); ``n0`` the normalized interpolated vertex
normal at a uniform point of a face of the material drawn by area among those facing the viewer
under the pose, turned by it (Lyon: uniform on the front hemisphere); ``n1`` uniform in the cap of
``max_span_angle_deg`` about ``n0``, redrawn until ``n1`` and ``N`` meet ``view_cos_min``; ``a``
uniform in [0, 1] with 2 % exactly 0 and 2 % exactly 1; with a point light or a local camera, span
start ``x0`` the surface point (half the points) or uniform in the ball, ``x1 = x0 + d·u`` with
``u`` uniform in the eye-space xz plane and ``d`` uniform in ``[-max_span_length,
max_span_length]`` clipped to the ball, the pixel at ``(1-a)x0 + a·x1`` (else all three the
surface point, as no vector depends on it); light and viewer vectors from these points as
:func:`phongfx.scene.geometry.frames` makes them.
"""

import math
from dataclasses import dataclass, field, replace

import numpy as np

from .geometry import scene_mesh
from .lyon import Scene, pixels
from .mesh import unit
from .patches import mesh_regions
from .regions import lyon_regions, summary
from .sampling import Surface, draw, draw_chunk, draw_chunks, face_table

__all__ = ["POSES", "WOBBLE_DEFAULT", "SAMPLES_DEFAULT", "FINAL_SAMPLES_DEFAULT", "SEED_DEFAULT", "Options",
           "Domain", "domain", "parse_options"]

POSES = ("motion", "any", "still")
WOBBLE_DEFAULT = 5.0
SAMPLES_DEFAULT = 1_000_000
FINAL_SAMPLES_DEFAULT = 2_000_000
SEED_DEFAULT = 1
_KEYS = ("pose", "wobble_degrees", "max_span_angle_deg", "samples", "final_samples", "seed")
_MAX_SAMPLES = 10 ** 10


@dataclass(frozen=True)
class Options:
    """A scene file's checked ``[domain]`` table (:func:`parse_options`); None: derived."""
    pose: str = None
    wobble_degrees: float = WOBBLE_DEFAULT
    max_span_angle_deg: float = None
    samples: int = SAMPLES_DEFAULT
    final_samples: int = FINAL_SAMPLES_DEFAULT
    seed: int = SEED_DEFAULT


def parse_options(reader, data, frame_count):
    """The :class:`Options` of a ``[domain]`` table ``data``, checked by the scene file's
    ``reader`` (its ``fail``, ``table``, ``number``, ``integer``: one-line
    :class:`~phongfx.scene.file.SceneError`)."""
    data = reader.table(data, "domain", _KEYS)
    pose = data.get("pose")
    if pose is not None and pose not in POSES:
        reader.fail(f"domain.pose must be one of {', '.join(POSES)}, not {pose!r}")
    if "wobble_degrees" in data and (pose or ("motion" if frame_count > 1 else "still")) != "still":
        why = f"{pose!r}" if pose else f"'motion' (the default for frames.count = {frame_count})"
        reader.fail(f"domain.wobble_degrees applies only to pose \"still\", not to pose {why}")
    wobble = reader.number(data.get("wobble_degrees", WOBBLE_DEFAULT), "domain.wobble_degrees", 0, 180)
    angle = data.get("max_span_angle_deg")
    angle = None if angle is None else reader.number(angle, "domain.max_span_angle_deg", 0, 180)
    counts = {key: reader.integer(data.get(key, default), f"domain.{key}", 1, _MAX_SAMPLES)
              for key, default in (("samples", SAMPLES_DEFAULT), ("final_samples", FINAL_SAMPLES_DEFAULT))}
    seed = reader.integer(data.get("seed", SEED_DEFAULT), "domain.seed", 0, 2 ** 63 - 1)
    return Options(pose, wobble, angle, counts["samples"], counts["final_samples"], seed)


@dataclass(frozen=True)
class Domain:
    """Every input the compiled hardware can receive while the scene plays (module docstring
    says what was chosen and why)."""
    pose: str                 # "motion" (the continuous rotation [frames] samples), "any", "still"
    axis: tuple               # rotation axis of "motion" (unit, 3 floats)
    degrees: tuple            # (lo, hi) rotation range of "motion", degrees
    wobble_degrees: float     # "still": any rotation up to this angle about any axis
    view_cos_min: float       # every presented unit normal N has N·V >= this (V toward the viewer)
    max_span_angle_deg: float  # angle between the two span-end normals of any span <= this
    min_normal_length: float  # = cos(max_span_angle/2): |(1-a)·n0 + a·n1| >= this
    ball: tuple               # ((cx, cy, cz), radius): holds every surface point under every pose
    max_span_length: float    # |x1 - x0| of a span's end points, scene units
    lights: tuple             # per light (kind "directional"|"point", vector, rgb) as the scene gives
    camera: tuple             # (kind "infinity"|"point", vector)
    materials: tuple          # per material index: (name, admissible n values, sorted ints; () unused)
    samples: int              # domain points per measured width point during the search
    final_samples: int        # for the chosen design
    seed: int
    still_degrees: tuple = (0.0,)   # "still": the frames' angles about axis, each wobbled
    camera_path: tuple = ()   # a local camera's positions, one per frame (empty: camera's own)
    face_cap_deg: float = 0.0  # β: largest vertex-normal to face-normal angle (module docstring)
    view_tilt_deg: float = 0.0  # γ: largest angle between a viewer direction and the view axis
    derived_span_angle_deg: float = None  # the derived bound, when [domain] gave its own
    coefficients: tuple = ()  # per material index (kd, ks, ka, (r, g, b))
    bits: int = 8
    surface: Surface = field(default=None, compare=False, hash=False, repr=False)
    view_cos_max: float = 1.0  # every presented N has N·V <= this (below 1 in a region)
    ends_cos: tuple = (-1.0, 1.0)  # a region's limits on n0·V and n1·V (a Lyon band's ends leave it)
    regions: tuple = ()       # :class:`~phongfx.scene.regions.Region`: together every input
    region_name: str = ""     # a region's sub-domain (:meth:`region`): its name

    def region(self, index):
        """The domain of region ``index`` alone (:mod:`phongfx.scene.regions`): this domain with
        the region's limits, which every bounding method and the sampler read."""
        r = self.regions[index]
        return replace(self, view_cos_min=r.view_cos_min, view_cos_max=r.view_cos_max, ends_cos=r.ends_cos,
                       max_span_angle_deg=r.max_span_angle_deg, min_normal_length=r.min_normal_length,
                       materials=r.materials, ball=r.ball, surface=r.surface, regions=(), region_name=r.name,
                       **dict(r.poses))

    @property
    def user_span_angle(self):
        """Whether ``max_span_angle_deg`` is the ``[domain]`` table's claim, not derived."""
        return self.derived_span_angle_deg is not None

    def cone(self, position):
        """``(axis, half_angle_deg)``: every direction toward ``position`` (a point light, a
        local camera) from a point of the ball lies within ``half_angle_deg`` of the unit
        ``axis``, ``asin(radius/distance)``; 180° (any direction) when the point is in the ball."""
        return _cone_of(self.ball, position)

    @property
    def light_cones(self):
        """Per light, its :meth:`cone` (a point light) or None (a directional one: one vector)."""
        return tuple(self.cone(vector) if kind == "point" else None for kind, vector, _ in self.lights)

    @property
    def viewer_cones(self):
        """Per camera position (the path's, or the one), its :meth:`cone`; () at infinity."""
        if self.camera[0] != "point":
            return ()
        return tuple(self.cone(p) for p in self.camera_path or (self.camera[1],))

    def chunks(self, count, seed):
        """:class:`~phongfx.scene.geometry.FrameGeometry` pieces of
        :data:`~phongfx.scene.sampling.CHUNK` points (the last shorter) whose concatenation is
        ``sample(count, seed)``: the same points in bounded memory."""
        return draw_chunks(self, count, seed)

    def chunk(self, count, seed, index):
        """Piece ``index`` of :meth:`chunks` alone (:func:`~phongfx.scene.sampling.draw_chunk`)."""
        return draw_chunk(self, count, seed, index)

    def sample(self, count, seed):
        """A :class:`~phongfx.scene.geometry.FrameGeometry` of ``count`` domain points (one
        pixel per span, ``span = arange(count)``, ``frame = -1``), drawn as the module
        docstring says; deterministic for (self, count, seed)."""
        return draw(self, count, seed)

    def as_dict(self):
        """JSON-able, for the manifest: what the domain holds and why (the sampler's surface and
        the materials' coefficients, which the scene gives, left out), where the span angle
        came from, and :meth:`describe`."""
        out = {"pose": self.pose, "axis": list(self.axis), "degrees": list(self.degrees),
               "wobble_degrees": self.wobble_degrees, "still_degrees": list(self.still_degrees),
               "view_cos_min": self.view_cos_min, "face_cap_deg": self.face_cap_deg,
               "view_tilt_deg": self.view_tilt_deg, "max_span_angle_deg": self.max_span_angle_deg,
               "max_span_angle_source": ("user claim ([domain] max_span_angle_deg)" if self.user_span_angle
                                         else "derived (sound)"),
               "derived_max_span_angle_deg": (self.derived_span_angle_deg if self.user_span_angle
                                              else self.max_span_angle_deg),
               "min_normal_length": self.min_normal_length,
               "ball": {"centre": list(self.ball[0]), "radius": self.ball[1]},
               "max_span_length": self.max_span_length,
               "lights": [{"kind": k, "vector": list(v), "rgb": list(c), "cone": _cone(cone)}
                          for (k, v, c), cone in zip(self.lights, self.light_cones)],
               "camera": {"kind": self.camera[0], "vector": list(self.camera[1]),
                          "path": [list(p) for p in self.camera_path],
                          "cones": [_cone(cone) for cone in self.viewer_cones]},
               "materials": [{"name": name, "n": _n_summary(values)} for name, values in self.materials],
               "samples": self.samples, "final_samples": self.final_samples, "seed": self.seed,
               "regions": {"count": len(self.regions), "summary": summary(self.regions),
                           "each": [r.as_dict() for r in self.regions]},
               "description": self.describe()}
        return out

    def describe(self):
        """One paragraph: what the domain is and why (for the manifest and the docs)."""
        if self.pose == "motion":
            pose = (f"the continuous rotation about ({_vec(self.axis)}) over [{self.degrees[0]:g}°, "
                    f"{self.degrees[1]:g}°] that the frames sample")
        elif self.pose == "any":
            pose = "every rotation of the objects about the origin"
        else:
            pose = (f"each frame's pose turned by up to {self.wobble_degrees:g}° about any axis (a still "
                    f"scene's default: it holds the normals between the frame's pixels)")
        lyon = self.surface is not None and self.surface.lyon
        if lyon:
            pose = "the fixed image of Lyon's spheres (they ignore rotation)"
            why = "front-hemisphere normals"
        else:
            why = f"faces' vertex normals within {self.face_cap_deg:.2f}° of the face's"
        source = "the image's widest span" if lyon else "the widest triangle"
        claim = (f", the [domain] table's claim (derived: {self.derived_span_angle_deg:.2f}°)"
                 if self.user_span_angle else f", from {source}")
        ns = "; ".join(f"{name}: n in {_n_text(values)}" for name, values in self.materials if values)
        return (f"Poses: {pose}. Every presented normal has N·V >= {self.view_cos_min:.4f} ({why}, "
                f"viewer within {self.view_tilt_deg:.2f}° of the view axis); span ends at most "
                f"{self.max_span_angle_deg:.2f}° apart{claim}, so |(1-a)n0 + a·n1| >= "
                f"{self.min_normal_length:.4f}, any a in [0, 1]; surface points within {self.ball[1]:.4g} "
                f"of ({_vec(self.ball[0])}), span ends at most {self.max_span_length:.4g} apart; "
                f"{ns}; {summary(self.regions)}. Searched on {self.samples:,} points per measured design and "
                f"{self.final_samples:,} for the chosen one (seed {self.seed}).")


def _cone(cone):
    return None if cone is None else {"axis": list(cone[0]), "half_angle_deg": cone[1]}


def _vec(v):
    return ", ".join(f"{x:.4g}" for x in v)


def _n_summary(values):
    """``[lo, hi]`` for a run of integers, else the list (JSON-able)."""
    values = list(values)
    if len(values) > 2 and values == list(range(values[0], values[-1] + 1)):
        return {"range": [values[0], values[-1]]}
    return values


def _n_text(values):
    summary = _n_summary(values)
    return "{}..{}".format(*summary["range"]) if isinstance(summary, dict) else "{" + ", ".join(map(str, summary)) + "}"


def _angle(u, w):
    """Angles (degrees) between rows of unit vectors ``u`` and ``w``."""
    return np.degrees(np.arccos(np.clip(np.sum(u * w, -1), -1.0, 1.0)))


def _mesh_surface(spec, names):
    """(Surface, β, span-angle bound, ball, longest edge) of the placed meshes (module docstring)."""
    mesh, owner = scene_mesh(spec)
    tri = mesh.vertices[mesh.faces]
    cross = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    area = np.linalg.norm(cross, axis=-1)
    keep = area > 0  # a zero-area face covers no pixel under any pose
    faces, f = mesh.faces[keep], cross[keep] / area[keep, None]
    normals = unit(mesh.normals)
    vn = normals[faces]  # (F, 3, 3)
    cap = max(float(np.max(_angle(vn[:, i], f))) for i in range(3)) if len(faces) else 0.0
    pair = max(float(np.max(_angle(vn[:, i], vn[:, (i + 1) % 3]))) for i in range(3)) if len(faces) else 0.0
    longest = max(float(np.max(np.linalg.norm(tri[keep][:, i] - tri[keep][:, (i + 1) % 3], axis=-1)))
                  for i in range(3)) if len(faces) else 0.0
    material = np.array([names.index(obj.material) for obj in spec.objects])[owner[keep]]
    tables = tuple(face_table(mesh.vertices, normals, faces[material == m], f[material == m],
                              area[keep][material == m]) if np.any(material == m) else None
                   for m in range(len(names)))
    surface = Surface(False, tables=tables)
    radius = float(np.max(np.linalg.norm(mesh.vertices, axis=-1)))
    return surface, cap, pair if pair <= 90.0 else 180.0, ((0.0, 0.0, 0.0), radius), longest


def _lyon_surface(spec, geometries):
    """(Surface, β = 0, widest span angle, ball, widest span chord) of Lyon's fixed image."""
    params = spec.objects[0].params
    if geometries:
        n0, n1 = geometries[0].n0, geometries[0].n1
    else:
        px = pixels(Scene(params["radius"], params["shininess"], span=params["span"]))
        n0, n1 = px.n0, px.n1
    angle = float(np.max(_angle(n0, n1), initial=0.0))
    chord = float(np.max(np.linalg.norm(n1 - n0, axis=-1), initial=0.0))
    half = (len(params["shininess"]) - 1) / 2
    return Surface(True, shininess=tuple(params["shininess"])), 0.0, angle, ((half, 0.0, 0.0), half + 1.0), chord


def _cone_of(ball, position):
    """:meth:`Domain.cone` of ``position`` seen from ``ball``."""
    d = np.asarray(position, dtype=np.float64) - np.asarray(ball[0])
    distance = float(np.linalg.norm(d))
    if distance <= ball[1]:
        return (0.0, 0.0, 1.0), 180.0
    return tuple(float(x) for x in d / distance), math.degrees(math.asin(ball[1] / distance))


def _view_tilt(spec, ball):
    """γ (degrees): the largest angle between the view axis z and a direction toward the
    viewer from a point of ``ball`` (module docstring)."""
    z = np.array([0.0, 0.0, 1.0])
    if spec.camera.kind == "infinity":
        return float(_angle(np.asarray(spec.camera.vector), z))
    cones = [_cone_of(ball, position) for position in spec.frames.camera_path or (spec.camera.vector,)]
    return min(180.0, max(float(_angle(np.asarray(axis), z)) + half for axis, half in cones))


def _admissible(spec, names):
    used = {obj.material: obj for obj in spec.objects}
    out = []
    for name in names:
        obj, m = used.get(name), spec.materials[name]
        if obj is None:
            out.append((name, ()))
        elif obj.kind == "lyon_spheres":
            out.append((name, tuple(sorted(set(obj.params["shininess"])))))
        else:
            out.append((name, tuple(range(m.n_lo, m.n_hi + 1))))
    return tuple(out)


def domain(spec, geometries=None):
    """The :class:`Domain` of a :class:`~phongfx.scene.file.SceneSpec` and its ``[domain]``
    table (module docstring); ``geometries``, the scene's frames if already made, saves
    re-rasterizing Lyon's image."""
    options = getattr(spec, "domain", None) or Options()
    names = list(spec.materials)
    lyon = spec.objects[0].kind == "lyon_spheres"
    surface, cap, span_angle, ball, span_length = (_lyon_surface(spec, geometries) if lyon
                                                   else _mesh_surface(spec, names))
    tilt = _view_tilt(spec, ball)
    # N within 90° + β of the view axis, V within γ: N·V >= cos(90° + β + γ) = -sin(β + γ)
    view_cos_min = 0.0 - math.sin(math.radians(cap + tilt)) if cap <= 90.0 and cap + tilt < 90.0 else -1.0
    derived = None
    if options.max_span_angle_deg is not None:
        derived, span_angle = span_angle, options.max_span_angle_deg
    coefficients = tuple((m.kd, m.ks, m.ka, tuple(m.colour)) for m in spec.materials.values())
    materials = _admissible(spec, names)
    pose = options.pose or ("motion" if spec.frames.count > 1 else "still")
    count, degrees = spec.frames.count, spec.frames.degrees
    still = tuple(f * degrees / count for f in range(count))
    if lyon:
        regions = lyon_regions(spec.objects[0].params, materials, spec.camera.vector, options.max_span_angle_deg)
    else:
        regions = mesh_regions(spec, materials, pose, (min(0.0, degrees), max(0.0, degrees)),
                               float(options.wobble_degrees), still, tilt, ball, options.max_span_angle_deg)
    return Domain(pose=pose, axis=tuple(float(x) for x in spec.frames.axis),
                  degrees=(min(0.0, degrees), max(0.0, degrees)),
                  wobble_degrees=float(options.wobble_degrees), view_cos_min=view_cos_min,
                  max_span_angle_deg=float(span_angle),
                  min_normal_length=math.cos(math.radians(span_angle) / 2), ball=ball,
                  max_span_length=span_length,
                  lights=tuple((light.kind, tuple(light.vector), tuple(light.rgb)) for light in spec.lights),
                  camera=(spec.camera.kind, tuple(spec.camera.vector)),
                  materials=materials, samples=options.samples,
                  final_samples=options.final_samples, seed=options.seed,
                  still_degrees=still,
                  camera_path=tuple(tuple(p) for p in spec.frames.camera_path), face_cap_deg=cap,
                  view_tilt_deg=tilt, derived_span_angle_deg=derived, coefficients=coefficients,
                  bits=spec.output.bits, surface=surface, regions=regions)
