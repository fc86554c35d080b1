"""Reading a compiled output folder's ``manifest.json`` back: its version, its design, its config.

``phongfx compile`` writes ``DIR/manifest.json`` (:mod:`phongfx.explore.compile.emit`); what a
design needs to be built again is in three of its fields: ``"block"`` (the registry block,
``"shader"``), ``"module"`` (the Verilog name, ``<scene>_<method>``) and ``"config"`` (the
block's configuration as :func:`dataclasses.asdict` wrote it: nested dicts, tuples as lists).
:func:`config_from_dict` turns the last into the config object again, each nested dict into
the class its template field holds (a :class:`~phongfx.config.ShaderConfig`'s ``units`` into
the config class of its ``unit``'s registry block), every list into a tuple, and lets the
config's own checks validate the result.

A manifest carries :data:`MANIFEST_VERSION` in ``"manifest_version"``; one of another
version (or without it: written before the field existed) is refused rather than guessed
at.  Version 2: ``"path"`` (the scene file) is relative to the manifest's folder, so the
folder reads the same from any working directory (:func:`scene_file`), and ``"certified"``
says whether the design's error is certified (``"certificate"``: its bound).  Every refusal
is a :class:`ManifestError` naming the file, the field, the value and what was expected.
"""

import dataclasses
import json
import os

from phongfx.config import BlockConfig, ShaderConfig
from phongfx.core.registry import REGISTRY

__all__ = ["MANIFEST_VERSION", "ManifestError", "manifest_path", "read_manifest", "check_version", "design_of",
           "scene_file", "config_from_dict"]

#: The version of the manifest's layout that this module reads (the manifest's ``"manifest_version"``).
MANIFEST_VERSION = 2


class ManifestError(ValueError):
    """A compiled folder or manifest that cannot give a design: the message names the file and field."""


def manifest_path(folder):
    """``folder/manifest.json``, or ``folder`` itself when it names a ``manifest.json``."""
    folder = os.fspath(folder)
    return folder if os.path.basename(folder) == "manifest.json" else os.path.join(folder, "manifest.json")


def read_manifest(folder):
    """The manifest dict of the compiled output folder ``folder`` (or of a ``manifest.json`` path),
    checked for its version; :class:`ManifestError` if it is missing, unreadable or of another version."""
    path = manifest_path(folder)
    if not os.path.isfile(path):
        if not os.path.isdir(os.path.dirname(path) or "."):
            raise ManifestError(f"{path}: no such folder: give the output folder of 'phongfx compile -o FOLDER'")
        raise ManifestError(f"{path}: no manifest.json: not the output folder of 'phongfx compile -o FOLDER'")
    try:
        with open(path, encoding="utf-8") as file:
            data = json.load(file)
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as error:
        raise ManifestError(f"{path}: not a readable JSON manifest: {error}") from None
    if not isinstance(data, dict):
        raise ManifestError(f"{path}: a manifest is a JSON object, not {type(data).__name__}")
    check_version(data, path)
    return data


def check_version(data, where="manifest"):
    """Raise :class:`ManifestError` unless ``data["manifest_version"]`` is :data:`MANIFEST_VERSION`."""
    version = data.get("manifest_version")
    if version != MANIFEST_VERSION:
        found = "absent (written by a phongfx before manifests had versions)" if version is None else repr(version)
        raise ManifestError(f"{where}: field 'manifest_version' is {found}; this phongfx reads version "
                            f"{MANIFEST_VERSION}: compile the scene again")


def design_of(data, where="manifest"):
    """``(block name, module name, config)`` of a manifest dict; :class:`ManifestError` for a
    manifest of a compile that found no design, or a field that cannot be read."""
    check_version(data, where)
    if data.get("config") is None:
        refused = data.get("refused")
        why = "; ".join(refused.get("text") or []) if isinstance(refused, dict) else ""
        why = why or "no method met the error requirement"
        raise ManifestError(f"{where}: field 'config' is absent: the compile of scene {data.get('scene')!r} "
                            f"found no design ({why}; 'chosen' is {data.get('chosen')!r}), so there is no core")
    block, module = data.get("block"), data.get("module")
    if block not in REGISTRY:
        raise ManifestError(f"{where}: field 'block' must be a registered block ({', '.join(REGISTRY)}), "
                            f"not {block!r}")
    if not isinstance(module, str) or not module.isidentifier():
        raise ManifestError(f"{where}: field 'module' must be a Verilog identifier, not {module!r}")
    try:
        config = config_from_dict(REGISTRY[block].default_config(), data["config"], "config")
    except (TypeError, ValueError) as error:
        raise ManifestError(f"{where}: {error}") from None
    return block, module, config


def scene_file(data, folder):
    """The scene file a manifest dict ``data`` of the compiled folder ``folder`` was compiled
    from (its ``"path"``, relative to the folder), as a path from the working directory;
    :class:`ManifestError` when the manifest names none or the file is not there any more."""
    where = manifest_path(folder)
    path = data.get("path")
    if not isinstance(path, str) or not path:
        raise ManifestError(f"{where}: field 'path' must name the scene file, not {path!r}")
    found = os.path.normpath(os.path.join(os.path.dirname(where), path))
    if not os.path.isfile(found):
        raise ManifestError(f"{where}: field 'path' is {path!r} (relative to the manifest's folder): the scene file "
                            f"{found} is not there any more")
    return found


def config_from_dict(template, data, field="config"):
    """The config of ``template``'s class from ``data`` (:func:`dataclasses.asdict` of one):
    every field present, none unknown; nested dicts become the class of ``template``'s field.
    ValueError naming the dotted ``field`` on a missing, unknown or rejected value."""
    kind = type(template)
    if not isinstance(data, dict):
        raise ValueError(f"field {field!r} must be an object of {kind.__name__}'s fields, not {data!r}")
    names = [f.name for f in dataclasses.fields(kind)]
    missing = [name for name in names if name not in data]
    unknown = sorted(set(data) - set(names))
    if missing or unknown:
        parts = ([f"lacks {', '.join(missing)}"] if missing else []) + (
            [f"has unknown {', '.join(unknown)}"] if unknown else [])
        raise ValueError(f"field {field!r} ({kind.__name__}) {' and '.join(parts)}")
    values = {}
    for name in names:
        inner = getattr(template, name)
        if isinstance(template, ShaderConfig) and name == "units":
            unit = data.get("unit")
            if unit not in REGISTRY:
                raise ValueError(f"field '{field}.unit' must be a registered block, not {unit!r}")
            inner = (REGISTRY[unit].default_config(),)
        values[name] = _value(inner, data[name], f"{field}.{name}")
    try:
        return kind(**values)
    except (TypeError, ValueError) as error:
        raise ValueError(f"field {field!r}: {error}") from None


def _value(template, value, field):
    """``value`` read as the kind of ``template``: a config for a config, tuples for lists (a
    tuple template's first item is the template of every item)."""
    if isinstance(template, BlockConfig):
        return config_from_dict(template, value, field)
    if isinstance(value, list):
        item = template[0] if isinstance(template, tuple) and template else None
        return tuple(_value(item, v, f"{field}[{i}]") for i, v in enumerate(value))
    return value
