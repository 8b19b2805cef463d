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
  (:meth:`~linkage_sym.numeric.plan.Plan.driving`), with its status.

A state the generated code screens as near-singular (or cannot assemble) goes through the
full run, so the result is the full run's in every case.
"""

from __future__ import annotations

import numpy as np

from linkage_sym.numeric.results.result import OK

__all__ = ["effort_at", "inertia_at", "numeric_inertia_at"]

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
    J = dJ = 0.0
    for link in scene.links:
        st = S[link.name]
        if link.mass > 0:
            vx, vy = (float(np.asarray(v).reshape(-1)[0]) for v in st.point_velocity(link.com))
            ax, ay = (float(np.asarray(a).reshape(-1)[0])
                      for a in st.point_acceleration(link.com))
            J += link.mass * (vx * vx + vy * vy)
            dJ += 2.0 * link.mass * (vx * ax + vy * ay)
        if link.inertia > 0:
            w = float(np.asarray(st.w).reshape(-1)[0])
            al = float(np.asarray(st.al).reshape(-1)[0])
            J += link.inertia * w * w
            dJ += 2.0 * link.inertia * w * al
    return J, dJ
