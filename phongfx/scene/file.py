"""Scene files: TOML (README "Scene files") to a checked, frozen :class:`SceneSpec`.

Everything is checked when the file is read, so a bad scene fails before anything is
rendered, with one line naming the file, the field path (``objects[0].polygons``), the
bad value and what is allowed (:class:`SceneError`).  :mod:`phongfx.scene.geometry`
turns a spec into per-frame pixels.
"""

import math
import os
import tomllib
import dataclasses
from dataclasses import dataclass

from .domain import parse_options
from .lyon import Scene
from .mesh import torus, uv_sphere
from .obj import ObjError, load_obj
from .requirement import Requirement, max_error, parse_requirement, throughput

__all__ = ["SceneError", "SceneSpec", "with_requirement", "with_throughput", "Camera", "Light", "Material",
           "SceneObject", "Frames", "Output", "Requirement", "load_scene", "parse_scene", "OBJECT_TYPES"]

N_MAX = 8000
_TOP = ("name", "camera", "lights", "materials", "objects", "frames", "output", "requirement",
        "domain")
#: Keys of each object type besides type, material, scale, offset; and their defaults.
OBJECT_TYPES = {
    "lyon_spheres": {"radius": 32, "shininess": [1, 4, 16, 64, 256], "span": 0},
    "sphere": {"stacks": 8, "slices": 16},
    "torus": {"polygons": 288, "major": 1.0, "minor": 0.4},
    "mesh": {"file": None},  # required
}


class SceneError(ValueError):
    """A scene file that cannot be read or holds a bad field (one line)."""


@dataclass(frozen=True)
class Camera:
    kind: str      # "infinity" (vector: unit direction toward the viewer) | "point" (position)
    vector: tuple


@dataclass(frozen=True)
class Light:
    kind: str      # "directional" (vector: unit direction toward the light) | "point" (position)
    vector: tuple
    #: the light's RGB intensity: ``intensity`` times ``colour`` (each 0..16)
    rgb: tuple = (1.0, 1.0, 1.0)

    @property
    def intensity(self):
        """The mean of :attr:`rgb`: the light's grey level."""
        return sum(self.rgb) / 3


@dataclass(frozen=True)
class Material:
    kd: float
    ks: float
    n_lo: int = None   # None: no n (only lyon_spheres objects, which carry their own)
    n_hi: int = None
    ka: float = 0.0    # ambient: ka·colour is added to every pixel of the material
    colour: tuple = (1.0, 1.0, 1.0)  # RGB, each 0..1: scales ambient, diffuse and specular


@dataclass(frozen=True)
class SceneObject:
    kind: str
    material: str
    params: dict


@dataclass(frozen=True)
class Frames:
    count: int = 1
    axis: tuple = (0.0, 1.0, 0.0)
    degrees: float = 0.0
    #: the local camera's position in each frame (empty: ``camera.position`` throughout)
    camera_path: tuple = ()


@dataclass(frozen=True)
class Output:
    width: int = 128
    height: int = 128
    bits: int = 8


@dataclass(frozen=True)
class SceneSpec:
    name: str
    path: str
    camera: Camera
    lights: tuple
    materials: dict
    objects: tuple
    frames: Frames
    output: Output
    requirement: Requirement
    #: the checked ``[domain]`` table (:class:`phongfx.scene.domain.Options`; None: every default)
    domain: object = None

    @property
    def local_lights(self):
        return any(light.kind == "point" for light in self.lights)

    @property
    def local_viewer(self):
        return self.camera.kind == "point"

    @property
    def shininess(self):
        values = set()
        for obj in self.objects:
            if obj.kind == "lyon_spheres":
                values.update(obj.params["shininess"])
            else:
                material = self.materials[obj.material]
                values.update((material.n_lo, material.n_hi))
        return tuple(sorted(values))


