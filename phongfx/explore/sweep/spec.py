"""Sweep specs: TOML (see ``sweeps/README.md``) to the list of points to evaluate.

A spec names reference scenes, optional synthesis options, the target whose tool-free
cost proxy prices the points that are not synthesized (``proxy``), and ``[[grid]]`` tables
(the cartesian product of their lists) or ``[[points]]`` tables (one point each)
over the methods of :mod:`phongfx.explore.evaluate`.  Everything is checked when the spec is
read, each point against its method's ranges, so a bad spec fails before anything
runs, with one line naming the field, the bad value and the allowed range
(:class:`SweepSpecError`).  :mod:`phongfx.explore.sweep.run` runs the points.
"""

import hashlib
import itertools
import json
import os
import tomllib

__all__ = ["SweepSpecError", "load_spec", "expand", "point_id", "is_int"]

_TOP_KEYS = ("scenes", "synth", "proxy", "grid", "points")
_SYNTH_KEYS = ("target", "freq", "device", "seed")


class SweepSpecError(ValueError):
    """A sweep spec that cannot be read or names something that does not exist."""


def _catalog():
    """(methods, scene names) of :mod:`phongfx.explore.methods`, imported when first needed."""
    from phongfx.core.methods import METHODS
    from phongfx.explore.methods import SCENES
    return METHODS, tuple(SCENES)


def is_int(value):
    return isinstance(value, int) and not isinstance(value, bool)


def _check_scenes(value, where, known, base_dir="."):
    """``(labels, files)``: the metric names of the scenes (a built-in name, or a scene file's
    stem) and ``{label: absolute path}`` of the files among them, resolved from ``base_dir``
    (the sweep file's folder) and checked (:func:`~phongfx.explore.scene_files.check_scene_file`)."""
    from phongfx.explore.scene_files import check_scene_file, is_scene_file, scene_label
    allowed = f"scenes: {', '.join(known)}, or a scene file (.toml) relative to the sweep file"
    if not isinstance(value, list) or not value or not all(isinstance(s, str) for s in value):
        raise SweepSpecError(f"{where} must be a non-empty list of scene names, not {value!r}; {allowed}")
    labels, files = [], {}
    for index, scene in enumerate(value):
        if scene in known:
            label = scene
        elif is_scene_file(scene):
            path = os.path.abspath(os.path.join(base_dir, scene))
            if not os.path.isfile(path):
                raise SweepSpecError(f"{where}[{index}]: no scene file {scene!r} (looked for {path}); {allowed}")
            try:
                check_scene_file(path)
            except ValueError as error:
                raise SweepSpecError(f"{where}[{index}] {scene!r}: {error}") from None
            label = scene_label(path)
            files[label] = path
        else:
            raise SweepSpecError(f"{where}: unknown scene {scene!r}; {allowed}")
        if label in labels:
            raise SweepSpecError(f"{where}[{index}]: {scene!r} names its metrics {label!r} as an earlier "
                                 f"scene does; rename the file")
        labels.append(label)
    return tuple(labels), files


