"""Designs whose dyad of two slides passes through infinity along the sweep (NumPy only).

A dyad of two slides (``PRP``, ``RPP``) has its joint at the intersection of its slides; where
they become parallel between two steps the joint goes out to infinity along one end of its
slides and comes back from the other.  Each step on either side is an exact solution of the
constraints, but a metric over the sweep (a peak or a mean of the efforts, the shaking, a
stroke) read from those steps as if the motion were continuous misses the passage, where
the joint's velocity and the forces that move it have no bound.  The sweep's table flags
those designs (the column ``through_infinity``, :mod:`linkage_sym.design.metrics`) by the
sign of the cross product of the slides, which the compiled mechanism's functions
``parallels_<group>`` give (the closed form's denominator,
:mod:`linkage_sym.codegen.parallels` for the runtime), between consecutive steps with
positions.  At the steps only: a design whose slides become parallel and turn back between
two steps, or on the way from the assembly configuration to the first step, is not counted.
"""

from __future__ import annotations

import numpy as np

__all__ = ["passages"]


def passages(model, sol) -> np.ndarray:
    """How many times each design's joints of dyads of two slides pass through infinity
    between consecutive steps with positions, ``(n,)``; NaN for a design that cannot be
    assembled, and for every design of a solution without the angles' cosines and sines
    (solved one at a time by the numeric plan).

    Parameters
    ----------
    model : Model
        The chunk's compiled functions (``art.parallels``, ``call``).
    sol : Solution
        The chunk solved at the steps.
    """
    n, N = sol.n, sol.N
    if sol.C is None or sol.S is None or not model.art.parallels:
        return np.full(n, np.nan)
    P = [v[:, None] if np.ndim(v) else v for v in sol.P]
    count = np.zeros(n)
    steps = np.arange(N)
    for g, *_ in model.art.parallels:
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            (cross,) = model.call(f"parallels_{g}", P, CS=(list(sol.C), list(sol.S)))
        cross = np.broadcast_to(np.asarray(cross, float), (n, N))
        has = sol.pos_ok & np.isfinite(cross)
        # each step's last step with positions before it (-1: none), and its side
        last = np.maximum.accumulate(np.where(has, steps, -1), axis=1)
        prev = np.concatenate([np.full((n, 1), -1), last[:, :-1]], axis=1)
        side = cross > 0
        before = np.take_along_axis(side, np.maximum(prev, 0), axis=1)
        count += (has & (prev >= 0) & (before != side)).sum(axis=1)
    return np.where(sol.assembled, count, np.nan)
