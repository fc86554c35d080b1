"""The scene compiler's record of measured widths, so that a rerun resumes where it stopped.

Each width point the search measures costs a render of every frame through the golden
model; an interrupted compile of a large scene would otherwise measure them all again
(the synthesis results are cached on their own, :mod:`phongfx.explore.synth.toolrun`).  A
:class:`Journal` appends one JSON line per measured point, flushed at once, to
``<folder>/<key>.jsonl``; the key covers the scene's frames (every array of every
:class:`~phongfx.scene.geometry.FrameGeometry`), its output bits and requirement, the source
of the package, and the domain sample the points are measured on (the domain, the sample's
size and seed, and every hard point added to it), so a changed scene, a changed domain or a
changed model never reuses a line.  A line torn by an interrupt is ignored.
"""

import dataclasses
import functools
import hashlib
import json
import os
from pathlib import Path

import numpy as np

__all__ = ["Journal", "scene_key", "source_digest"]


@functools.cache
def source_digest():
    """SHA-256 of every Python source of the package (``phongfx``, its ``golden``, ``hdl``
    and ``sim`` parts): a rerun after any code change measures afresh.  Read once per
    process (the sources of a running process do not change under it)."""
    import phongfx
    import phongfx.golden
    import phongfx.hdl
    import phongfx.sim
    from phongfx.hdl.identity import folder_digest

    roots = {Path(m.__file__).parent for m in (phongfx, phongfx.golden, phongfx.hdl, phongfx.sim)}
    return hashlib.sha256("\n".join(f"{root.name}:{folder_digest(root)}" for root in sorted(roots)).encode()).hexdigest()


def _update(h, value):
    if isinstance(value, np.ndarray):
        h.update(str((value.dtype, value.shape)).encode() + np.ascontiguousarray(value).tobytes())
    elif dataclasses.is_dataclass(value):
        for f in dataclasses.fields(value):
            _update(h, getattr(value, f.name))
    elif hasattr(value, "__dict__"):
        for name in sorted(vars(value)):
            _update(h, vars(value)[name])
    else:
        h.update(repr(value).encode())


def scene_key(spec, geometries, domain=None):
    """The journal key of a scene's evaluation (module docstring); ``domain``: the key of
    the domain sample the points are measured on as well
    (:meth:`phongfx.explore.compile.points.DomainPoints.key`), None for none."""
    h = hashlib.sha256(source_digest().encode())
    h.update(repr(domain).encode())
    h.update(repr((spec.output, spec.requirement, spec.materials)).encode())
    for geometry in geometries:
        _update(h, geometry)
    return h.hexdigest()[:20]


class Journal:
    """``<folder>/<key>.jsonl``: :meth:`load` the points measured so far, :meth:`add` one."""

    def __init__(self, folder, key):
        self.path = os.path.join(folder, f"{key}.jsonl")

    def load(self):
        """``{(method, ((name, value), ...)): error dict}`` of the complete lines."""
        out = {}
        try:
            with open(self.path, encoding="utf-8") as file:
                for line in file:
                    try:
                        method, params, error = json.loads(line)
                    except ValueError:
                        continue  # torn by an interrupt
                    out[(method, tuple((k, v) for k, v in params))] = error
        except FileNotFoundError:
            pass
        return out

    def add(self, key, error):
        os.makedirs(os.path.dirname(self.path) or ".", exist_ok=True)
        with open(self.path, "a+b") as file:
            torn = file.tell() > 0 and (file.seek(-1, os.SEEK_END) or file.read(1)) != b"\n"
        with open(self.path, "a", encoding="utf-8") as file:
            file.write("\n" * torn + json.dumps([key[0], [list(p) for p in key[1]], error]) + "\n")
            file.flush()
