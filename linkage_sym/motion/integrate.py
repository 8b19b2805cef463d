"""Integration of the equation of motion, with the events that end it.

SciPy's ``solve_ivp`` solvers are used as ``solve_ivp`` uses them: a solver object
(:class:`scipy.integrate.Radau` by default, or ``LSODA``/``BDF``, all stiff-capable) is
stepped and each step's dense output kept; stepping it here rather than through
``solve_ivp`` keeps every step taken before a state the mechanism cannot be solved at (the
right-hand side raises there; ``solve_ivp`` would lose the whole run), and lets a progress bar
follow the time.  The events are found on the dense output of the step in which they occur
(``brentq`` to rounding).  The motion is integrated **piece by piece**
(:mod:`~linkage_sym.motion.pieces`): where it crosses a row of the motor's table or a load's
switch point the step is cut at the crossing and the solver restarts there on the next
smooth piece, the dense output of each piece kept in turn.  The events:

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
from linkage_sym.motion.methods import METHODS, check_solver
from linkage_sym.motion.pieces import Pieces

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

    The motion is integrated piece by piece (:mod:`~linkage_sym.motion.pieces`): the solver
    restarts where the motion crosses a breakpoint of the motor's table or of the loads, so
    that every piece it steps over is smooth.

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
    check_solver(method, rtol, RTOL)
    scale = 1.0 if eq.driver.kind == "R" else (eq.scene.characteristic_length() or 1.0)
    atol = (ATOL * scale, ATOL * scale)
    traj = Trajectory(t=[float(t0)], method=method, rtol=rtol, atol=atol,
                      y0=tuple(float(v) for v in y0))
    calls = eq.evaluations
    _Stepper(eq, traj, t_bound, target, progress).run(float(t0), np.asarray(y0, float))
    traj.evaluations = eq.evaluations - calls
    if len(traj.pieces) == 0:  # not one step: the state at t0 alone
        y = np.asarray(y0, float)
        traj.pieces.append(lambda t: np.repeat(y[:, None], np.size(t), axis=1))
        traj.t.append(float(t0))
    return traj


MAX_STILL = 8
"""Most restarts in a row at one time (the motion held on a breakpoint) before the run ends."""


class _Stepper:
    """The integration's loop: the solver stepped over one smooth piece after another."""

    def __init__(self, eq, traj, t_bound, target, progress):
        self.eq, self.traj, self.t_bound = eq, traj, t_bound
        self.target, self.progress = target, progress
        self.pieces = Pieces(eq)

    def _solver(self, piece, t, y, max_step=np.inf):
        eq = self.eq

        def fun(_t, yy):
            return np.array([yy[1], eq.acceleration(yy[0], yy[1], piece)])

        return getattr(integrate, self.traj.method)(
            fun, t, y, self.t_bound, rtol=self.traj.rtol, atol=np.asarray(self.traj.atol),
            max_step=max_step)

    def _fail(self, t, q, qd, what, detail="") -> None:
        self.traj.end = "failure"
        self.traj.message = what.format(t=t, where=_where(self.eq, q, qd)) + detail

    def run(self, t: float, y: np.ndarray) -> None:
        """Integrate from ``(t, y)`` until the motion ends (``traj.end``, ``traj.message``)."""
        self.sign = np.sign(y[1])
        try:
            qdd = self.eq.acceleration(y[0], y[1])
        except StepFailure as exc:
            return self._fail(t, exc.q, exc.qd, _CANNOT, str(exc))
        piece = self.pieces.at(y[0], y[1], y[1] > 0 or (y[1] == 0 and qdd >= 0), qdd >= 0)
        still = 0
        while True:
            got = self._piece(piece, t, y)
            if got is None:
                return
            t_next, y, piece = got
            still = still + 1 if t_next == t else 0
            t = t_next
            if still > MAX_STILL:
                return self._fail(t, y[0], y[1], "the motion is held at t = {t:.6g} s, {where}, "
                                  "on a breakpoint of the motor's table or of the loads: it "
                                  "leaves each side of it toward the other")

    def _piece(self, piece, t, y):
        """Step over ``piece`` from ``(t, y)``: ``(t, y, next piece)`` where the motion leaves
        it, ``None`` where the motion ends."""
        traj = self.traj
        try:
            solver = self._solver(piece, t, y)
        except StepFailure as exc:
            return self._fail(t, exc.q, exc.qd, _CANNOT, str(exc))
        while solver.status == "running":
            t_before, y_before = solver.t, solver.y.copy()
            try:
                failed = solver.step()
            except StepFailure as exc:
                return self._fail(t_before, exc.q, exc.qd, _CANNOT, str(exc))
            if solver.status == "failed":
                return self._fail(t_before, *y_before, "the integrator failed at t = {t:.6g} "
                                  "s, {where}: ", str(failed))
            t_after, y_after = solver.t, solver.y
            if not piece.inside_safe(y_after[0]):  # past the frozen loads' lines: shorter
                solver = self._solver(piece, t_before, y_before, (t_after - t_before) / 2)
                continue
            dense = solver.dense_output()
            traj.steps += 1
            end, kind, k = self._event(piece, dense, t_before, y_before, t_after, y_after)
            if self.sign == 0:
                self.sign = np.sign(y_after[1])
            if end > t_before or kind != "switch":
                traj.pieces.append(dense)
                traj.t.append(float(end))
                if self.progress is not None:
                    self.progress(end)
            if kind == "switch":
                return end, dense(end), self.pieces.neighbour(piece, k)
            if kind is not None:
                return None
        return None

    def _event(self, piece, dense, t_before, y_before, t_after, y_after):
        """The first event in the step: ``(time, kind, k)``, kind ``"stall"``, ``"target"``,
        ``"switch"`` (leaving the piece by its switching function ``k``) or ``None``."""
        traj, eq = self.traj, self.eq
        found = [(t_after, None, -1)]
        if self.sign != 0 and np.sign(y_after[1]) != self.sign:  # speed crossed zero: a stall
            found.append((_root(lambda s: dense(s)[1], t_before, t_after), "stall", -1))
        target = self.target
        if target is not None and (y_after[0] - target) * (y_before[0] - target) <= 0 \
                and y_after[0] != y_before[0]:
            found.append((_root(lambda s: dense(s)[0] - target, t_before, t_after), "target", -1))
        g_after = piece.switching(y_after)
        if np.any(g_after < 0):
            g_before = piece.switching(y_before)
            for k in np.flatnonzero(g_after < 0):
                at = t_before if g_before[k] <= 0 else \
                    _root(lambda s, k=k: piece.switching(dense(s))[k], t_before, t_after)
                found.append((at, "switch", int(k)))
        end, kind, k = min(found, key=lambda e: (e[0], e[1] != "stall", e[1] != "target"))
        if kind == "stall":
            traj.end = "stall"
            traj.message = (f"the machine stalls at t = {end:.6g} s, "
                            f"{_where(eq, dense(end)[0], 0.0)}: the driver's speed crosses zero")
        elif kind == "target":
            traj.end = "target"
        return end, kind, k


_CANNOT = ("the mechanism cannot be solved at t = {t:.6g} s, {where} (a state the "
           "integrator tried after its last step): ")


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
