"""``simulate`` for several motors: the integration of ``M q̈ = τ - E0`` and its result.

The state is ``y = (q_1 .. q_n, q̇_1 .. q̇_n)``; SciPy's stiff-capable solvers are stepped as
``solve_ivp`` steps them (as :func:`~linkage_sym.motion.integrate.integrate_motion` does for one
driver: each step's dense output kept, the steps taken before a state the mechanism cannot be
solved at kept), to the same tolerances.  The events end the simulation, each with a message
that says where (the time and every driver's value and speed):

* a **stall** of any motor: a driver's speed crosses zero (from the sign it had, not from a
  start at rest); the earliest crossing in the step, found on its dense output (``brentq``);
* a state at which the mechanism **cannot be solved** (it cannot be assembled, is singular,
  friction locks it, or ``M`` is not positive definite).

The result (:class:`SeveralSimulationResult`) has the contract's layout: each sampled state
analysed as ``analyze`` analyses a step (every driver's ``q``, ``qd``, ``qdd``; ``driving`` the
motors' efforts), ``time``, ``integrator``.  ``motion``: the contract's periodic regime is one
driver's; with several drivers it holds ``reason`` (why there is no single periodic regime) and
``drivers``, each driver's last full turn (its ``period``, ``mean_speed``,
``speed_fluctuation``, ``max_speed``, ``min_speed``, ``from``, ``to``) or its own ``reason``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import integrate
from scipy.optimize import brentq

from linkage_sym.model import Scene
from linkage_sym.motion.equations import StepFailure, motor_effort
from linkage_sym.motion.integrate import ATOL, RTOL, Trajectory
from linkage_sym.motion.memory import check_memory
from linkage_sym.motion.result_json import SimulationJSON
from linkage_sym.motion.methods import check_solver
from linkage_sym.motion.multi import SeveralEquations, where
from linkage_sym.motion.periodic import crossing_times, turn_record

__all__ = ["SeveralSimulationResult", "SeveralTrajectory", "simulate_several"]


@dataclass
class SeveralTrajectory(Trajectory):
    """The integrated motion of ``n`` drivers: ``y(t) = (q, q̇)``, ``2 n`` rows."""

    n: int = 1

    def __call__(self, t) -> np.ndarray:
        """``(q, q̇)`` at the times ``t`` (within ``[t[0], t_end]``): ``(2 n, N)``."""
        t = np.atleast_1d(np.asarray(t, float))
        edges = np.asarray(self.t)
        which = np.clip(np.searchsorted(edges, t, side="right") - 1, 0, len(self.pieces) - 1)
        out = np.empty((2 * self.n, len(t)))
        for k in np.unique(which):
            sel = which == k
            out[:, sel] = self.pieces[k](t[sel])
        out[:, t == self.t[0]] = np.asarray(self.y0, float)[:, None]  # the start, as given
        return out


class _DriverView:
    """One driver's ``(q, q̇)`` of a :class:`SeveralTrajectory`, as the periodic regime's
    functions read a one-driver trajectory."""

    def __init__(self, traj: SeveralTrajectory, k: int):
        self.traj, self.k, self.t = traj, k, traj.t
        self.end, self.message = traj.end, traj.message

    def __call__(self, t) -> np.ndarray:
        return self.traj(t)[[self.k, self.traj.n + self.k]]


def integrate_several(eq: SeveralEquations, y0, t_bound: float, *, method: str = "LSODA",
                      rtol: float = RTOL, progress=None) -> SeveralTrajectory:
    """Integrate the motion of ``eq`` from ``y0 = (q, q̇)`` (``2 n`` values) at time 0 to
    ``t_bound``.

    Parameters
    ----------
    eq : SeveralEquations
        The equations of motion.
    y0 : sequence of float
        The drivers' coordinates, then their speeds, at time 0.
    t_bound : float
        The latest end (s).
    method : {"LSODA", "Radau", "BDF"}
        The solver.
    rtol : float
        Relative tolerance (at most :data:`~linkage_sym.motion.integrate.RTOL`).
    progress : callable, optional
        Called with the time reached after each step.

    Returns
    -------
    SeveralTrajectory
    """
    check_solver(method, rtol, RTOL)
    n = eq.n
    length = eq.scene.characteristic_length() or 1.0
    scale = [1.0 if d.kind == "R" else length for d in eq.drivers]
    atol = tuple(ATOL * s for s in scale + scale)
    traj = SeveralTrajectory(t=[0.0], method=method, rtol=rtol, atol=atol,
                             y0=tuple(float(v) for v in y0), n=n)
    calls = eq.evaluations

    def fun(t, y):
        return np.concatenate([y[n:], eq.acceleration(y[:n], y[n:])])

    solver = getattr(integrate, method)(fun, 0.0, np.asarray(y0, float), t_bound, rtol=rtol,
                                        atol=np.asarray(atol))
    signs = np.sign(np.asarray(y0, float)[n:])
    while solver.status == "running":
        t_before, y_before = solver.t, solver.y.copy()
        try:
            failed = solver.step()
        except StepFailure as exc:
            traj.end = "failure"
            traj.message = (f"the mechanism cannot be solved at t = {t_before:.6g} s, "
                            f"{where(eq, exc.q, exc.qd)} (a state the integrator tried after "
                            f"its last step): {exc}")
            break
        if solver.status == "failed":
            traj.end = "failure"
            traj.message = (f"the integrator failed at t = {t_before:.6g} s, "
                            f"{where(eq, y_before[:n], y_before[n:])}: {failed}")
            break
        piece = solver.dense_output()
        end = _stall(eq, traj, piece, signs, t_before, solver.t, solver.y)
        signs = np.where(signs == 0, np.sign(solver.y[n:]), signs)
        traj.steps += 1
        traj.pieces.append(piece)
        traj.t.append(float(solver.t if end is None else end))
        if progress is not None:
            progress(traj.t[-1])
        if end is not None:
            break
    traj.evaluations = eq.evaluations - calls
    if len(traj.pieces) == 0:  # not one step: the state at time 0 alone
        y = np.asarray(y0, float)
        traj.pieces.append(lambda t: np.repeat(y[:, None], np.size(t), axis=1))
        traj.t.append(0.0)
    return traj


def _stall(eq, traj, piece, signs, t_before, t_after, y_after) -> float | None:
    """The time at which the first motor stalls within the step (its speed crossing zero from
    the sign it had), the trajectory's end and message set; ``None`` when none does."""
    n = eq.n
    crossed = [k for k in range(n) if signs[k] != 0 and np.sign(y_after[n + k]) != signs[k]]
    if not crossed:
        return None
    times = [_root(lambda t, k=k: piece(t)[n + k], t_before, t_after) for k in crossed]
    first = int(np.argmin(times))
    end, k = times[first], crossed[first]
    y = piece(end)
    y[n + k] = 0.0
    traj.end = "stall"
    traj.message = (f"the motor of driver {eq.joints[k]} stalls at t = {end:.6g} s, "
                    f"{where(eq, y[:n], y[n:])}: its speed crosses zero")
    return end