def _check_synth(value, where):
    from phongfx.explore.synth.asic import LIBRARIES, is_liberty_path
    from phongfx.explore.synth.fpga import ALL_TARGETS, TARGETS
    if not isinstance(value, dict):
        raise SweepSpecError(f"{where} must be a table with keys {', '.join(_SYNTH_KEYS)}, "
                             f"not {value!r}")
    for key in value:
        if key not in _SYNTH_KEYS:
            raise SweepSpecError(f"{where}: unknown key {key!r}; keys: {', '.join(_SYNTH_KEYS)}")
    target, freq = value.get("target", "ecp5"), value.get("freq", 150)
    if target not in ALL_TARGETS:
        raise SweepSpecError(f"{where}.target must be one of {', '.join(ALL_TARGETS)}, not {target!r}")
    if isinstance(freq, bool) or not isinstance(freq, (int, float)) or not 0 < freq <= 1000:
        raise SweepSpecError(f"{where}.freq must be a number of MHz in (0, 1000], not {freq!r}")
    options = {"target": target, "freq": freq}
    if "device" in value:  # on asic the standard-cell library: a name or a Liberty file's path
        devices = LIBRARIES if target == "asic" else TARGETS[target].devices
        liberty = target == "asic" and is_liberty_path(value["device"])
        if value["device"] not in devices and not liberty:
            raise SweepSpecError(f"{where}.device must be one of {', '.join(devices)}"
                                 f"{' or a Liberty file' if target == 'asic' else ''} for {target}, "
                                 f"not {value['device']!r}")
        if liberty:
            from phongfx.explore.synth.liberty import LibertyError, read_liberty
            try:
                read_liberty(value["device"])
            except LibertyError as error:
                raise SweepSpecError(f"{where}.device: {error}") from None
        options["device"] = value["device"]
    if "seed" in value:
        if not is_int(value["seed"]) or value["seed"] < 0:
            raise SweepSpecError(f"{where}.seed must be a non-negative integer, not {value['seed']!r}")
        options["seed"] = value["seed"]
    return options


def _check_value(value, default, where):
    """``value`` if it has the type of the method's ``default``; why not otherwise."""
    if isinstance(default, bool):
        ok, kind = isinstance(value, bool), "a boolean"
    elif is_int(default):
        ok, kind = is_int(value), "an integer"
    elif isinstance(default, float):
        ok, kind = is_int(value) or isinstance(value, float), "a number"
    else:
        ok, kind = isinstance(value, type(default)), f"a {type(default).__name__}"
    if not ok:
        raise SweepSpecError(f"{where} must be {kind}, not {value!r}")
    return value


def _entry(table, where, kind, methods, scenes, synth, known_scenes, proxy=None, base_dir="."):
    """The points of one ``[[grid]]`` or ``[[points]]`` table."""
    if not isinstance(table, dict):
        raise SweepSpecError(f"{where} must be a table, not {table!r}")
    name = table.get("method")
    if name is None:
        raise SweepSpecError(f"{where}.method is missing; methods: {', '.join(methods)}")
    if name not in methods:
        raise SweepSpecError(f"{where}.method: unknown method {name!r}; methods: {', '.join(methods)}")
    spec = methods[name]
    if "scenes" in table:
        scenes = _check_scenes(table["scenes"], f"{where}.scenes", known_scenes, base_dir)
    if "synth" in table:
        option = table["synth"]
        if isinstance(option, bool):
            if option and synth is None:
                raise SweepSpecError(f"{where}.synth = true needs a top-level [synth] table "
                                     f"(or give the options here as a table)")
            synth = synth if option else None
        else:
            synth = _check_synth(option, f"{where}.synth")
    axes = {}
    for key, value in table.items():
        if key in ("method", "scenes", "synth"):
            continue
        if key not in spec.params:
            raise SweepSpecError(f"{where} ({name}): unknown parameter {key!r}; "
                                 f"parameters: {', '.join(spec.params)}")
        field = f"{where}.{key}"
        if kind == "grid" and isinstance(value, list):
            if not value:
                raise SweepSpecError(f"{field} must be a non-empty list, not []")
            axes[key] = [_check_value(v, spec.params[key], f"{field}[{i}]") for i, v in enumerate(value)]
        else:
            axes[key] = [_check_value(value, spec.params[key], field)]
    points = []
    for combo in itertools.product(*axes.values()):
        params = {**spec.params, **dict(zip(axes, combo))}
        try:
            spec.config(params)
        except ValueError as error:
            raise SweepSpecError(f"{where} ({name}, {_brief(dict(zip(axes, combo)))}): {error}") from None
        points.append(_point(name, params, scenes, synth, proxy))
    return points


def _brief(params):
    return " ".join(f"{k}={v}" for k, v in params.items()) or "defaults"