class _Reader:
    """Checks of one file's fields; every error is prefixed with the file's name."""

    def __init__(self, where):
        self.where = where

    def fail(self, message):
        raise SceneError(f"{self.where}: {message}")

    def table(self, value, field, allowed, required=()):
        if not isinstance(value, dict):
            self.fail(f"{field} must be a table, not {value!r}")
        for key in value:
            if key not in allowed:
                self.fail(f"{field}: unknown key {key!r}; allowed: {', '.join(allowed)}")
        for key in required:
            if key not in value:
                self.fail(f"{field}.{key} is missing")
        return value

    def integer(self, value, field, lo, hi):
        if isinstance(value, bool) or not isinstance(value, int) or not lo <= value <= hi:
            self.fail(f"{field} must be an integer in {lo}..{hi}, not {value!r}")
        return value

    def number(self, value, field, lo, hi, open_lo=False):
        ok = not isinstance(value, bool) and isinstance(value, (int, float)) and math.isfinite(value)
        if not ok or not (lo < value if open_lo else lo <= value) or value > hi:
            self.fail(f"{field} must be a number in {'(' if open_lo else '['}{lo}, {hi}], "
                      f"not {value!r}")
        return float(value)

    def vector(self, value, field, nonzero=True):
        if (not isinstance(value, list) or len(value) != 3
                or not all(not isinstance(x, bool) and isinstance(x, (int, float))
                           and math.isfinite(x) for x in value)):
            self.fail(f"{field} must be 3 numbers, not {value!r}")
        if nonzero and not any(value):
            self.fail(f"{field} must be a nonzero vector (a direction), not {value!r}")
        return tuple(float(x) for x in value)

    def colour(self, value, field, hi):
        """An RGB triple, each in 0..hi, from ``[r, g, b]`` or one number (grey)."""
        if isinstance(value, list):
            if len(value) != 3:
                self.fail(f"{field} must be a number or [r, g, b], not {value!r}")
            return tuple(self.number(x, f"{field}[{i}]", 0, hi) for i, x in enumerate(value))
        grey = self.number(value, field, 0, hi)
        return (grey, grey, grey)

    def unit(self, value, field):
        v = self.vector(value, field)
        length = math.sqrt(sum(x * x for x in v))
        return tuple(x / length for x in v)

    def n(self, value, field):
        if isinstance(value, list):
            if len(value) != 2:
                self.fail(f"{field} must be an integer in 1..{N_MAX} or a range [lo, hi], not {value!r}")
            lo, hi = (self.integer(x, field, 1, N_MAX) for x in value)
            if lo > hi:
                self.fail(f"{field} must be a range [lo, hi] with lo <= hi, not {value!r}")
            return lo, hi
        value = self.integer(value, field, 1, N_MAX)
        return value, value


def _camera(r, data):
    data = r.table(data, "camera", ("at", "direction", "position"))
    if "position" in data:
        if "at" in data or "direction" in data:
            r.fail("camera must have either position (local) or at/direction (at infinity), "
                   f"not both: {sorted(data)}")
        return Camera("point", r.vector(data["position"], "camera.position", nonzero=False))
    if data.get("at", "infinity") != "infinity":
        r.fail(f"camera.at must be \"infinity\" (or give camera.position), not {data['at']!r}")
    return Camera("infinity", r.unit(data.get("direction", [0, 0, 1]), "camera.direction"))


def _light(r, data, field):
    data = r.table(data, field, ("direction", "position", "intensity", "colour", "color"))
    kinds = [key for key in ("direction", "position") if key in data]
    if len(kinds) != 1:
        r.fail(f"{field} must have exactly one of direction (at infinity) or position (local), "
               f"not {kinds or 'neither'}")
    if "colour" in data and "color" in data:
        r.fail(f"{field} must have at most one of colour, color, not both")
    intensity = r.number(data.get("intensity", 1.0), f"{field}.intensity", 0, 16)
    key = "color" if "color" in data else "colour"
    colour = r.colour(data.get(key, 1.0), f"{field}.{key}", 16)
    rgb = tuple(intensity * c for c in colour)
    if max(rgb) > 16:
        r.fail(f"{field}: intensity × {key} must be at most 16 in each channel, not {list(rgb)}")
    if kinds[0] == "direction":
        return Light("directional", r.unit(data["direction"], f"{field}.direction"), rgb)
    return Light("point", r.vector(data["position"], f"{field}.position", nonzero=False), rgb)


def _material(r, data, field):
    data = r.table(data, field, ("kd", "ks", "ka", "n", "colour", "color"), ("kd", "ks"))
    kd, ks = r.number(data["kd"], f"{field}.kd", 0, 1), r.number(data["ks"], f"{field}.ks", 0, 1)
    ka = r.number(data.get("ka", 0.0), f"{field}.ka", 0, 1)
    if "colour" in data and "color" in data:
        r.fail(f"{field} must have at most one of colour, color, not both")
    key = "color" if "color" in data else "colour"
    colour = r.colour(data.get(key, 1.0), f"{field}.{key}", 1)
    n = r.n(data["n"], f"{field}.n") if "n" in data else (None, None)
    return Material(kd, ks, *n, ka=ka, colour=colour)


