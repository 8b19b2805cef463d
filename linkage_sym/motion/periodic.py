"""The periodic regime of a simulated motion: its period, mean speed and speed fluctuation.

A machine driven by a motor whose effort falls with its speed settles into a periodic motion:
the driver's speed repeats with each turn (or with the loads' period, a whole number of
turns).  Over the **last full turn** of a simulation, from the time the driver passes its
start angle plus a whole number of periods to the next such time (found on the dense output,
``brentq``)::

    period = t_end - t_start,   mean_speed = turn / period,
    speed_fluctuation = (w_max - w_min) / mean_speed

(the mean speed is the time average of the speed over the turn; ``w_max``, ``w_min`` the
extremes of the speed on the dense output, sampled at :data:`SAMPLES_PER_TURN` points and
refined where the acceleration vanishes).  The motion counts as periodic when the turn before
the last one agrees with it: its end speeds differ by at most :data:`PERIODIC_TOL` of the
last turn's speed range, and its period by at most that fraction of the last turn's
``speed_fluctuation`` times its period.  Otherwise the record says why the motion has none.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

from linkage_sym.motion.equations import TURN

__all__ = ["PERIODIC_TOL", "SAMPLES_PER_TURN", "periodic_motion", "turn_record"]

PERIODIC_TOL = 1e-3
"""How closely two consecutive turns must agree for the motion to count as periodic."""
SAMPLES_PER_TURN = 4000
"""Points of the dense output at which a turn's speed extremes are sought."""


def crossing_times(traj, start: float, period: float) -> tuple[np.ndarray, float]:
    """The times at which the driver passes ``start + k period`` (k = 1, 2, ... in the
    direction it turns), and that direction (+1, -1; 0 when it does not move)."""
    t = np.asarray(traj.t)
    q = traj(t)[0]
    direction = float(np.sign(q[-1] - start))
    if direction == 0:
        return np.empty(0), 0.0
    turns = math.floor((q[-1] - start) * direction / period + 1e-12)
    out = []
    for k in range(1, turns + 1):
        target = start + direction * k * period
        i = int(np.searchsorted(q * direction, target * direction))
        i = min(max(i, 1), len(t) - 1)
        f = lambda s: traj(s)[0][0] - target  # noqa: E731
        a, b = t[i - 1], t[i]
        out.append(a if f(a) == 0 else b if f(b) == 0 else
                   brentq(f, a, b, xtol=1e-15, rtol=4 * np.finfo(float).eps))
    return np.asarray(out), direction


def turn_record(traj, t0: float, t1: float, angle: float) -> dict:
    """``period``, ``mean_speed``, ``speed_fluctuation``, ``max_speed``, ``min_speed`` of
    the motion between ``t0`` and ``t1`` (over which the driver turns by ``angle``)."""
    ts = np.linspace(t0, t1, SAMPLES_PER_TURN + 1)
    w = traj(ts)[1]
    w_max, w_min = _extreme(traj, ts, w, np.argmax), _extreme(traj, ts, w, np.argmin)
    period = t1 - t0
    mean = angle / period
    return {"period": period, "mean_speed": mean,
            "speed_fluctuation": (w_max - w_min) / abs(mean),
            "max_speed": w_max, "min_speed": w_min, "from": t0, "to": t1}


def _extreme(traj, ts, w, pick) -> float:
    """The speed's extreme near the sampled one (a parabola through its neighbours)."""
    i = int(pick(w))
    if 0 < i < len(w) - 1:
        a, b, c = w[i - 1], w[i], w[i + 1]
        den = a - 2 * b + c
        if den != 0:
            x = 0.5 * (a - c) / den
            if abs(x) < 1:
                return float(traj(ts[i] + x * (ts[1] - ts[0]))[1][0])
    return float(w[i])


def periodic_motion(traj, kind: str, start: float, period: float | None) -> dict:
    """The ``motion`` record of a simulation: the last full turn's period, mean speed and
    speed fluctuation when the motion is periodic, else ``{"reason": ...}``."""
    if kind != "R":
        return {"reason": "the driver is a P joint: the motion has no turns to repeat with"}
    if period is None:
        return {"reason": "the scene's loads do not repeat with a whole number (at most 64) "
                          "of the driver's turns"}
    if traj.end in ("stall", "failure"):
        return {"reason": f"the motion ended early: {traj.message}"}
    times, direction = crossing_times(traj, start, period)
    turns = "turns" if period > TURN * (1 + 1e-12) else "turn"
    if len(times) < 3:
        return {"reason": f"the driver completes {max(len(times) - 1, 0)} full period(s) of "
                          f"{period / TURN:g} {turns} from its start angle; the periodic "
                          "regime needs two to compare: simulate longer"}
    angle = direction * period
    last = turn_record(traj, times[-2], times[-1], angle)
    before = turn_record(traj, times[-3], times[-2], angle)
    w_end = traj(np.array([times[-3], times[-2], times[-1]]))[1]
    span = last["max_speed"] - last["min_speed"]
    speed_gap = abs(w_end[2] - w_end[1])
    period_gap = abs(last["period"] - before["period"])
    if speed_gap > PERIODIC_TOL * span or \
            period_gap > PERIODIC_TOL * last["speed_fluctuation"] * last["period"]:
        return {"reason": f"the motion is not periodic yet: over the last two full turns the "
                          f"speed at the start angle went from {w_end[1]:.6g} to {w_end[2]:.6g} "
                          f"and the period from {before['period']:.6g} s to "
                          f"{last['period']:.6g} s (the speed varies by {span:.3g} within a "
                          "turn); simulate longer"}
    return last
