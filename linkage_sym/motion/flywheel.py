"""The flywheel a requested speed fluctuation needs: the energy method, refined by simulation.

**Energy method** (the textbook's: the largest energy surplus over a cycle).  At the steady
mean speed ``w_m`` -- where the motor's effort balances the mean resisting effort over a
period, ``M(w_m) = mean E0(q, w_m)``, ``E0`` the kinetostatic driving effort at constant speed
(:mod:`~linkage_sym.motion.equations`) -- the work surplus of the driving over the resisting
effort from the period's start is ``dE(q) = integral (M(w_m) - E0(q, w_m)) dq``; its range
``dE_max = max dE - min dE`` is the largest energy surplus, and the flywheel::

    J_F = dE_max / (delta w_m^2) - J_mean

(``J_mean`` the mechanism's own equivalent moment of inertia, its mean over the period) keeps
the fluctuation ``delta`` under the approximations of the method (a constant speed in ``E0``
and in ``J``, ``w_max^2 - w_min^2 = 2 delta w_m^2``).

**Refinement by simulation.**  With a moment of inertia ``I`` added to the driven link (a
flywheel on its shaft) the periodic motion is found by shooting: the speed ``w0`` at the start
angle whose motion over one period returns to ``w0`` (a secant on ``w_end(w0) - w0``, to
:data:`SHOOTING_TOL` of ``w_m``; each trial after the first starts from the last trial's
periodic speed and secant slope, a Newton step where a fresh search takes two shots to make
its first secant), integrated as ``simulate`` integrates; its
``speed_fluctuation`` is measured as ``simulate`` measures it (:mod:`~linkage_sym.motion.periodic`).  ``1/delta`` is nearly affine
in ``I``: a secant on ``1/delta(I) - 1/target``, kept within a bracket (bisection when the
secant leaves it), until the simulated ``delta`` is at most the request and within
:data:`TOLERANCE` of it.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import brentq

from linkage_sym.errors import SceneError
from linkage_sym.model import Scene
from linkage_sym.motion.equations import MotionEquations, ground_driven_link, motor_effort
from linkage_sym.motion.integrate import integrate_motion
from linkage_sym.motion.periodic import turn_record
from linkage_sym.motion.simulate import with_inertia

__all__ = ["FlywheelResult", "energy_method", "flywheel", "TOLERANCE"]

TOLERANCE = 0.01
"""The refined flywheel's simulated fluctuation is within this fraction below the request."""
GRID = 7200
"""Points per period of the energy method's integral (trapezoidal rule)."""
MAX_REFINE = 30
"""Most simulated trials of the refinement."""
MAX_SHOTS = 30
"""Most shots (one period each) in the search of one periodic motion."""
SHOOTING_TOL = 1e-8
"""A periodic motion's speed at the start angle returns to within this fraction of the mean
speed after one period (the fluctuation it measures is then exact to far better than the
refinement's 1 %)."""


@dataclass
class FlywheelResult:
    """What :func:`flywheel` found (moments of inertia in kg m^2, speeds in rad/s)."""

    requested: float
    estimate: float
    inertia: float
    fluctuation: float
    estimate_fluctuation: float
    mean_speed: float
    energy: dict
    orbit: dict
    iterations: list = field(default_factory=list)
    link: str = ""

    def to_dict(self) -> dict:
        """A JSON-ready record."""
        return {"link": self.link, "requested_fluctuation": self.requested,
                "energy_method": {"inertia": self.estimate, **{k: v for k, v in self.energy.items()
                                                               if k in ("delta_E_max", "mean_speed",
                                                                        "mean_J", "mean_effort")},
                                  "simulated_fluctuation": self.estimate_fluctuation},
                "inertia": self.inertia, "fluctuation": self.fluctuation,
                "mean_speed": self.mean_speed,
                "iterations": [{"inertia": i, "fluctuation": d} for i, d in self.iterations]}


