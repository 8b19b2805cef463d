"""Integration of the equation of motion, with the events that end it.

SciPy's ``solve_ivp`` solvers are used as ``solve_ivp`` uses them: a solver object
(:class:`scipy.integrate.Radau` by default, or ``LSODA``/``BDF``, all stiff-capable) is
stepped and each step's dense output kept; stepping it here rather than through
``solve_ivp`` keeps every step taken before a state the mechanism cannot be solved at (the
right-hand side raises there; ``solve_ivp`` would lose the whole run), and lets a progress bar
follow the time.  The events are found on the dense output of the step in which they occur
(``brentq`` to rounding):

* a **stall**: the driver's speed crosses zero (from the sign it had, not from a start at
  rest);
* a **target** coordinate reached (one turn of the driver, for the periodic orbit's search);
* a state at which the mechanism **cannot be solved** (it cannot be assembled, is singular,
  or its equivalent inertia vanishes): the integration ends at the last step taken, and the
  message says at which time and driver value the solver met it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy import integrate
from scipy.optimize import brentq

from linkage_sym.motion.equations import MotionEquations, StepFailure
from linkage_sym.motion.methods import METHODS

__all__ = ["METHODS", "RTOL", "Trajectory", "integrate_motion"]

RTOL = 1e-10
"""The relative tolerance of the contract (at most)."""
ATOL = 1e-12
"""The absolute tolerance, on the coordinate (rad, or m over the mechanism's size) and on the
speed (the same over one second)."""


@dataclass
class Trajectory:
    """The integrated motion: ``y(t) = (q, qd)`` between ``t[0]`` and ``t[-1]``.

    ``end`` is ``"duration"`` (the time asked for was reached), ``"stall"``, ``"target"`` or
    ``"failure"``; ``message`` says where the motion ended when it ended early.
    """

    t: list = field(default_factory=list)
    pieces: list = field(default_factory=list)
    end: str = "duration"
    message: str | None = None
    method: str = "Radau"
    rtol: float = RTOL
    atol: tuple = ()
    steps: int = 0
    evaluations: int = 0
    y0: tuple = ()

    @property
    def t_end(self) -> float:
        """The time at which the motion ends."""
        return self.t[-1]

    def __call__(self, t) -> np.ndarray:
        """``(q, qd)`` at the times ``t`` (within ``[t[0], t_end]``): ``(2, N)``."""
        t = np.atleast_1d(np.asarray(t, float))
        edges = np.asarray(self.t)
        which = np.clip(np.searchsorted(edges, t, side="right") - 1, 0, len(self.pieces) - 1)
        out = np.empty((2, len(t)))
        for k in np.unique(which):
            sel = which == k
            out[:, sel] = self.pieces[k](t[sel])
        out[:, t == self.t[0]] = np.asarray(self.y0, float)[:, None]  # the start, as given
        return out

    def integrator(self) -> dict:
        """The ``integrator`` record of a result."""
        return {"method": f"scipy.integrate {self.method} (the solver of solve_ivp)",
                "rtol": self.rtol, "atol": list(self.atol), "steps": self.steps,
                "evaluations": self.evaluations, "end": self.end}


def integrate_motion(eq: MotionEquations, t0: float, y0, t_bound: float, *,
                     method: str = "Radau", rtol: float = RTOL, target: float | None = None,
                     progress=None) -> Trajectory:
    """Integrate the motion of ``eq`` from ``y0 = (q, qd)`` at ``t0`` to ``t_bound``.

    Parameters
    ----------
    eq : MotionEquations
        The equation of motion.
    t0, t_bound : float
        The start and the latest end (s).
    y0 : sequence of float
        The driver's coordinate and speed at ``t0``.
    method : {"Radau", "LSODA", "BDF"}
        The solver.
    rtol : float
        Relative tolerance (at most :data:`RTOL`).
    target : float, optional
        End when the coordinate reaches this value (an event).
    progress : callable, optional
        Called with the time reached after each step.

    Returns
    -------
    Trajectory
    """
    if method not in METHODS:
        raise ValueError(f"method: one of {', '.join(METHODS)}, got {method!r}")
    if not 0 < rtol <= RTOL:
        raise ValueError(f"rtol: must be in (0, {RTOL:g}], got {rtol!r}")
    scale = 1.0 if eq.driver.kind == "R" else (eq.scene.characteristic_length() or 1.0)
    atol = (ATOL * scale, ATOL * scale)
    traj = Trajectory(t=[float(t0)], method=method, rtol=rtol, atol=atol,
                      y0=tuple(float(v) for v in y0))
    calls = eq.evaluations

    def fun(t, y):
        return np.array([y[1], eq.acceleration(y[0], y[1])])

    solver = getattr(integrate, method)(fun, t0, np.asarray(y0, float), t_bound, rtol=rtol,
                                        atol=np.asarray(atol))
    sign = np.sign(y0[1])
    while solver.status == "running":
        t_before, y_before = solver.t, solver.y.copy()
        try:
            failed = solver.step()
        except StepFailure as exc:
            traj.end = "failure"
            traj.message = (f"the mechanism cannot be solved at t = {t_before:.6g} s, "
                            f"{_where(eq, exc.q, exc.qd)} (a state the integrator tried after "
                            f"its last step): {exc}")
            break
        if solver.status == "failed":
            traj.end = "failure"
            traj.message = (f"the integrator failed at t = {t_before:.6g} s, "
                            f"{_where(eq, *y_before)}: {failed}")
            break
        piece = solver.dense_output()
        t_after, y_after = solver.t, solver.y
        traj.steps += 1
        end = None
        if sign != 0 and np.sign(y_after[1]) != sign:  # the speed crossed zero: a stall
            end = _root(lambda t: piece(t)[1], t_before, t_after)
            traj.end = "stall"
            qs = piece(end)[0]
            traj.message = (f"the machine stalls at t = {end:.6g} s, {_where(eq, qs, 0.0)}: "
                            "the driver's speed crosses zero")
        elif target is not None and (y_after[0] - target) * (y_before[0] - target) <= 0 \
                and y_after[0] != y_before[0]:
            end = _root(lambda t: piece(t)[0] - target, t_before, t_after)
            traj.end = "target"
        if sign == 0:
            sign = np.sign(y_after[1])
        traj.pieces.append(piece)
        traj.t.append(float(t_after if end is None else end))
        if progress is not None:
            progress(traj.t[-1])
        if end is not None:
            break
    traj.evaluations = eq.evaluations - calls
    if len(traj.pieces) == 0:  # not one step: the state at t0 alone
        y = np.asarray(y0, float)
        traj.pieces.append(lambda t: np.repeat(y[:, None], np.size(t), axis=1))
        traj.t.append(float(t0))
    return traj


def _root(f, a: float, b: float) -> float:
    fa, fb = f(a), f(b)
    if fa == 0:
        return a
    if fb == 0 or fa * fb > 0:
        return b
    return brentq(f, a, b, xtol=1e-15, rtol=4 * np.finfo(float).eps)


def _where(eq: MotionEquations, q: float, qd: float) -> str:
    """The driver's value and speed, in the scene's units."""
    j = eq.joint
    if eq.driver.kind == "R":
        return f"driver {j} at {math.degrees(q):.6g} degrees, {qd:.6g} rad/s"
    return f"driver {j} at {q:.6g} m, {qd:.6g} m/s"