def _root(f, a: float, b: float) -> float:
    """The root of ``f`` in ``[a, b]`` (an end where ``f`` vanishes there or keeps its sign)."""
    fa, fb = f(a), f(b)
    if fa == 0:
        return a
    if fb == 0 or fa * fb > 0:
        return b
    return brentq(f, a, b, xtol=1e-15, rtol=4 * np.finfo(float).eps)


@dataclass
class SeveralSimulationResult(SimulationJSON):
    """A simulated motion of several motors: the analysis of its sampled states and what the
    integration says.

    Attributes
    ----------
    analysis : Analysis
        The sampled states, analysed as ``analyze`` analyses a sweep (``drivers`` hold each
        driver's integrated ``q``, ``qd`` and the equations' ``qdd``).
    time : ndarray (N,)
        The sample times (s).
    motor : dict
        Each driver's motor effort at each sample, ``(N,)``.
    mass_matrix : ndarray (N, n, n)
        ``M`` at each sample, the drivers in the order of ``joints``.
    trajectory : SeveralTrajectory
        The integrated motion.
    motion : dict
        ``reason`` and each driver's last full turn (see the module docstring).
    joints : tuple of str
        The driven joints.
    """

    analysis: object
    time: np.ndarray
    motor: dict
    mass_matrix: np.ndarray
    trajectory: SeveralTrajectory
    motion: dict
    joints: tuple

    @property
    def message(self) -> str | None:
        """Why the motion ended before ``duration`` (``None`` when it did not)."""
        return self.trajectory.message

    @property
    def effort_error(self) -> float:
        """The largest difference, over the ``ok`` samples and the drivers, between the effort
        the solver finds at the integrated states and the motor's, relative to the largest
        motor effort."""
        if self.analysis.forces is None:
            return float("nan")
        ok = self.analysis.ok
        scale = max(max(float(np.max(np.abs(m[ok]), initial=0.0)) for m in self.motor.values()),
                    1e-300)
        return max(float(np.max(np.abs(self.analysis.forces.driving[j][ok] - m[ok]),
                                initial=0.0)) for j, m in self.motor.items()) / scale