def _object(r, data, field, materials, base_dir):
    if not isinstance(data, dict):
        r.fail(f"{field} must be a table, not {data!r}")
    kind = data.get("type")
    if kind not in OBJECT_TYPES:
        r.fail(f"{field}.type must be one of {', '.join(OBJECT_TYPES)}, not {kind!r}")
    defaults = OBJECT_TYPES[kind]
    r.table(data, field, ("type", "material", "scale", "offset") + tuple(defaults),
            ("material", "file") if kind == "mesh" else ("material",))
    material = data["material"]
    if material not in materials:
        r.fail(f"{field}.material must name a [materials] table ({', '.join(materials) or 'none'}), "
               f"not {material!r}")
    if kind != "lyon_spheres" and materials[material].n_lo is None:
        r.fail(f"materials.{material}.n is missing (needed by {field}, type {kind!r})")
    params = {"scale": r.number(data.get("scale", 1.0), f"{field}.scale", 0, 1e6, open_lo=True),
              "offset": r.vector(data.get("offset", [0, 0, 0]), f"{field}.offset", nonzero=False)}
    value = {**defaults, **data}
    if kind == "lyon_spheres":
        shininess = value["shininess"]
        if not isinstance(shininess, list) or not 1 <= len(shininess) <= 16:
            r.fail(f"{field}.shininess must be a list of 1..16 integers, not {shininess!r}")
        params.update(radius=r.integer(value["radius"], f"{field}.radius", 4, 2048),
                      shininess=tuple(r.integer(n, f"{field}.shininess", 1, N_MAX) for n in shininess),
                      span=r.integer(value["span"], f"{field}.span", 0, 2048))
    elif kind == "sphere":
        params.update(stacks=r.integer(value["stacks"], f"{field}.stacks", 2, 512),
                      slices=r.integer(value["slices"], f"{field}.slices", 3, 1024))
        params["mesh"] = uv_sphere(params["stacks"], params["slices"])
    elif kind == "torus":
        params.update(polygons=value["polygons"],
                      major=r.number(value["major"], f"{field}.major", 0, 1e6, open_lo=True),
                      minor=r.number(value["minor"], f"{field}.minor", 0, 1e6, open_lo=True))
        if isinstance(params["polygons"], int) and params["polygons"] > 2 * 512 ** 2:
            r.fail(f"{field}.polygons must be at most {2 * 512 ** 2}, not {params['polygons']!r}")
        try:  # the mesh's own check says what polygons and radii may be
            params["mesh"] = torus(params["polygons"], params["major"], params["minor"])
        except ValueError as error:
            r.fail(f"{field}.{error}")
    else:
        if not isinstance(value["file"], str) or not value["file"]:
            r.fail(f"{field}.file must be the path of an OBJ file, not {value['file']!r}")
        path = os.path.join(base_dir, value["file"])
        if not os.path.isfile(path):
            r.fail(f"{field}.file: no such file {value['file']!r} (looked in {base_dir or '.'})")
        try:
            params["mesh"] = load_obj(path)
        except ObjError as error:
            r.fail(f"{field}.file: {error}")
        params["file"] = os.path.abspath(path)
    return SceneObject(kind, material, params)


