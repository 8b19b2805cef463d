"""Design sweeps: many designs of one topology, evaluated at once.

* :mod:`~linkage_sym.design.parameters` -- the design space (grid, samples, Monte Carlo);
* :mod:`~linkage_sym.design.evaluate` -- the compiled mechanism's functions on chunks of
  designs x steps;
* :mod:`~linkage_sym.design.newton_groups` -- designs whose groups have no closed form,
  one at a time by the numeric plan;
* :mod:`~linkage_sym.design.metrics` -- what is reported per design;
* :mod:`~linkage_sym.design.execute` -- in-process, local processes or Dask;
* :mod:`~linkage_sym.design.scenes` -- each design as a scene of its own;
* :mod:`~linkage_sym.design.table` -- the table, CSV or Parquet;
* :mod:`~linkage_sym.design.plots` -- design maps and histograms;
* ``linkage-sym sweep`` reads its options in :mod:`linkage_sym.cli.sweep`.
"""

from linkage_sym.design.api import scene_parameters, sweep
from linkage_sym.design.errors import SweepError
from linkage_sym.design.metrics import DEFAULT_METRICS, METRICS
from linkage_sym.design.parameters import Designs, grid, monte_carlo, read_samples
from linkage_sym.design.table import SweepResult

__all__ = ["DEFAULT_METRICS", "METRICS", "Designs", "SweepError", "SweepResult", "grid",
           "monte_carlo", "read_samples", "scene_parameters", "sweep"]
