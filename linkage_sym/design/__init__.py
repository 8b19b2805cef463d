"""Design sweeps: many designs of one topology, evaluated at once.

* :mod:`~linkage_sym.design.api` -- :func:`sweep`: ``sweep(scene, parameters, metrics)``,
  with :class:`MonteCarlo`, :class:`SceneFiles` and :class:`Execution` for what a grid
  does not say;
* :mod:`~linkage_sym.design.parameters` -- the design space (grid, samples, Monte Carlo);
* :mod:`~linkage_sym.design.evaluate` -- the compiled mechanism's functions on chunks of
  designs x steps;
* :mod:`~linkage_sym.design.newton_groups` -- designs whose groups have no closed form,
  one at a time by the numeric plan;
* :mod:`~linkage_sym.design.metrics` -- what is reported per design (their names:
  :mod:`~linkage_sym.design.names`);
* :mod:`~linkage_sym.design.execute` -- in-process, local processes or Dask
  (:class:`Execution`);
* :mod:`~linkage_sym.design.scenes` -- each design as a scene of its own (:class:`SceneFiles`);
* :mod:`~linkage_sym.design.table` -- the table, CSV or Parquet;
* :mod:`~linkage_sym.design.plots` -- design maps and histograms;
* ``linkage-sym sweep`` reads its options in :mod:`linkage_sym.cli.sweep`.
"""

from importlib import import_module

_HOME = {"scene_parameters": "api", "sweep": "api", "SweepError": "errors",
         "DEFAULT_METRICS": "names", "METRICS": "names", "Designs": "parameters",
         "MonteCarlo": "parameters", "grid": "parameters", "monte_carlo": "parameters",
         "read_samples": "parameters", "Execution": "execute", "SceneFiles": "scenes",
         "SweepResult": "table"}
"""The module of each name the package exports: imported when the name is first used, so
that importing a module of the package (:mod:`~linkage_sym.design.names` for the help
of ``linkage-sym sweep``) does not load the sweep's machinery."""

__all__ = ["DEFAULT_METRICS", "METRICS", "Designs", "Execution", "MonteCarlo", "SceneFiles",
           "SweepError", "SweepResult", "grid", "monte_carlo", "read_samples",
           "scene_parameters", "sweep"]


def __getattr__(name):
    if name in _HOME:
        value = getattr(import_module(f"linkage_sym.design.{_HOME[name]}"), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(_HOME))
