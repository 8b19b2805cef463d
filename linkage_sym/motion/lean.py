"""The equation of motion's quantities at one state, without a result's bookkeeping.

The integrator asks for ``qdd`` at one state ``(q, qd)`` some five hundred times a turn of
the driver; :meth:`~linkage_sym.numeric.plan.Plan.run` and
:meth:`~linkage_sym.codegen.runtime.CompiledMechanism.run` build a whole
:class:`~linkage_sym.numeric.results.result.Analysis` (every point's record, warnings,
transmission angles, accuracies) each time, most of an evaluation's cost.  Here the same
computations are called for the one state and only what the equation reads is kept:

* :func:`inertia_at`: ``J`` and ``J'`` from the generated functions of the compiled
  mechanism (the positions along the same path from the assembly configuration, the same
  rate systems, the same ``points`` function), summed as
  :meth:`~linkage_sym.motion.equations.MotionEquations.inertia` sums them;
* :func:`effort_at`: the driver's effort from the numeric plan's solve
  (:meth:`~linkage_sym.numeric.plan.Plan.driving`), with its status;
* :func:`effort_inertia_at`: both of what the integrator's equation reads, the effort at
  ``(q, qd, qdd)`` and ``J`` at ``q``, from **one** solve of the numeric plan over two
  states at the same ``q`` (the second at unit speed and no acceleration, whose velocities
  are the velocity coefficients): an evaluation's positions, rates and bookkeeping paid once
  instead of once in each layer.  ``J`` is then the numeric solver's, equal to the derived
  equations' to rounding (:func:`inertia_at`; 1e-12 in the tests).

:func:`inertia_at` and :func:`numeric_inertia_at` (one state, ``J`` and ``J'``) are the
references the tests hold :func:`effort_inertia_at`'s ``J`` to; :func:`inertia_at` declines
(``None``) a state the generated code screens as near-singular or cannot assemble.
"""

from __future__ import annotations

import numpy as np

from linkage_sym.numeric.results.result import OK

__all__ = ["effort_at", "effort_inertia_at", "inertia_at", "numeric_inertia_at"]

SCREEN = 1e-3
"""The Hadamard ratio under which the compiled mechanism's run computes a condition number
(:mod:`linkage_sym.codegen.runtime`); such a state takes the full run here."""


def inertia_at(mech, scene, joint: str, q: float):
    """``(J, J')`` at the driver value ``q`` (one state) from the compiled mechanism ``mech``
    of ``scene``'s links (kinematics only), or ``None`` where the state needs the full run
    (a group not assembled, or a block screened as near-singular).

    Examples
    --------
    >>> import linkage_sym
    >>> from linkage_sym.examples import example_dict
    >>> from linkage_sym.motion.equations import MotionEquations
    >>> d = example_dict("crank_rocker_motor")
    >>> eq = MotionEquations(linkage_sym.load_scene(d), require_simulate=False)
    >>> J, dJ = inertia_at(eq.mechanism, eq.scene, eq.joint, 0.7)
    >>> full = eq.inertia(0.7, reduce=False)
    >>> bool(abs(J - full[0][0]) <= 1e-14 * J and abs(dJ - full[1][0]) <= 1e-12 * J)
    True
    """
    one = np.ones(1)
    Qs, QDs, QDDs, X, failed, _ = mech.step_positions({joint: np.array([q])}, {joint: one},
                                                      {joint: np.zeros(1)})
    if failed[0] >= 0:
        return None
    Qk, QDk, QDDk = list(Qs), list(QDs), list(QDDs)
    CS = (list(np.cos(X)), list(np.sin(X)))
    A, Bqd = mech.rate_system(X, Qk, QDk, CS)
    for ratio in A.ratios():
        if ratio is not None and not ratio[0] >= SCREEN:
            return None
    XD = np.asarray(A.solve(Bqd))
    XDD = np.asarray(A.solve(mech.accelerations_rhs(list(X), list(XD), Qk, QDk, QDDk, CS,
                                                    shape=1)))
    with np.errstate(invalid="ignore"):
        pts = mech.call("points", None, X=list(X), XD=list(XD), XDD=list(XDD), Q=Qk, QD=QDk,
                        QDD=QDDk, CS=CS)
    J = dJ = 0.0
    for link in scene.links:
        if link.mass > 0:
            vx, vy = (float(np.asarray(r).reshape(-1)[0])
                      for r in mech.art.rows(pts, f"com:{link.name}:1"))
            ax, ay = (float(np.asarray(r).reshape(-1)[0])
                      for r in mech.art.rows(pts, f"com:{link.name}:2"))
            J += link.mass * (vx * vx + vy * vy)
            dJ += 2.0 * link.mass * (vx * ax + vy * ay)
        if link.inertia > 0:
            c = mech.angle_of[link.name]
            w, al = float(XD[c, 0]), float(XDD[c, 0])
            J += link.inertia * w * w
            dJ += 2.0 * link.inertia * w * al
    return J, dJ


