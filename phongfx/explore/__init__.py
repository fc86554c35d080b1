"""Exploring the trade of cost and speed for accuracy.

* :mod:`.synth`: synthesis, place and route (yowasp Yosys + nextpnr, ECP5 and iCE40),
  cached; :mod:`.asic`: standard-cell synthesis (Yosys onto the OSU Liberty cells) and
  static timing (OpenSTA); :mod:`.toolrun`: what both flows share (tool runs, logs,
  the cache); :mod:`.cost_proxy`: tool-free cost estimates from the elaborated RTLIL
  (LUT-eq, and µm² fitted to the standard-cell flow: :mod:`.proxy_table`);
* :mod:`.methods`: the sweepable methods (block, width parameters, how to build and run
  them) and the reference scenes; :mod:`.evaluate`: one method at one width point;
* :mod:`.sweep_spec`, :mod:`.sweep`: TOML grids run on a process pool or Dask, resumable;
* :mod:`.report`: Pareto fronts and the report page; :mod:`.tables`: every
  ``phongfx tables`` name and its module; :mod:`.cost_table`, :mod:`.pipeline_table`,
  :mod:`.extremes`: the synthesized cost, Fmax-against-depth and extremes tables;
* :mod:`.compile`: the scene compiler (the cheapest datapath whose error a scene hides).

May import every layer but ``phongfx.cli``.
"""