def parse_scene(source, name=None, base_dir=".", path=None):
    """The :class:`SceneSpec` of a TOML string or an already-parsed dict.

    ``name`` is the default scene name and, with ``path``, what error messages start
    with; ``base_dir`` is where mesh files are looked for.
    """
    where = os.fspath(path) if path is not None else (name or "scene")
    r = _Reader(where)
    if isinstance(source, str):
        try:
            source = tomllib.loads(source)
        except tomllib.TOMLDecodeError as error:
            r.fail(f"invalid TOML: {error}")
    data = r.table(source, "scene", _TOP, ("lights", "materials", "objects"))
    scene_name = data.get("name", name or "scene")
    if not isinstance(scene_name, str) or not scene_name:
        r.fail(f"name must be a non-empty string, not {scene_name!r}")
    camera = _camera(r, data.get("camera", {}))
    lights = data["lights"]
    if not isinstance(lights, list) or not 1 <= len(lights) <= 8:
        r.fail(f"lights must be an array of 1..8 tables ([[lights]]), not {lights!r}")
    lights = tuple(_light(r, light, f"lights[{i}]") for i, light in enumerate(lights))
    materials = r.table(data["materials"], "materials", tuple(data["materials"])
                        if isinstance(data["materials"], dict) else ())
    if not materials:
        r.fail("materials must hold at least one [materials.NAME] table, not {}")
    materials = {key: _material(r, value, f"materials.{key}") for key, value in materials.items()}
    objects = data["objects"]
    if not isinstance(objects, list) or not 1 <= len(objects) <= 64:
        r.fail(f"objects must be an array of 1..64 tables ([[objects]]), not {objects!r}")
    objects = tuple(_object(r, obj, f"objects[{i}]", materials, base_dir)
                    for i, obj in enumerate(objects))
    frames = r.table(data.get("frames", {}), "frames", ("count", "axis", "degrees", "camera_path"))
    count = r.integer(frames.get("count", 1), "frames.count", 1, 1000)
    camera_path = frames.get("camera_path", [])
    if camera_path and camera.kind != "point":
        r.fail("frames.camera_path moves a local camera: give camera.position, not a camera at infinity")
    if not isinstance(camera_path, list) or (camera_path and len(camera_path) != count):
        r.fail(f"frames.camera_path must be an array of frames.count = {count} positions, "
               f"not {camera_path!r}")
    frames = Frames(count, r.unit(frames.get("axis", [0, 1, 0]), "frames.axis"),
                    r.number(frames.get("degrees", 0.0), "frames.degrees", -3600, 3600),
                    tuple(r.vector(v, f"frames.camera_path[{i}]", nonzero=False)
                          for i, v in enumerate(camera_path)))
    options = parse_options(r, data.get("domain", {}), count)
    output = r.table(data.get("output", {}), "output", ("width", "height", "bits"))
    size = {}
    if any(obj.kind == "lyon_spheres" for obj in objects):
        if len(objects) > 1:
            r.fail(f"objects: lyon_spheres must be the only object (it has its own image), "
                   f"not one of {len(objects)}")
        p = objects[0].params
        lyon = Scene(p["radius"], p["shininess"], span=p["span"])
        size = {"width": lyon.width, "height": lyon.height}
        for key, value in size.items():
            if output.get(key, value) != value:
                r.fail(f"output.{key} must be {value} (Lyon's image for radius {p['radius']} and "
                       f"{len(p['shininess'])} spheres) or left out, not {output[key]!r}")
    output = Output(r.integer(output.get("width", size.get("width", 128)), "output.width", 8, 4096),
                    r.integer(output.get("height", size.get("height", 128)), "output.height", 8, 4096),
                    r.integer(output.get("bits", 8), "output.bits", 1, 16))
    requirement = parse_requirement(r, data.get("requirement", {}))
    return SceneSpec(scene_name, None if path is None else os.fspath(path), camera, lights,
                     materials, objects, frames, output, requirement, options)


def with_requirement(spec, max_error_levels):
    """``spec`` with ``requirement.max_error_levels`` replaced (``phongfx compile --max-error``),
    checked as the file's own value is."""
    value = max_error(_Reader("--max-error"), max_error_levels, "max_error_levels")
    return dataclasses.replace(spec, requirement=dataclasses.replace(spec.requirement, max_error_levels=value))


def with_throughput(spec, mpixels_per_second):
    """``spec`` with its pixel rate requirement replaced (``phongfx compile --throughput``),
    checked as the file's own ``requirement.mpixels_per_second`` is."""
    value = throughput(_Reader("--throughput"), mpixels_per_second, "throughput")
    return dataclasses.replace(spec, requirement=dataclasses.replace(spec.requirement, mpixels_per_second=value,
                                                                     display=None))


def load_scene(path):
    """The :class:`SceneSpec` of the TOML file ``path`` (:func:`parse_scene`)."""
    where = os.fspath(path)
    try:
        with open(path, "rb") as file:
            text = file.read().decode("utf-8")
    except OSError as error:
        raise SceneError(f"{where}: cannot read: {error.strerror}") from None
    except UnicodeDecodeError as error:
        raise SceneError(f"{where}: not UTF-8 text: {error.reason} at byte {error.start}") from None
    stem = os.path.splitext(os.path.basename(where))[0]
    return parse_scene(text, name=stem, base_dir=os.path.dirname(where), path=where)
