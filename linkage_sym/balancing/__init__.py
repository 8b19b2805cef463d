"""Balancing of planar linkages: Song and Wang's (1992) conditions for hinged ones, and counterweights.

Two layers, kept apart by an import contract (``pyproject.toml``): the
derivation of the conditions is SymPy; choosing counterweights by
optimisation is NumPy/SciPy only and never loads SymPy.

Modules
-------
SymPy (derivation, hinged linkages only):

pins
    Pins, link frames and symbols of a hinged linkage (:class:`BalanceModel`).
module
    The mass/acceleration-parameter module of one link.
assembly
    The modules summed over a mechanism's links: the shaking moment.
force
    Shaking-force balance conditions by linearly independent vectors.
conditions
    Shaking-moment balance: what force balance leaves, and its conditions.
force_counterweights
    Counterweights that satisfy the derived force conditions (one linear solve).
series
    Shaking force and moment over a sweep from the lambdified modules (and
    from the force solver, for comparison and for slider linkages).
report
    The JSON ``linkage-sym balance`` writes, built whole (:func:`balance_document`).

NumPy/SciPy only (counterweight optimisation, any linkage):

counterweight
    :class:`Counterweight` and the scene with counterweights merged.
cycle
    :class:`CycleModel`: force, moment and efforts over a cycle, linear in
    the counterweights.
options
    The optimiser's options, checked in one place (also for the command line).
search
    :func:`optimize_counterweights`: convex relaxation and local searches.
optimize
    The names of the former one-module optimiser, re-exported.

The names below are importable from this package; each loads its module on
first use, so ``from linkage_sym.balancing import optimize_counterweights``
does not load SymPy.
"""

from __future__ import annotations

import importlib

_HOMES = {
    # SymPy
    "BalanceModel": "pins",
    "link_module": "module",
    "shaking_moment": "assembly",
    "force_balance": "force",
    "Balance": "conditions",
    "derive_balance": "conditions",
    "force_balancing_counterweights": "force_counterweights",
    "solve_counterweights": "force_counterweights",
    "BalanceSeries": "series",
    "module_series": "series",
    "solver_series": "series",
    "balance_document": "report",
    "balance_report": "report",
    # NumPy/SciPy only
    "Counterweight": "counterweight",
    "with_counterweights": "counterweight",
    "CycleModel": "cycle",
    "OptionsError": "options",
    "SearchOptions": "options",
    "default_bounds": "options",
    "search_options": "options",
    "OptimizationResult": "search",
    "ZERO_START": "search",
    "optimize_counterweights": "search",
}

__all__ = sorted(_HOMES)


def __getattr__(name):
    home = _HOMES.get(name)
    if home is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(f"{__name__}.{home}"), name)
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(_HOMES))
