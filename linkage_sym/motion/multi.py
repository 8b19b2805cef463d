"""The equations of motion of a mechanism of several degrees of freedom driven by its motors.

With ``q`` the drivers' coordinates (``n`` of them, one motor each), the kinetic energy of the
links is ``T = q̇ᵀ M(q) q̇ / 2`` with the *mass matrix*::

    M(q) = sum over the links of  m J_Gᵀ J_G + I J_ωᵀ J_ω

``J_G`` (2 x n) and ``J_ω`` (1 x n) the Jacobians of a link's centre-of-mass velocity and of its
angular velocity with respect to ``q̇``; Lagrange's equations read::

    M(q) q̈ + h(q, q̇) = τ_motors(q̇) - Q(q, q̇)

``h`` the velocity-product terms, ``h = sum m J_Gᵀ a_G⁰ + I J_ωᵀ α⁰`` (``a_G⁰``, ``α⁰`` the
accelerations at ``q̈ = 0``: ``J̇ q̇``), ``Q`` the efforts the loads, gravity, springs and
friction resist with.

**Formulation** (the one-degree-of-freedom case's, :mod:`~linkage_sym.motion.equations`, for
``n`` drivers).  The numeric kinetostatic solver's driving efforts at a state are affine in
``q̈`` (without friction)::

    effort(q, q̇, q̈) = E0(q, q̇) + M(q) q̈,   E0 = effort at q̈ = 0 = h + Q

(the virtual power of the d'Alembert forces along each driver's velocity coefficients), so the
motion is ``q̈ = M⁻¹ (τ - E0)`` exactly, every effect the solver includes counted once and as
``analyze`` counts it.  With Coulomb friction the effort is not affine in ``q̈``: ``q̈`` is the
root of ``effort(q, q̇, q̈) = τ``, by the steps ``q̈ -= M⁻¹ (effort - τ)`` from the affine one.

``M`` and ``h`` come from the SymPy-derived, lambdified and cached equations of the mechanism
(:func:`linkage_sym.compile_mechanism`): at ``q̇ = e_k`` (the ``k``-th unit vector) and
``q̈ = 0`` the velocities the generated code returns are the ``k``-th columns of ``J_G`` and
``J_ω``; at ``(q, q̇, 0)`` its accelerations are ``a_G⁰`` and ``α⁰`` (exact derivatives, no
finite difference).  ``h`` is not needed by the motion (it is part of ``E0``); it is offered
(:meth:`SeveralEquations.velocity_terms`) for checking the two against each other.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from linkage_sym.model import Scene
from linkage_sym.motion.equations import (
    MAX_ROOT_STEPS,
    MAX_TURNS_IN_PERIOD,
    TURN,
    StepFailure,
    check_simulation_scene,
    motor_effort,
)
from linkage_sym.motion.lean import SCREEN
from linkage_sym.numeric.results.result import OK

__all__ = ["SeveralEquations", "mass_matrix_at"]


class SeveralEquations:
    """The equations of motion of a scene's mechanism driven by its motors (several drivers).

    Parameters
    ----------
    scene : Scene
        A scene whose every driver carries a ``motor``, with ``effects.inertia`` true and a
        ``simulate`` section (checked here, each problem naming its field).
    """

    def __init__(self, scene: Scene):
        from linkage_sym.codegen.compile import compile_mechanism
        from linkage_sym.numeric.plan import compile_plan
        from linkage_sym.structure.parameters import driver_q0

        check_simulation_scene(scene, several=True)
        self.scene = scene
        self.drivers = scene.drivers
        self.joints = tuple(d.joint for d in scene.drivers)
        self.n = len(self.joints)
        self.motors = tuple(d.motor for d in scene.drivers)
        self.effort_plan = compile_plan(dataclasses.replace(scene, outputs=("driving",)))
        kin = dataclasses.replace(scene, outputs=("kinematics",), loads=(),
                                  effects=dataclasses.replace(scene.effects, gravity=None,
                                                              springs=False, friction=False))
        self.mechanism = compile_mechanism(kin)
        q0 = driver_q0(scene)
        self.q0 = np.array([q0[j] for j in self.joints])
        self.periods = _reduction_periods(scene)
        self.evaluations = 0
        self._last = (None, None)  # the last q at which M was evaluated, and its M
        self.nonlinear = bool(getattr(scene.effects, "friction", False))

    # -- the state's quantities --------------------------------------------
    def reduce(self, q) -> np.ndarray:
        """``q`` (``(n,)`` or ``(n, N)``) with each ``R`` driver's value reduced by whole
        periods to within half a period of its assembly value (see
        :meth:`~linkage_sym.motion.equations.MotionEquations.reduce`)."""
        q = np.array(q, float)
        for k, period in enumerate(self.periods):
            if period is not None:
                q[k] = self.q0[k] + np.remainder(q[k] - self.q0[k] + period / 2,
                                                 period) - period / 2
        return q

    def _states(self, q, qd, qdd) -> tuple[dict, dict, dict]:
        """The solvers' dicts of ``(N,)`` arrays from ``(n, N)`` arrays."""
        return tuple({j: np.asarray(a[k], float) for k, j in enumerate(self.joints)}
                     for a in (q, qd, qdd))

    def efforts(self, q, qd, qdd=None, reduce=True):
        """The drivers' efforts ``(n, N)`` at the states ``(q, qd, qdd)`` (``(n, N)`` arrays;
        ``qdd`` default 0), with the solver's result (its steps' statuses)."""
        q = np.asarray(q, float).reshape(self.n, -1)
        qd = np.asarray(qd, float).reshape(self.n, -1)
        qdd = np.zeros_like(q) if qdd is None else np.asarray(qdd, float).reshape(self.n, -1)
        res = self.effort_plan.run(*self._states(self.reduce(q) if reduce else q, qd, qdd))
        return np.array([res.forces.driving[j] for j in self.joints], float), res

    def mass_matrices(self, q, reduce=True) -> np.ndarray:
        """``M`` at the driver values ``q`` (``(n, N)``): ``(N, n, n)``, from the derived
        equations (one run at ``q̇ = e_k``, ``q̈ = 0`` for each driver ``k``)."""
        q = np.asarray(q, float).reshape(self.n, -1)
        N = q.shape[1]
        qq = np.repeat(self.reduce(q) if reduce else q, self.n, axis=1)  # state s*n + k
        qd = np.tile(np.eye(self.n), (1, N))
        res = self.mechanism.run(*self._states(qq, qd, np.zeros_like(qq)))
        M = np.zeros((N, self.n, self.n))
        for link in self.scene.links:
            lk = res.links[link.name]
            if link.mass > 0:
                V = np.asarray(lk.com_velocity).reshape(N, self.n, 2)
                M += link.mass * np.einsum("sic,sjc->sij", V, V)
            if link.inertia > 0:
                w = np.asarray(lk.omega).reshape(N, self.n)
                M += link.inertia * np.einsum("si,sj->sij", w, w)
        return M

    def velocity_terms(self, q, qd) -> np.ndarray:
        """``h(q, q̇)`` at one state (``(n,)`` each): ``sum m J_Gᵀ a_G⁰ + I J_ωᵀ α⁰`` from the
        derived equations (the unit-speed velocities and the accelerations at ``q̈ = 0``)."""
        q = np.asarray(q, float).reshape(self.n, 1)
        qq = np.repeat(self.reduce(q), self.n + 1, axis=1)
        qd_all = np.hstack([np.eye(self.n), np.asarray(qd, float).reshape(self.n, 1)])
        res = self.mechanism.run(*self._states(qq, qd_all, np.zeros_like(qq)))
        h = np.zeros(self.n)
        for link in self.scene.links:
            lk = res.links[link.name]
            if link.mass > 0:
                v, a = np.asarray(lk.com_velocity), np.asarray(lk.com_acceleration)
                h += link.mass * (v[:self.n] @ a[self.n])
            if link.inertia > 0:
                h += link.inertia * np.asarray(lk.omega)[:self.n] * lk.alpha[self.n]
        return h

    def acceleration(self, q, qd) -> np.ndarray:
        """``q̈`` (``(n,)``) at the state ``(q, qd)``; raises :class:`StepFailure` where the
        mechanism cannot be solved or ``M`` is not positive definite."""
        self.evaluations += 1
        q, qd = np.asarray(q, float), np.asarray(qd, float)
        e0 = self._efforts_at(q, qd, np.zeros(self.n))
        key = tuple(q)
        if key != self._last[0]:
            self._last = (key, self._mass_at(q, qd))
        L = self._last[1]
        tau = np.array([float(motor_effort(m, v)) for m, v in zip(self.motors, qd)])
        qdd = _solve(L, tau - e0)
        if self.nonlinear:
            scale = np.abs(tau) + np.abs(e0)
            for _ in range(MAX_ROOT_STEPS):
                r = self._efforts_at(q, qd, qdd) - tau
                if np.all(np.abs(r) <= 1e-13 * (scale + np.abs(_times(L, qdd)))):
                    return qdd
                qdd = qdd - _solve(L, r)
            raise StepFailure(q, qd, f"the accelerations at which the drivers' efforts equal "
                              f"the motors' were not found in {MAX_ROOT_STEPS} steps")
        return qdd

    def _efforts_at(self, q, qd, qdd) -> np.ndarray:
        """The drivers' efforts at one state (``q`` reduced); :class:`StepFailure` where
        the step is not ``ok``."""
        state = self._states(self.reduce(q).reshape(self.n, 1), qd.reshape(self.n, 1),
                             np.asarray(qdd, float).reshape(self.n, 1))
        driving, status, messages = self.effort_plan.driving(*state)
        if status[0] != OK:
            raise StepFailure(q, qd, f"{status[0]}: {messages[0]}")
        return np.array([driving[j][0] for j in self.joints], float)

    def _mass_at(self, q, qd) -> np.ndarray:
        """The Cholesky factor of ``M`` at one state (``q`` reduced), by the full run where
        the lean one declines the state; :class:`StepFailure` where ``M`` is not positive
        definite."""
        qr = self.reduce(q)
        M = mass_matrix_at(self.mechanism, self.scene, self.joints, qr)
        if M is None:
            M = self.mass_matrices(qr, reduce=False)[0]
        try:
            return np.linalg.cholesky(M)
        except np.linalg.LinAlgError:
            raise StepFailure(q, qd, "the mass matrix M is not positive definite (eigenvalues "
                              f"{', '.join(f'{v:.3g}' for v in np.linalg.eigvalsh(M))}): the "
                              "motion has no equation there") from None

    def accelerations(self, q, qd):
        """``q̈`` at many states at once (``(n, N)`` arrays: the states in order along one
        motion, not reduced), with ``M`` ``(N, n, n)`` and the solver's result at them."""
        q, qd = np.asarray(q, float), np.asarray(qd, float)
        tau = np.array([motor_effort(m, v) for m, v in zip(self.motors, qd)])
        e0, res = self.efforts(q, qd, reduce=False)
        M = self.mass_matrices(q, reduce=False)
        with np.errstate(invalid="ignore", divide="ignore"):
            qdd = _batch_solve(M, tau - e0)
            scale = np.abs(tau) + np.abs(e0)
            for _ in range(MAX_ROOT_STEPS if self.nonlinear else 0):
                e, res = self.efforts(q, qd, qdd, reduce=False)
                r = np.where(res.status == OK, e - tau, 0.0)
                if np.all(np.abs(r) <= 1e-13 * (scale + np.abs(np.einsum("sij,js->is", M, qdd)))):
                    break
                qdd = qdd - _batch_solve(M, r)
        return qdd, M, res


