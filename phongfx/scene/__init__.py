"""What is shaded: Lyon's test scene, scene files, meshes, per-frame geometry, span inputs.

* :mod:`.lyon`: the appendix scene of Lyon 1993 (unit spheres, n = 1…256, two lights at
  infinity) and its pixels;
* :mod:`.mesh`: triangle meshes (UV spheres, tori, the 200-frame rotation of Hast et al.)
  and a vectorized scanline rasterizer yielding spans with unit normals at their ends;
* :mod:`.obj`: the Wavefront OBJ reader;
* :mod:`.file`: scene files (TOML) for the scene compiler, validated; :mod:`.requirement`
  their ``[requirement]``: the error allowed and the pixel rate;
* :mod:`.geometry`: one frame of a scene file as the datapaths see it (span ends of N,
  L and V, interpolation amounts);
* :mod:`.domain`: a scene's input domain, every input its hardware can meet while the scene
  plays (poses, normals, spans, positions, n), derived soundly, and :mod:`.sampling`, which
  draws seeded points of it;
* :mod:`.span_inputs`: the per-span setups of the scanline units (Euler, Gouraud,
  spherical, Schlick, Blinn–Phong, Phong) laid out as per-pixel input streams.

May import: ``phongfx.core``, ``phongfx.config``, ``phongfx.golden``.
"""