def simulate_several(scene: Scene, *, method: str = "LSODA", rtol: float = RTOL,
                     progress=None) -> SeveralSimulationResult:
    """Simulate the motion of a scene's machine driven by several motors (one per driver).

    What :func:`~linkage_sym.motion.simulate.simulate` does for a scene of several drivers
    (the parameters are its).

    Returns
    -------
    SeveralSimulationResult
    """
    from linkage_sym.numeric.plan import compile_plan

    eq = SeveralEquations(scene)
    sim = scene.simulate
    plan = compile_plan(scene)
    check_memory(plan, sim.samples)
    y0 = tuple(sim.start) + tuple(sim.start_speed)
    traj = integrate_several(eq, y0, sim.duration, method=method, rtol=rtol, progress=progress)
    times = np.linspace(0.0, sim.duration, sim.samples)
    times = times[times <= traj.t_end]
    y = traj(times)
    n = eq.n
    qdd, M, _ = eq.accelerations(y[:n], y[n:])
    analysis = plan.run(*eq._states(y[:n], y[n:], qdd))
    motor = {j: np.asarray(motor_effort(m, y[n + k]), float)
             for k, (j, m) in enumerate(zip(eq.joints, eq.motors))}
    return SeveralSimulationResult(analysis, times, motor, M, traj, several_motion(eq, traj),
                                   eq.joints)


def several_motion(eq: SeveralEquations, traj: SeveralTrajectory) -> dict:
    """The ``motion`` record of several drivers: why there is no single periodic regime, and
    each driver's last full turn (or why it has none)."""
    drivers = {}
    for k, d in enumerate(eq.drivers):
        if d.kind != "R":
            drivers[d.joint] = {"reason": "a P driver: its motion has no turns"}
            continue
        view = _DriverView(traj, k)
        start = float(traj.y0[k])
        times, direction = crossing_times(view, start, 2 * np.pi)
        if len(times) < 1:
            drivers[d.joint] = {"reason": "the driver completes no full turn from its start "
                                          "angle"}
            continue
        times = np.concatenate([[traj.t[0]], times])  # the first turn starts at the start
        drivers[d.joint] = turn_record(view, times[-2], times[-1], direction * 2 * np.pi)
    reason = ("several drivers: the periodic regime (one driver's turns repeating) is not "
              "sought; each driver's last full turn is given in drivers")
    if traj.end in ("stall", "failure"):
        reason = f"the motion ended early: {traj.message}; {reason}"
    return {"reason": reason, "drivers": drivers}