def effort_at(plan, joint: str, q: float, qd: float, qdd: float) -> tuple:
    """The driver's effort at one state from the numeric ``plan`` (its ``driving`` output):
    ``(effort, status, message)``, ``message`` ``None`` where the status is ``ok``.

    Examples
    --------
    >>> import linkage_sym
    >>> from linkage_sym.examples import example_dict
    >>> from linkage_sym.motion.equations import MotionEquations
    >>> eq = MotionEquations(linkage_sym.load_scene(example_dict("crank_rocker_motor")),
    ...                      require_simulate=False)
    >>> e, status, _ = effort_at(eq.effort_plan, eq.joint, 0.7, 10.0, 0.0)
    >>> bool(status == "ok" and e == eq.effort(0.7, 10.0, reduce=False)[0][0])
    True
    """
    driving, status, messages = plan.driving({joint: np.array([q])}, {joint: np.array([qd])},
                                             {joint: np.array([qdd])})
    ok = status[0] == OK
    return float(driving[joint][0]), str(status[0]), None if ok else messages[0]


def numeric_inertia_at(plan, scene, joint: str, q: float):
    """``(J, J')`` at the driver value ``q`` (one state) from the numeric ``plan`` of
    ``scene``'s links (kinematics only: a scene the symbolic layer does not derive), summed
    as :meth:`~linkage_sym.motion.equations.MotionEquations.inertia` sums them from the
    links' states at unit speed, or ``None`` where the step is not ``ok``.

    Examples
    --------
    >>> import linkage_sym
    >>> from linkage_sym.examples import example_dict
    >>> from linkage_sym.motion.equations import MotionEquations
    >>> d = example_dict("cam_eccentric_rocker")
    >>> d["drivers"][0]["motor"] = {"torque": 1.0}
    >>> eq = MotionEquations(linkage_sym.load_scene(d), require_simulate=False)
    >>> J, dJ = numeric_inertia_at(eq.mechanism, eq.scene, eq.joint, 0.7)
    >>> full = eq.inertia(0.7, reduce=False)
    >>> bool(abs(J - full[0][0]) <= 1e-14 * J and abs(dJ - full[1][0]) <= 1e-12 * J)
    True
    """
    S, status = plan.link_states({joint: np.array([q])}, {joint: np.ones(1)},
                                 {joint: np.zeros(1)})
    if status[0] != OK:
        return None
    return _unit_speed_sums(scene, S, 0, True)


def effort_inertia_at(plan, scene, joint: str, q: float, qd: float, qdd: float) -> tuple:
    """The driver's effort at the state ``(q, qd, qdd)`` and ``J`` at ``q``, from one solve
    of the numeric ``plan`` (of ``scene``) over the two states ``(q, qd, qdd)`` and
    ``(q, 1, 0)``: ``(effort, J, status, message)``, ``message`` ``None`` where the status is
    ``ok`` (``J`` is read only then: the second state has the first one's positions, so the
    same status).

    Examples
    --------
    >>> import linkage_sym
    >>> from linkage_sym.examples import example_dict
    >>> from linkage_sym.motion.equations import MotionEquations
    >>> eq = MotionEquations(linkage_sym.load_scene(example_dict("crank_rocker_motor")),
    ...                      require_simulate=False)
    >>> e, J, status, _ = effort_inertia_at(eq.effort_plan, eq.scene, eq.joint, 0.7, 10.0, 0.0)
    >>> e0, _, _ = effort_at(eq.effort_plan, eq.joint, 0.7, 10.0, 0.0)
    >>> Jd, _ = inertia_at(eq.mechanism, eq.scene, eq.joint, 0.7)
    >>> bool(status == "ok" and abs(e - e0) <= 1e-13 * abs(e0) and abs(J - Jd) <= 1e-14 * Jd)
    True
    """
    Q = np.array([q, q])
    driving, S, status, messages = plan.driving_states(
        {joint: Q}, {joint: np.array([qd, 1.0])}, {joint: np.array([qdd, 0.0])})
    if status[0] != OK:
        return float(driving[joint][0]), float("nan"), str(status[0]), messages[0]
    return float(driving[joint][0]), _unit_speed_sums(scene, S, 1, False)[0], OK, None


def _unit_speed_sums(scene, S, i: int, derivative: bool) -> tuple:
    """``(J, J')`` summed from the links' states ``S`` at step ``i``, a state at unit speed
    and no acceleration (``J'`` 0.0 unless ``derivative``)."""
    J = dJ = 0.0
    for link in scene.links:
        st = S[link.name]
        if link.mass > 0:
            vx, vy = (_at(v, i) for v in st.point_velocity(link.com))
            J += link.mass * (vx * vx + vy * vy)
            if derivative:
                ax, ay = (_at(a, i) for a in st.point_acceleration(link.com))
                dJ += 2.0 * link.mass * (vx * ax + vy * ay)
        if link.inertia > 0:
            w = _at(st.w, i)
            J += link.inertia * w * w
            if derivative:
                dJ += 2.0 * link.inertia * w * _at(st.al, i)
    return J, dJ


def _at(value, i: int) -> float:
    """Step ``i`` of a state's component (an array over the steps, or one value for all)."""
    a = np.asarray(value).reshape(-1)
    return float(a[i] if a.size > 1 else a[0])
