"""The scene compiler: ``phongfx compile SCENE.toml -o DIR``.

* :mod:`.analysis`: what varies in the scene (local L and V, lights, n, span angles,
  highlights inside spans);
* :mod:`.run`: how each method represents and shades a scene's frame;
* :mod:`.compiler`: fitting every method, the width search with its local-minimality
  proof, the choice of the cheapest;
* :mod:`.emit`: the output folder (manifest, Verilog, frames, the RTL check).

May import what :mod:`phongfx.explore` may.
"""
