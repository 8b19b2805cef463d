"""``simulate``: the motion of a machine driven by its motor, and its result.

The equation of motion (:mod:`~linkage_sym.motion.equations`) is integrated from the scene's
``simulate.start_deg`` (or ``start``) and ``start_speed`` at time 0 for ``duration`` seconds
(:mod:`~linkage_sym.motion.integrate`); the state at ``samples`` equally spaced times is read
off the dense output, the acceleration at each is the equation's, and the numeric solver
analyses those states as ``analyze`` analyses a sweep, so each step's ``driving`` is the effort
that moves the mechanism as integrated: the motor's (to the integration's rounding, a check
every run makes: :attr:`SimulationResult.effort_error`).  The result has the first part's
layout plus each step's ``time``, the ``integrator`` and the periodic ``motion``
(:mod:`~linkage_sym.motion.periodic`).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from linkage_sym.model import Scene
from linkage_sym.motion.equations import MotionEquations, motor_effort
from linkage_sym.motion.integrate import RTOL, Trajectory, integrate_motion
from linkage_sym.motion.memory import check_memory
from linkage_sym.motion.result_json import SimulationJSON
from linkage_sym.motion.periodic import periodic_motion

__all__ = ["SimulationResult", "simulate"]


@dataclass
class SimulationResult(SimulationJSON):
    """A simulated motion: the analysis of its sampled states and what the integration says.

    Attributes
    ----------
    analysis : Analysis
        The sampled states, analysed as ``analyze`` analyses a sweep (``drivers`` hold the
        integrated ``q``, ``qd`` and the equation's ``qdd``).
    time : ndarray (N,)
        The sample times (s): ``samples`` equally spaced times from 0 to ``duration``, those
        reached when the motion ended early.
    motor : ndarray (N,)
        The motor's effort at each sample.
    inertia : ndarray (N,)
        The equivalent moment of inertia ``J`` at each sample (kg m^2; kg for a ``P`` driver).
    trajectory : Trajectory
        The integrated motion (its dense output, end and message).
    motion : dict
        The periodic regime (``period``, ``mean_speed``, ``speed_fluctuation``, ...) or its
        ``reason`` for having none.
    """

    analysis: object
    time: np.ndarray
    motor: np.ndarray
    inertia: np.ndarray
    trajectory: Trajectory
    motion: dict
    joint: str

    @property
    def message(self) -> str | None:
        """Why the motion ended before ``duration`` (``None`` when it did not)."""
        return self.trajectory.message

    @property
    def effort_error(self) -> float:
        """The largest difference, over the ``ok`` samples, between the effort the solver
        finds at the integrated states and the motor's, relative to the largest effort."""
        driving = self.analysis.forces.driving[self.joint] if self.analysis.forces else None
        if driving is None:
            return float("nan")
        ok = self.analysis.ok
        scale = max(float(np.max(np.abs(self.motor[ok]), initial=0.0)), 1e-300)
        return float(np.max(np.abs(driving[ok] - self.motor[ok]), initial=0.0) / scale)


def simulate(scene: Scene, *, method: str = "LSODA", rtol: float = RTOL,
             progress=None) -> SimulationResult:
    """Simulate the motion of a scene's machine driven by its motor (or motors).

    Parameters
    ----------
    scene : Scene
        A scene with a ``simulate`` section, a ``motor`` on every driver and
        ``effects.inertia`` true (each refused by name otherwise).  Several drivers (a
        mechanism of as many degrees of freedom) are simulated by
        :func:`~linkage_sym.motion.multi_simulate.simulate_several`.
    method : {"LSODA", "Radau", "BDF"}
        The stiff-capable SciPy solver.
    rtol : float
        Relative tolerance of the integration (at most 1e-10).
    progress : callable, optional
        Called with the simulated time after each integration step.

    Returns
    -------
    SimulationResult
        A :class:`~linkage_sym.motion.multi_simulate.SeveralSimulationResult` for several
        drivers (the same layout, each driver's motor and the mass matrix).

    Raises
    ------
    SceneError
        A scene that cannot be simulated, each problem naming its field.
    """
    from linkage_sym.numeric.plan import compile_plan

    if len(scene.drivers) > 1:  # several motors: the mass matrix's equations
        from linkage_sym.motion.multi_simulate import simulate_several

        return simulate_several(scene, method=method, rtol=rtol, progress=progress)
    eq = MotionEquations(scene)
    sim = scene.simulate
    plan = compile_plan(scene)
    check_memory(plan, sim.samples)
    traj = integrate_motion(eq, 0.0, (sim.start, sim.start_speed), sim.duration,
                            method=method, rtol=rtol, progress=progress)
    times = np.linspace(0.0, sim.duration, sim.samples)
    times = times[times <= traj.t_end]
    y = traj(times)
    qdd, J, _ = eq.accelerations(y[0], y[1])
    j = eq.joint
    analysis = plan.run({j: y[0]}, {j: y[1]}, {j: qdd})
    motion = periodic_motion(traj, eq.driver.kind, sim.start, eq.period)
    return SimulationResult(analysis, times, motor_effort(eq.motor, y[1]), J, traj, motion, j)


def with_inertia(scene: Scene, link: str, added: float) -> Scene:
    """``scene`` with ``added`` (kg m^2) on the moment of inertia of ``link`` (a flywheel on
    its shaft: centred on its pivot, it adds nothing else)."""
    links = tuple(dataclasses.replace(lk, inertia=lk.inertia + added) if lk.name == link else lk
                  for lk in scene.links)
    return dataclasses.replace(scene, links=links)
