"""The scene compiler: the cheapest datapath whose error a scene's viewer cannot see, certified.

* :mod:`.request`: :class:`~.request.CompileRequest`, the scene and every option of a compile,
  checked when made;
* :mod:`.compile`: :func:`~.compile.compile_scene`, which puts together the compile room of
  :mod:`phongfx.explore.compile` (the scene's analysis, the width search, the witness, the
  costing) and the certificates of :mod:`phongfx.certify`.

It sits above :mod:`phongfx.certify`, which bounds a design through the compile room's
fitting of a method to a scene, and below the command line.  From Python::

    from phongfx.compiler import CompileRequest, compile_scene
    from phongfx.explore.compile.emit import emit
    from phongfx.scene.file import load_scene

    compiled = compile_scene(CompileRequest(load_scene("scenes/torus.toml"), methods=["fig7"]))
    emit(compiled, "build/compile/torus")

May import every layer but ``phongfx.cli``.
"""

from .compile import Compiled, compile_scene
from .request import CompileRequest

__all__ = ["CompileRequest", "compile_scene", "Compiled"]
