"""Exploring the trade of cost and speed for accuracy.

Three rooms and the pieces they share:

* :mod:`.synth`: what a block costs in hardware (FPGA and standard-cell synthesis and
  timing, tool runs, netlist checks, the tool-free cost proxies);
* :mod:`.sweep`: TOML grids of methods and widths run on a process pool or Dask,
  resumable, their Pareto fronts and plots;
* :mod:`.tables`: every ``phongfx tables`` name and the measured tables (cost,
  pipeline, proxy calibration, extremes);
* :mod:`.methods`: the sweepable methods (block, width parameters, how to build and run
  them) and the reference scenes; :mod:`.evaluate`: one method at one width point;
* :mod:`.report`: Pareto fronts and the report page; :mod:`.progress`: the progress
  bars of the long runs; :mod:`.cluster`: independent jobs on Dask (the sweeps and the
  parallel synthesis share it);
* :mod:`.compile`: the scene compiler (the cheapest datapath whose error a scene hides).

May import every layer but ``phongfx.cli``.
"""