def _solve(L: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``M⁻¹ b`` from the Cholesky factor ``L`` of ``M``."""
    return np.linalg.solve(L.T, np.linalg.solve(L, b))


def _times(L: np.ndarray, x: np.ndarray) -> np.ndarray:
    """``M x`` from the Cholesky factor ``L`` of ``M``."""
    return L @ (L.T @ x)


def _batch_solve(M: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``M⁻¹ b`` for ``M`` ``(N, n, n)`` and ``b`` ``(n, N)``: ``(n, N)`` (NaN where ``M`` is
    singular or not finite)."""
    out = np.full(b.shape, np.nan)
    good = np.all(np.isfinite(M), axis=(1, 2)) & (np.abs(np.linalg.det(np.where(
        np.isfinite(M), M, 0.0))) > 0)
    if good.any():
        out[:, good] = np.linalg.solve(M[good], b.T[good][..., None])[..., 0].T
    return out


def mass_matrix_at(mech, scene: Scene, joints: tuple, q) -> np.ndarray | None:
    """``M`` (``(n, n)``) at the driver values ``q`` (one state) from the compiled mechanism
    ``mech`` of ``scene``'s links (kinematics only), or ``None`` where the state needs the full
    run (a group not assembled, or a block screened as near-singular).  What
    :meth:`SeveralEquations.mass_matrices` computes, without a result's bookkeeping
    (:mod:`~linkage_sym.motion.lean` does the same for one driver).

    Examples
    --------
    >>> import linkage_sym
    >>> from linkage_sym.examples import load_example
    >>> eq = SeveralEquations(load_example("fivebar_motors"))
    >>> q = np.array([0.7, 2.1])
    >>> M = mass_matrix_at(eq.mechanism, eq.scene, eq.joints, q)
    >>> full = eq.mass_matrices(q, reduce=False)[0]
    >>> bool(np.max(np.abs(M - full)) <= 1e-14 * np.max(np.abs(full)))
    True
    """
    n = len(joints)
    qs = {j: np.full(n, float(q[k])) for k, j in enumerate(joints)}
    unit = {j: np.eye(n)[k] for k, j in enumerate(joints)}
    Qs, QDs, QDDs, X, failed, _ = mech.step_positions(qs, unit, {j: np.zeros(n) for j in joints})
    if np.any(failed >= 0):
        return None
    Qk, QDk, QDDk = list(Qs), list(QDs), list(QDDs)
    CS = (list(np.cos(X)), list(np.sin(X)))
    A, Bqd = mech.rate_system(X, Qk, QDk, CS)
    for ratio in A.ratios():
        if ratio is not None and not np.all(ratio >= SCREEN):
            return None
    XD = np.asarray(A.solve(Bqd))
    with np.errstate(invalid="ignore"):
        pts = mech.call("points", None, X=list(X), XD=list(XD), XDD=list(np.zeros_like(XD)),
                        Q=Qk, QD=QDk, QDD=QDDk, CS=CS)
    M = np.zeros((n, n))
    for link in scene.links:
        if link.mass > 0:
            V = np.array([np.broadcast_to(np.asarray(r, float), (n,))
                          for r in mech.art.rows(pts, f"com:{link.name}:1")])  # (2, n)
            M += link.mass * (V.T @ V)
        if link.inertia > 0:
            w = XD[mech.angle_of[link.name]]
            M += link.inertia * np.outer(w, w)
    return M


def _reduction_periods(scene: Scene) -> tuple:
    """The period with which each driver's value may be reduced (``None``: not reduced)."""
    if any(getattr(spring, "joint", None) for spring in getattr(scene, "springs", ()) or ()):
        return (None,) * len(scene.drivers)  # a torsion spring's angle counts whole turns
    out = []
    for d in scene.drivers:
        periods = [load.period for load in scene.loads
                   if load.period is not None and load.driver == d.joint
                   and (load.table is not None or load.active is not None)]
        span = None
        for turns in range(1, MAX_TURNS_IN_PERIOD + 1) if d.kind == "R" else ():
            if all(abs(turns * TURN / p - round(turns * TURN / p)) < 1e-9 for p in periods):
                span = turns * TURN
                break
        out.append(span)
    return tuple(out)


def where(eq: SeveralEquations, q, qd) -> str:
    """The drivers' values and speeds, in the scene's units."""
    parts = []
    for d, v, w in zip(eq.drivers, np.atleast_1d(q), np.atleast_1d(qd)):
        if d.kind == "R":
            parts.append(f"{d.joint} at {math.degrees(v):.6g} degrees, {w:.6g} rad/s")
        else:
            parts.append(f"{d.joint} at {v:.6g} m, {w:.6g} m/s")
    return "drivers " + "; ".join(parts)