def _base_equations(scene: Scene) -> tuple[MotionEquations, str]:
    eq = MotionEquations(scene, require_simulate=False)
    link = ground_driven_link(scene)
    if link is None:
        raise SceneError([f"drivers[0]: a flywheel turns with a link driven by an R joint on "
                          f"the ground; joint '{eq.joint}' is not one"])
    if eq.period is None:
        raise SceneError(["loads: the scene's loads do not repeat with a whole number (at "
                          "most 64) of the driver's turns: the motion has no period"])
    return eq, link


def energy_method(eq: MotionEquations, delta: float) -> dict:
    """The energy method's flywheel for the fluctuation ``delta`` (see the module docstring):
    ``{"inertia", "delta_E_max", "mean_speed", "mean_J", "mean_effort", "q", "energy",
    "effort"}`` (the last three over one period, for the plots)."""
    start = eq.driver.start if eq.scene.simulate is None else eq.scene.simulate.start
    q = start + np.linspace(0.0, eq.period, GRID + 1)
    motor = eq.motor

    def balance(w):
        e0 = eq.effort(q, np.full_like(q, w), reduce=False)[0]
        return float(motor_effort(motor, w)) - float(np.mean(e0[:-1])), e0

    speeds = np.asarray(motor.speeds)
    lo, hi = (speeds[0], speeds[-1]) if len(speeds) > 1 else (0.0, 0.0)
    grid = np.linspace(lo, hi, 65)
    values = [balance(w)[0] if w != 0 else np.nan for w in grid]
    root = None
    for k in range(len(grid) - 1):
        a, b = values[k], values[k + 1]
        if np.isfinite(a) and np.isfinite(b) and a * b <= 0 and grid[k] > 0:
            root = brentq(lambda w: balance(w)[0], grid[k], grid[k + 1], xtol=1e-12)
            break
    if root is None:
        raise SceneError([f"drivers[0].motor: the motor's effort balances the mean resisting "
                          f"effort at no positive speed of its table ({lo:g} to {hi:g}): the "
                          "machine has no steady mean speed (a constant effort accelerates or "
                          "stops it)"])
    _, e0 = balance(root)
    M = float(motor_effort(motor, root))
    surplus = M - e0
    energy = np.concatenate([[0.0], np.cumsum(0.5 * (surplus[1:] + surplus[:-1]) * np.diff(q))])
    dE = float(energy.max() - energy.min())
    J = eq.inertia(q[:-1], reduce=False)[0]
    mean_J = float(np.mean(J))
    return {"inertia": max(dE / (delta * root**2) - mean_J, 0.0), "delta_E_max": dE,
            "mean_speed": root, "mean_J": mean_J, "mean_effort": M, "q": q, "energy": energy,
            "effort": e0}


def periodic_orbit(eq: MotionEquations, w_guess: float, rtol: float, w_start=None,
                   slope=None) -> dict:
    """The periodic motion over one period from the start angle (shooting, see the module
    docstring): ``turn_record`` of it, with ``w0``, the trajectory and ``slope``, the last
    secant's slope of ``w_end(w0) - w0``.  ``w_start`` and ``slope`` (a neighbouring orbit's,
    e.g. with another flywheel) start the search: a first shot from ``w_start`` and a Newton
    step with ``slope``, where a search without them takes two shots to make its first
    secant."""
    start = eq.driver.start if eq.scene.simulate is None else eq.scene.simulate.start
    target = start + eq.period

    def shot(w0):
        traj = integrate_motion(eq, 0.0, (start, w0), 1e3 * eq.period / w_guess,
                                rtol=rtol, target=target)
        if traj.end != "target":
            raise SceneError([f"simulate: no periodic motion near {w_guess:.6g} rad/s: from "
                              f"{w0:.6g} rad/s the machine does not complete a period "
                              f"({traj.message or 'too slow'})"])
        return float(traj(traj.t_end)[1][0]) - w0, traj

    w = w_guess if w_start is None else w_start
    f, traj = shot(w)
    before = None
    for _ in range(MAX_SHOTS):
        if abs(f) <= SHOOTING_TOL * w_guess:
            break
        if before is not None:
            if f == before[1]:
                break
            slope = (f - before[1]) / (w - before[0])
        step = -f / slope if slope else w * 1e-3
        before = (w, f)
        w = w + step
        f, traj = shot(w)
    else:
        raise SceneError([f"simulate: the periodic motion was not found in {MAX_SHOTS} "
                          "shots (its speed at the start angle does not settle)"])
    record = turn_record(traj, 0.0, traj.t_end, eq.period)
    return {**record, "w0": w, "trajectory": traj, "slope": slope}


