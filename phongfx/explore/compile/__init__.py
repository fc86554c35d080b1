"""The scene compiler: ``phongfx compile SCENE.toml -o DIR``.

* :mod:`.analysis`: what varies in the scene (local L and V, lights, n, span angles,
  highlights inside spans);
* :mod:`.run`: how each method represents and shades a scene's frame;
* :mod:`.measure`: a width point's error on the frames and the scene's input domain
  (:mod:`.points`: the domain sample; :mod:`.climb`: the local search for the worst input);
* :mod:`.compiler`: fitting every method, the width search with its local-minimality
  proof, the choice of the cheapest whose witness meets the requirement (:mod:`.witness`);
* :mod:`.emit`: the output folder (manifest, Verilog, frames, the RTL check).

The names below are the compiler's entry points from Python, imported on first use (so
that importing one submodule does not load the others): :func:`compile_scene` chooses the
design and :func:`analyse` says what varies in a scene; :func:`.emit.emit` writes the output
folder (it keeps its module's name, so it is not re-exported here)::

    from phongfx.scene.file import load_scene
    from phongfx.explore.compile import compile_scene
    from phongfx.explore.compile.emit import emit

    compiled = compile_scene(load_scene("scenes/torus.toml"), methods=["fig7"])
    emit(compiled, "build/compile/torus")

May import what :mod:`phongfx.explore` may.
"""

from importlib import import_module

#: public name -> the module it lives in
_HOMES = {"compile_scene": ".compiler", "Compiled": ".compiler", "check_methods": ".compiler",
          "analyse": ".analysis", "Analysis": ".analysis"}
__all__ = list(_HOMES)


def __getattr__(name):
    if name not in _HOMES:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    return getattr(import_module(_HOMES[name], __name__), name)


def __dir__():
    return sorted(set(globals()) | set(_HOMES))