def point_id(method, params, scenes, synth, files=None):
    """A point's identity: sha256 of method, sorted params, scenes and synth options, 16 hex
    digits; with scene ``files`` (``{label: path}``) their contents too, so an edited scene
    file runs again (without, the hash is what it always was: old sweeps resume)."""
    from phongfx.explore.scene_files import file_digest
    fields = {"method": method, "params": params, "scenes": list(scenes), "synth": synth}
    if files:
        fields["scene_files"] = {label: file_digest(path) for label, path in files.items()}
    key = json.dumps(fields, sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(key.encode()).hexdigest()[:16]


def _point(method, params, scenes, synth, proxy=None):
    # the proxy is not part of the identity: a point's error does not depend on it
    labels, files = scenes
    point = {"id": point_id(method, params, labels, synth, files), "method": method, "params": params,
             "scenes": list(labels), "synth": synth, "proxy": None if synth else proxy}
    if files:
        point["scene_files"] = dict(files)
    return point


def _check_proxy(value, where, synth):
    """The target whose tool-free proxy costs the points that are not synthesized: ``value``
    (a target, or false for none), by default the ``[synth]`` target, else ``ecp5``."""
    from phongfx.explore.synth.fpga import ALL_TARGETS
    if value is None:
        return (synth or {}).get("target", "ecp5")
    if value is False:
        return None
    if value not in ALL_TARGETS:
        raise SweepSpecError(f"{where} must be one of {', '.join(ALL_TARGETS)} or false, not {value!r}")
    return value


def load_spec(spec):
    """A sweep spec, checked: a TOML file's path, or the same content as a dict.

    Returns ``{"scenes": tuple, "synth": dict | None, "points": [point, ...]}``, the
    points expanded and without duplicates (each a dict with ``id``, ``method``,
    ``params`` (every parameter of the method, defaults filled in), ``scenes`` (the names
    their metrics carry), ``synth``, and ``scene_files`` ``{name: absolute path}`` where
    scene files were given, resolved from the spec file's folder (a dict spec: the
    working directory)).

    Raises
    ------
    SweepSpecError
        A missing file, malformed TOML (tomllib's message, with its line), or a bad
        field: the message names the field, the bad value and what is allowed.
    """
    if isinstance(spec, dict):
        where, data, base_dir = "sweep spec", spec, "."
    else:
        where, base_dir = f"sweep spec {os.fspath(spec)}", os.path.dirname(os.fspath(spec))
        try:
            with open(spec, "rb") as file:
                data = tomllib.load(file)
        except FileNotFoundError:
            raise SweepSpecError(f"{where}: no such file") from None
        except tomllib.TOMLDecodeError as error:
            raise SweepSpecError(f"{where}: invalid TOML: {error}") from None
    methods, known_scenes = _catalog()
    for key in data:
        if key not in _TOP_KEYS:
            raise SweepSpecError(f"{where}: unknown key {key!r}; keys: {', '.join(_TOP_KEYS)}")
    scenes = _check_scenes(data.get("scenes", ["torus", "sphere"]), f"{where}: scenes", known_scenes, base_dir)
    synth = _check_synth(data["synth"], f"{where}: synth") if "synth" in data else None
    proxy = _check_proxy(data.get("proxy"), f"{where}: proxy", synth)
    points = {}
    for kind in ("grid", "points"):
        tables = data.get(kind, [])
        if not isinstance(tables, list):
            raise SweepSpecError(f"{where}: {kind} must be an array of tables ([[{kind}]]), not {tables!r}")
        for index, table in enumerate(tables):
            for point in _entry(table, f"{where}: {kind}[{index}]", kind, methods, scenes, synth,
                                known_scenes, proxy, base_dir):
                points.setdefault(point["id"], point)
    if not points:
        raise SweepSpecError(f"{where}: no points; add a [[grid]] or [[points]] table")
    return {"scenes": scenes[0], "synth": synth, "proxy": proxy, "points": list(points.values())}


def expand(spec):
    """The points of ``spec`` (a path or a dict), as :func:`load_spec` returns them."""
    return load_spec(spec)["points"]
