"""Counterweights and partial balancing: the names of the former one-module optimiser (NumPy/SciPy only).

Kept so that ``from linkage_sym.balancing.optimize import ...`` goes on
working; the code lives in :mod:`~.counterweight` (the data and the scene
merge), :mod:`~.cycle` (the linear cycle model), :mod:`~.options` (the
checked options and default bounds) and :mod:`~.search` (the optimisation).
New code imports from :mod:`linkage_sym.balancing`.
"""

from __future__ import annotations

from linkage_sym.balancing.counterweight import Counterweight, with_counterweights
from linkage_sym.balancing.cycle import CycleModel
from linkage_sym.balancing.options import default_bounds
from linkage_sym.balancing.search import ZERO_START, OptimizationResult, optimize_counterweights

__all__ = [
    "Counterweight",
    "CycleModel",
    "OptimizationResult",
    "ZERO_START",
    "default_bounds",
    "optimize_counterweights",
    "with_counterweights",
]
