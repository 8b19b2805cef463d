"""Averages over a sweep's cycle: the repeated end point of a whole period counted once.

A sweep of ``steps`` evenly spaced driver values from ``start`` to ``stop``
holds both ends.  When the sweep is a whole period (every ``R`` driver turns
a whole number of turns, at least one of them turns, every ``P`` driver ends
where it starts, every load that varies with a driver's value ends its
``period`` where it starts, and the scene has no gear mesh), the last step is the first one again: an
average that counted both would weigh that state twice.  The average over
the period is then the mean over every step but the last, the rectangle
rule on a periodic function (which, for a sampled trigonometric polynomial
of degree below ``steps - 1``, is its exact mean over the period).

A sweep that is not a whole period is averaged over its steps as given:
each step counts once.  A scene with gear meshes is averaged that way too:
whether its gears are back where they started after the drivers' turns
depends on their ratios, which this test does not judge.

Every cycle average of linkage_sym (the balancing optimiser's RMS shaking
force, moment and efforts, :class:`~linkage_sym.balancing.cycle.CycleModel`;
a design sweep's ``rms_*`` metrics) takes its steps from
:func:`counted_steps`.

Examples
--------
>>> import numpy as np
>>> from linkage_sym.examples import load_example
>>> scene = load_example("crank_rocker")  # 0 to 360 degrees in 361 steps
>>> whole_period(scene)
True
>>> ok = np.ones(5, dtype=bool)
>>> counted_steps(ok, True).tolist()
[True, True, True, True, False]
>>> float(cycle_rms(np.array([1.0, -1.0, 1.0, -1.0, 1.0]) * 2, ok, True))
2.0
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["PERIOD_RTOL", "counted_steps", "cycle_mean", "cycle_rms", "whole_period",
           "whole_turns"]

PERIOD_RTOL = 1e-9
"""A driver's range is a whole number of periods when it is within this fraction
of a period of one."""


def _whole_multiple(span: float, period: float) -> int | None:
    """``span / period`` when it is a whole number (to :data:`PERIOD_RTOL`), else None."""
    k = span / period
    n = round(k)
    return int(n) if abs(k - n) <= PERIOD_RTOL * max(1.0, abs(k)) else None


def whole_period(scene) -> bool:
    """Whether the scene's sweep is a whole period, its last step a repeat of its first.

    Parameters
    ----------
    scene : Scene

    Returns
    -------
    bool
        True when the sweep has at least two steps, every ``R`` driver's
        ``stop - start`` is a whole number of turns (at least one driver
        turning), every ``P`` driver's is zero, and every load that varies
        with an ``R`` driver's value (``table`` or ``active``) spans a whole
        number of its ``period`` over that driver's range, and the scene
        has no gear mesh (``G`` joint).  The drivers'
        speeds and accelerations hold at every step, so the state of the
        last step is then the state of the first.
    """
    drivers = scene.drivers
    if not drivers or drivers[0].steps < 2 or scene.meshes:
        return False
    turning = False
    span = {}
    for d in drivers:
        s = float(d.stop) - float(d.start)
        span[d.joint] = s
        if d.kind == "R":
            n = _whole_multiple(s, 2.0 * math.pi)
            if n is None:
                return False
            turning = turning or n != 0
        elif s != 0.0:
            return False
    if not turning:
        return False
    for load in scene.loads:
        if (load.table is not None or load.active is not None) and load.period is not None:
            if _whole_multiple(span.get(load.driver, 0.0), float(load.period)) is None:
                return False
    return True


def whole_turns(q, kind: str = "R") -> bool:
    """Whether sampled driver values ``q`` (N,) end a whole number of turns (at least one,
    to :data:`PERIOD_RTOL`) from where they start: the sweep of a series known by its
    driver values alone (a plot's), its last step then a repeat of its first.

    >>> import numpy as np
    >>> whole_turns(np.linspace(0, 2 * np.pi, 13)), whole_turns(np.linspace(0, 5.8, 12))
    (True, False)
    """
    q = np.asarray(q, dtype=float)
    if kind != "R" or len(q) < 2 or not (np.isfinite(q[0]) and np.isfinite(q[-1])):
        return False
    n = _whole_multiple(float(q[-1] - q[0]), 2.0 * math.pi)
    return n is not None and n != 0


def counted_steps(ok, periodic: bool) -> np.ndarray:
    """The steps a cycle average counts: the ``ok`` ones, the repeated end point once.

    Parameters
    ----------
    ok : array_like of bool (..., N)
        Which steps have a value (the last axis runs over the sweep).
    periodic : bool
        The sweep is a whole period (:func:`whole_period`).

    Returns
    -------
    ndarray of bool (..., N)
        ``ok``, except that for a whole period the last step is left out
        wherever the first is ``ok`` (it holds the same state).  Where the
        first step is not ``ok`` the last one stands for that state and is
        counted.
    """
    c = np.array(ok, dtype=bool, copy=True)
    if periodic and c.shape[-1] >= 2:
        c[..., -1] &= ~c[..., 0]
    return c


def cycle_mean(values, ok, periodic: bool) -> np.ndarray:
    """Mean over the cycle of ``values`` along the last axis (:func:`counted_steps`).

    NaN where no step is counted.
    """
    v = np.asarray(values, dtype=float)
    c = counted_steps(ok, periodic)
    n = c.sum(axis=-1)
    s = np.where(c, v, 0.0).sum(axis=-1)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(n > 0, s / np.maximum(n, 1), np.nan)


def cycle_rms(values, ok, periodic: bool) -> np.ndarray:
    """Root mean square over the cycle of ``values`` along the last axis (:func:`cycle_mean`)."""
    v = np.asarray(values, dtype=float)
    return np.sqrt(cycle_mean(v * v, ok, periodic))
