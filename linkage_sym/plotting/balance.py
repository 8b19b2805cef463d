"""Balancing plots: shaking force polar diagram and shaking moment curve.

Two figures compare series of shaking loads, typically *before* and *after*
balancing, on one figure each:

* the *shaking force polar diagram*: the tip of the shaking force vector
  ``F = (F_x, F_y)`` traced over the cycle in the ``F_x``–``F_y`` plane with
  equal axes and the origin marked (a hodograph in Cartesian axes, the classic
  diagram of balancing texts);
* the *shaking moment curve*: the moment about the global origin against the
  first driver's coordinate (degrees for an ``R`` driver).

The inputs are :class:`~linkage_sym.balancing.series.BalanceSeries` objects
(or anything with the same attributes ``label``, ``q``, ``status``, ``force``
and ``moment``).  This module only reads them: it does not import
:mod:`linkage_sym.balancing` (which needs SymPy) nor SymPy, so the plotting
layer keeps consuming results only.

Steps whose status is not ``ok`` are gaps: their values are dropped (set to
NaN) whatever they hold, the curves are not joined across them, and the
figure says how many steps were skipped.

A series whose peak is a small fraction (below :data:`SMALL_RATIO`) of the
largest peak is drawn a second time in a *zoom panel* at its own scale, so a
well-balanced *after* series can be read next to the *before* series.  A
series that is numerically zero (see :data:`ZERO_ABS`, :data:`ZERO_REL`) is
drawn as a diamond at the origin (polar diagram) or a marked line on zero
(moment curve) and its legend entry says so, with the peak value it has.

The polar diagram is drawn by :mod:`~linkage_sym.plotting.balance_force`,
the moment curve by :mod:`~linkage_sym.plotting.balance_moment`, and what
both share -- the series as drawn, the before/after styling, the
driver-value axis and the legend's wording -- is
:mod:`~linkage_sym.plotting.balance_series`; their public names are
importable from here.

Examples
--------
>>> import numpy as np
>>> from types import SimpleNamespace
>>> q = np.linspace(0.0, 2 * np.pi, 73)
>>> before = SimpleNamespace(label="before", q=q, status=np.full(73, "ok"),
...                          force=np.stack([np.cos(q), 0.5 * np.sin(q)], axis=-1),
...                          moment=0.1 * np.sin(2 * q))
>>> fig = shaking_force_polar_figure([before])
>>> len(fig.legends[0].get_texts())
1
"""

from linkage_sym.plotting.balance_force import shaking_force_polar, shaking_force_polar_figure
from linkage_sym.plotting.balance_moment import shaking_moment_curve, shaking_moment_figure
from linkage_sym.plotting.balance_series import SMALL_RATIO, ZERO_ABS, ZERO_REL

__all__ = [
    "SMALL_RATIO",
    "ZERO_ABS",
    "ZERO_REL",
    "shaking_force_polar",
    "shaking_force_polar_figure",
    "shaking_moment_curve",
    "shaking_moment_figure",
]
