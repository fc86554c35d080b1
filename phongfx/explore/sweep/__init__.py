"""Sweeps: methods at many bit widths, their error against their cost, and the fronts.

* :mod:`.spec`: a TOML sweep file (``sweeps/README.md``) to the list of points;
* :mod:`.run`: the points evaluated on a process pool or a Dask cluster, resumable,
  one JSON record each;
* :mod:`.front`: the cost a record is ranked by and the Pareto front;
* :mod:`.plot`: the Pareto plots of the report.
"""

from phongfx.explore.sweep.front import cost_key, pareto
from phongfx.explore.sweep.plot import pareto_plot
from phongfx.explore.sweep.run import load_records, run_sweep, write_csv
from phongfx.explore.sweep.spec import SweepSpecError, expand, load_spec, point_id

__all__ = ["SweepSpecError", "load_spec", "expand", "point_id", "run_sweep", "load_records", "write_csv",
           "cost_key", "pareto", "pareto_plot"]
