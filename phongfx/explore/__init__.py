"""Exploring the trade of cost and speed for accuracy.

Its rooms, lowest first; each imports only itself and the rooms before it
(``tests/test_imports.py``'s ``EXPLORE_LAYERS``), and the shared pieces none of each other:

1. the shared pieces: :mod:`.methods`, :mod:`.scene_files`, :mod:`.progress`, :mod:`.cluster`;
2. :mod:`.synth`, which runs its parallel jobs on :mod:`.cluster`;
3. :mod:`.evaluate`, one method at one point, its cost by :mod:`.synth`;
4. :mod:`.sweep`, many points evaluated;
5. :mod:`.tables`, which evaluate, synthesize and rank by the sweep's fronts;
6. :mod:`.report`, which runs the tables and reads the sweeps;
7. :mod:`.compile`, the scene compiler's room, which may use any of them.

What they hold:

* :mod:`.synth`: what a block costs in hardware (FPGA and standard-cell synthesis and
  timing, tool runs, netlist checks, the tool-free cost proxies);
* :mod:`.sweep`: TOML grids of methods and widths run on a process pool or Dask,
  resumable, their Pareto fronts and plots;
* :mod:`.tables`: every ``phongfx tables`` name and the measured tables (cost,
  pipeline, proxy calibration, extremes);
* :mod:`.methods`: the sweepable methods (block, width parameters, how to build and run
  them) and the reference scenes; :mod:`.scene_files`: a user's scene file as such a scene
  (frames and lights pooled); :mod:`.evaluate`: one method at one width point;
* :mod:`.report`: Pareto fronts and the report page; :mod:`.progress`: the progress
  bars of the long runs; :mod:`.cluster`: independent jobs on Dask (the sweeps and the
  parallel synthesis share it);
* :mod:`.compile`: the scene compiler's parts (analysis, measurement, width search, witness,
  costing, the output folder); :mod:`phongfx.compiler`, above :mod:`phongfx.certify`, puts
  them together with the certificates.

May import every layer before it: everything but ``phongfx.certify``, ``phongfx.compiler``
and ``phongfx.cli``.
"""