def flywheel(scene: Scene, fluctuation: float, *, rtol: float = 1e-10,
             progress=None) -> FlywheelResult:
    """The moment of inertia to add to the driven link so that the periodic motion's speed
    fluctuation is at most ``fluctuation`` (the energy method's estimate, refined by
    simulation to within :data:`TOLERANCE` below the request).

    Parameters
    ----------
    scene : Scene
        A scene driven by a motor through an ``R`` joint on the ground, with inertia.
    fluctuation : float
        The requested coefficient of speed fluctuation ``(w_max - w_min) / w_m`` (> 0).
    rtol : float
        Relative tolerance of the simulations.
    progress : callable, optional
        Called with ``(inertia, fluctuation)`` after each simulated trial.

    Returns
    -------
    FlywheelResult
    """
    if not (isinstance(fluctuation, (int, float)) and 0 < fluctuation < 2):
        raise ValueError(f"fluctuation: must be a number in (0, 2), got {fluctuation!r}")
    eq, link = _base_equations(scene)
    energy = energy_method(eq, fluctuation)
    w_m = energy["mean_speed"]
    trials: list = []
    cache: dict = {}

    def measure(added):
        if added not in cache:
            near = trials and cache[trials[-1][0]]  # the last orbit starts the search
            orbit = periodic_orbit(MotionEquations(with_inertia(scene, link, added),
                                                   require_simulate=False), w_m, rtol,
                                   near["w0"] if near else None, near["slope"] if near else None)
            cache[added] = orbit
            trials.append((added, orbit["speed_fluctuation"]))
            if progress is not None:
                progress(added, orbit["speed_fluctuation"])
        return cache[added]["speed_fluctuation"]

    target = fluctuation * (1 - TOLERANCE / 2)
    x0 = energy["inertia"]
    d0 = measure(x0)
    estimate_delta = d0
    if d0 <= fluctuation and (x0 == 0.0 or d0 >= fluctuation * (1 - TOLERANCE)):
        best = x0
    else:
        best = _refine(measure, x0, d0, target, fluctuation, energy)
    orbit = cache[best]
    return FlywheelResult(fluctuation, x0, best, orbit["speed_fluctuation"], estimate_delta,
                          orbit["mean_speed"], energy, orbit, trials, link)


def _refine(measure, x0, d0, target, request, energy) -> float:
    """Secant on ``1/delta(I) - 1/target`` within a bracket (see the module docstring)."""
    lo, hi = (0.0, x0) if d0 <= target else (x0, None)
    scale = energy["delta_E_max"] / energy["mean_speed"] ** 2
    xa, fa = x0, 1 / d0 - 1 / target
    xb = x0 + 0.1 * scale / target if d0 > target else max(x0 * 0.9, 0.0)
    for _ in range(MAX_REFINE):
        db = measure(xb)
        if db <= request and db >= request * (1 - TOLERANCE):
            return xb
        if db > target:
            lo = max(lo, xb)
        else:
            hi = xb if hi is None else min(hi, xb)
        fb = 1 / db - 1 / target
        x = xb - fb * (xb - xa) / (fb - fa) if fb != fa else xb * 2
        if not (x > lo and (hi is None or x < hi)):
            x = 0.5 * (lo + hi) if hi is not None else 2 * max(xb, scale / target)
        xa, fa, xb = xb, fb, x
    raise SceneError([f"simulate: the flywheel was not refined to the fluctuation {request:g} "
                      f"in {MAX_REFINE} simulations"])

