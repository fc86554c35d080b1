"""The scene compiler's room: the parts :func:`phongfx.compiler.compile.compile_scene` puts together.

* :mod:`.analysis`: what varies in the scene (local L and V, lights, n, span angles,
  highlights inside spans);
* :mod:`.run`: how each method represents and shades a scene's frame;
* :mod:`.measure`: a width point's error on the frames and the scene's input domain
  (:mod:`.points`: the domain sample; :mod:`.climb`: the local search for the worst input);
* :mod:`.search`: fitting every method, the width search with its local-minimality
  proof; :mod:`.choice`: the choice of the cheapest whose witness meets the requirement
  (:mod:`.witness`), :mod:`.certified` with a certificate too;
* :mod:`.architecture`, :mod:`.costing`, :mod:`.fit`: what a design costs at the speed asked;
* :mod:`.emit`: the output folder (manifest, Verilog, frames, the RTL check).

The compiler itself, :mod:`phongfx.compiler`, sits above :mod:`phongfx.certify`, which
bounds a design through :mod:`.run` and :mod:`.analysis`.  The names below are imported on
first use (so that importing one submodule does not load the others): :func:`analyse` says
what varies in a scene.

May import what :mod:`phongfx.explore` may.
"""

from importlib import import_module

#: public name -> the module it lives in
_HOMES = {"analyse": ".analysis", "Analysis": ".analysis"}
__all__ = list(_HOMES)


def __getattr__(name):
    if name not in _HOMES:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    return getattr(import_module(_HOMES[name], __name__), name)


def __dir__():
    return sorted(set(globals()) | set(_HOMES))
