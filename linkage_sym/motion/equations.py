"""The equation of motion of a mechanism of one degree of freedom driven by a motor.

With ``q`` the driver's coordinate (an angle, or a slide for a ``P`` driver), the kinetic
energy of the links is ``T = J(q) qd^2 / 2`` with the *equivalent moment of inertia*
(an equivalent mass for a ``P`` driver)::

    J(q) = sum over the links of (m |v_G|^2 + I w^2) / qd^2

and Lagrange's equation reads ``J qdd + J'(q) qd^2 / 2 = M_motor(qd) - Q(q, qd)``, ``Q``
the effort the loads, gravity (and any other effect the scene asks for) resist with.

**Formulation.**  Neither ``Q`` nor ``J'`` is written out here: the inverse dynamics of the
numeric kinetostatic solver (:func:`linkage_sym.compile_plan`) gives the driver's effort at
any state ``(q, qd, qdd)``, and for a mechanism whose forces do not depend on the
accelerations otherwise than through the d'Alembert forces that effort is affine in ``qdd``::

    effort(q, qd, qdd) = E0(q, qd) + J(q) qdd,   E0 = effort at qdd = 0

(power balance: ``effort qd = dT/dt - power of the other forces``, and
``dT/dt = J qd qdd + J' qd^3 / 2``).  So ``E0 = J' qd^2 / 2 + Q`` and the motion is::

    qdd = (M_motor(qd) - E0(q, qd)) / J(q)

exactly, with every effect the kinetostatic solver includes counted once and in the same way
as ``analyze`` counts it: springs and dampers enter ``E0`` (a spring's force depends on the
state, not on ``qdd``) as soon as the solver includes them.  Coulomb friction makes the effort
nonlinear in ``qdd`` (the reactions, whose magnitudes the friction follows, depend on it):
for a scene whose ``effects`` ask for friction, ``qdd`` is the root of
``effort(q, qd, qdd) = M_motor(qd)``, the affine step above its first iterate
(:meth:`MotionEquations.acceleration`).

``J`` and ``J'`` come from the SymPy-derived, lambdified and cached equations of the
mechanism (:func:`linkage_sym.compile_mechanism`): at ``qd = 1`` and ``qdd = 0`` the
velocities the generated code returns *are* the velocity coefficients (``v_G / qd``,
``w / qd``) and the accelerations their derivatives with respect to ``q``
(``a_G = dv_G/dq qd^2 + v_G qdd``), so::

    J  = sum m |v_G|^2 + I w^2,   J' = 2 sum m v_G . a_G + I w alpha   (at qd = 1, qdd = 0)

both exact (no finite difference).  The symbolic layer derives no cam contact: a scene with
one takes the same sums from the numeric plan's kinematics at ``qd = 1`` and ``qdd = 0``
(its velocities and accelerations are the same coefficients and their derivatives, exact as
well).  The integrator's evaluations
(:meth:`MotionEquations.acceleration`) read ``J`` alone, and take it from the numeric solve
that gives the effort, at a second state of unit speed
(:func:`~linkage_sym.motion.lean.effort_inertia_at`): one solve an evaluation, its ``J`` the
derived equations' to rounding.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from linkage_sym.errors import SYMBOLIC_LACKS, SceneError
from linkage_sym.model import GROUND, Scene
from linkage_sym.motion.lean import effort_at, effort_inertia_at

__all__ = ["MotionEquations", "StepFailure", "motor_effort"]

TURN = 2.0 * math.pi
MAX_ROOT_STEPS = 50
"""Most fixed-point steps on ``qdd`` where the effort is not affine in it (friction)."""
MAX_TURNS_IN_PERIOD = 64
"""Most turns of the driver over which the scene's loads repeat (their ``period_deg``) for the
driver's angle to be reduced by whole periods before each solve (see
:meth:`MotionEquations.reduce`)."""


class StepFailure(RuntimeError):
    """The mechanism cannot be solved at a state of the integration (it cannot be
    assembled, or it is singular, or its equivalent inertia vanishes there)."""

    def __init__(self, q: float, qd: float, message: str):
        self.q, self.qd = q, qd
        super().__init__(message)


def motor_effort(motor, speed):
    """The effort of ``motor`` (a :class:`~linkage_sym.model.scene.Motor`) at ``speed``.

    Linear between the table's rows, the end rows' effort held beyond them.

    Examples
    --------
    >>> from linkage_sym.model import Motor
    >>> m = Motor("torque", (0.0, 150.0), (60.0, 0.0))
    >>> [float(motor_effort(m, w)) for w in (-5.0, 75.0, 200.0)]
    [60.0, 30.0, 0.0]
    """
    return np.interp(speed, motor.speeds, motor.efforts)


def check_simulation_scene(scene: Scene, require_simulate: bool = True,
                           several: bool = False) -> None:
    """Refuse, naming the field, a scene that cannot be simulated (``require_simulate``:
    its ``simulate`` section too; ``several``: several drivers allowed, each with a motor,
    :mod:`~linkage_sym.motion.multi`)."""
    problems = []
    if scene.simulate is None and require_simulate:
        problems.append("simulate: required to simulate the machine's motion (duration, "
                        "samples, the start and its speed)")
    if len(scene.drivers) != 1 and not several:
        problems.append(f"drivers: the equation of motion of one degree of freedom (and the "
                        f"flywheel's design) takes one driver; the scene has "
                        f"{len(scene.drivers)}")
    for i, d in enumerate(scene.drivers):
        if d.motor is None:
            key = "torque" if d.kind == "R" else "force"
            problems.append(f"drivers[{i}].motor: required to simulate (the {key} the motor "
                            f"gives against its speed)")
    if not scene.effects.inertia:
        problems.append("effects.inertia: must be true to simulate: without the masses' "
                        "inertia the motion has no equation")
    elif not any(link.mass > 0 or link.inertia > 0 for link in scene.links):
        problems.append("links: every link is massless (mass and inertia 0); the motion of a "
                        "machine without inertia has no equation")
    if problems:
        raise SceneError(problems)


class MotionEquations:
    """The equation of motion of a scene's mechanism driven by its motor (one driver).

    Parameters
    ----------
    scene : Scene
        A scene with one driver carrying a ``motor``, ``effects.inertia`` true and a
        ``simulate`` section (checked here, each problem naming its field).
    require_simulate : bool
        Whether the ``simulate`` section is required (the flywheel's search needs none).
    numeric_inertia : bool, optional
        ``J`` and ``J'`` from the numeric solver's kinematics at unit speed rather than from
        the derived equations; default: where the symbolic layer derives no joint of the
        scene (a cam contact) only.
    """

    def __init__(self, scene: Scene, require_simulate: bool = True,
                 numeric_inertia: bool | None = None):
        from linkage_sym.codegen.compile import compile_mechanism
        from linkage_sym.numeric.plan import compile_plan

        check_simulation_scene(scene, require_simulate)
        self.scene = scene
        self.driver = scene.drivers[0]
        self.joint = self.driver.joint
        self.motor = self.driver.motor
        # the effort at a state: the driving output only (no kinematics records)
        self.effort_plan = compile_plan(dataclasses.replace(scene, outputs=("driving",)))
        # J and J' need the links' motion alone: no loads, gravity, springs or friction (those
        # reach the equation through the kinetostatic solver's effort)
        kin = dataclasses.replace(scene, outputs=("kinematics",), loads=(),
                                  effects=dataclasses.replace(scene.effects, gravity=None,
                                                              springs=False, friction=False))
        # the symbolic layer derives no cam contact (SYMBOLIC_LACKS): such a scene's J and J'
        # come from the numeric solver's kinematics at unit speed (the same sums, exact too)
        self.numeric_inertia = (any(j.type in SYMBOLIC_LACKS for j in scene.joints)
                                if numeric_inertia is None else bool(numeric_inertia))
        self.mechanism = compile_plan(kin) if self.numeric_inertia else compile_mechanism(kin)
        self.q0 = float(_assembly_value(scene))
        self.period = _reduction_period(scene)
        self.evaluations = 0
        # friction (the contract's effects.friction) makes the effort nonlinear in qdd
        self.nonlinear = bool(getattr(scene.effects, "friction", False))

    # -- the state's quantities --------------------------------------------
    def reduce(self, q):
        """``q`` reduced by whole periods to within half a period of the assembly value:
        the mechanism's configuration and its loads repeat with each turn of an ``R``
        driver (or with the loads' period, a whole number of turns), and the solver's
        path from the assembly configuration stays short.  ``P`` drivers: ``q`` itself."""
        if self.period is None:
            return q
        return self.q0 + np.remainder(np.asarray(q) - self.q0 + self.period / 2,
                                      self.period) - self.period / 2

    def effort(self, q, qd, qdd=None, reduce=True):
        """The driver's effort at the states ``(q, qd, qdd)`` (arrays ``(N,)``; ``qdd``
        default 0), with the solver's result (its steps' statuses)."""
        q = np.atleast_1d(np.asarray(q, float))
        qd = np.atleast_1d(np.asarray(qd, float))
        qdd = np.zeros_like(q) if qdd is None else np.atleast_1d(np.asarray(qdd, float))
        res = self.effort_plan.run({self.joint: self.reduce(q) if reduce else q},
                                   {self.joint: qd}, {self.joint: qdd})
        return np.asarray(res.forces.driving[self.joint], float), res

    def inertia(self, q, reduce=True):
        """``(J, J')`` at the driver values ``q`` (arrays ``(N,)``), from the derived equations
        (from the numeric solver's kinematics for a scene the symbolic layer does not derive:
        a cam contact)."""
        q = np.atleast_1d(np.asarray(q, float))
        res = self.mechanism.run({self.joint: self.reduce(q) if reduce else q},
                                 {self.joint: np.ones_like(q)}, {self.joint: np.zeros_like(q)})
        J = np.zeros(len(q))
        dJ = np.zeros(len(q))
        for link in self.scene.links:
            lk = res.links[link.name]
            if link.mass > 0:
                v, a = np.asarray(lk.com_velocity), np.asarray(lk.com_acceleration)
                J += link.mass * np.einsum("ij,ij->i", v, v)
                dJ += 2.0 * link.mass * np.einsum("ij,ij->i", v, a)
            if link.inertia > 0:
                w, al = np.asarray(lk.omega), np.asarray(lk.alpha)
                J += link.inertia * w * w
                dJ += 2.0 * link.inertia * w * al
        return J, dJ

    def acceleration(self, q: float, qd: float, piece=None) -> float:
        """``qdd`` at the state ``(q, qd)``; raises :class:`StepFailure` where the mechanism
        cannot be solved.  One state, without a result's bookkeeping
        (:mod:`~linkage_sym.motion.lean`): the effort and ``J`` from one solve of the
        numeric plan (:func:`~linkage_sym.motion.lean.effort_inertia_at`), :meth:`effort`
        and :meth:`inertia` to rounding.  With a ``piece``
        (:class:`~linkage_sym.motion.pieces.Piece`), the equation frozen on it: its effort plan
        and its motor line."""
        self.evaluations += 1
        plan = self.effort_plan if piece is None else piece.plan
        # the effort and J from one solve of the plan (lean.effort_inertia_at)
        e0, J = self._effort_at(q, qd, 0.0, plan, inertia=True)
        if not J > 0:
            raise StepFailure(q, qd, f"the equivalent moment of inertia J is {J:.3g}: the "
                              "motion has no equation there")
        M = float(motor_effort(self.motor, qd)) if piece is None else piece.motor(qd)
        qdd = (M - e0) / J
        if self.nonlinear:
            qdd = self._root(q, qd, qdd, M, J, abs(M) + abs(e0), plan)
        return float(qdd)

    def _effort_at(self, q: float, qd: float, qdd: float, plan=None, inertia=False):
        """The driver's effort at one state (``q`` reduced) from ``plan`` (default the
        scene's), with ``J`` at ``q`` from the same solve where ``inertia`` (a pair then);
        :class:`StepFailure` where the step is not ``ok``."""
        plan = self.effort_plan if plan is None else plan
        qr = float(self.reduce(q))
        if inertia:
            e, J, status, message = effort_inertia_at(plan, self.scene, self.joint, qr, qd, qdd)
        else:
            e, status, message = effort_at(plan, self.joint, qr, qd, qdd)
        if status != "ok":  # the status once, where the step's message does not begin with it
            raise StepFailure(q, qd, message if message.startswith(f"{status}:") else
                              f"{status}: {message}")
        return (e, J) if inertia else e

    def _root(self, q, qd, qdd, M, J, scale, plan=None):
        """``qdd`` where the effort equals ``M`` when the effort is not affine in ``qdd``
        (friction): fixed-point steps ``qdd -= (effort - M) / J`` from the affine one."""
        for _ in range(MAX_ROOT_STEPS):
            r = self._effort_at(q, qd, qdd, plan) - M
            if abs(r) <= 1e-13 * (scale + abs(J * qdd)):
                return qdd
            qdd -= r / J
        raise StepFailure(q, qd, f"the acceleration at which the driver's effort equals the "
                          f"motor's ({M:.6g}) was not found in {MAX_ROOT_STEPS} steps")

    def accelerations(self, q, qd):
        """``qdd`` at many states at once (arrays: the states in order along one motion, not
        reduced), with ``J`` and the solver's result at them (statuses; ``driving`` the
        effort at ``qdd``)."""
        q = np.asarray(q, float)
        qd = np.asarray(qd, float)
        M = motor_effort(self.motor, qd)
        e0, res = self.effort(q, qd, reduce=False)
        J = self.inertia(q, reduce=False)[0]
        with np.errstate(invalid="ignore", divide="ignore"):
            qdd = (M - e0) / J
            scale = np.abs(M) + np.abs(e0)
            for _ in range(MAX_ROOT_STEPS if self.nonlinear else 0):
                e, res = self.effort(q, qd, qdd, reduce=False)
                r = np.where(res.status == "ok", e - M, 0.0)
                if np.all(np.abs(r) <= 1e-13 * (scale + np.abs(J * qdd))):
                    break
                qdd = qdd - r / J
        return qdd, J, res


def _assembly_value(scene: Scene) -> float:
    from linkage_sym.structure.parameters import driver_q0

    return driver_q0(scene)[scene.drivers[0].joint]


def _reduction_period(scene: Scene) -> float | None:
    """The period with which the driver's angle may be reduced (``None``: not reduced)."""
    d = scene.drivers[0]
    if d.kind != "R":
        return None
    # a torsion spring's angle (the contract's springs at an R joint) counts whole turns: the
    # forces then do not repeat with the driver's turns, and the angle is not reduced
    if any(getattr(spring, "joint", None) for spring in getattr(scene, "springs", ()) or ()):
        return None
    periods = [load.period for load in scene.loads
               if load.period is not None and load.driver in (None, d.joint)
               and (load.table is not None or load.active is not None)]
    for turns in range(1, MAX_TURNS_IN_PERIOD + 1):
        span = turns * TURN
        if all(abs(span / p - round(span / p)) < 1e-9 for p in periods):
            return span
    return None


def ground_driven_link(scene: Scene) -> str | None:
    """The link an ``R`` driver on the ground turns (``None`` otherwise)."""
    d = scene.drivers[0]
    joint = scene.joint(d.joint)
    if d.kind == "R" and GROUND in joint.links:
        return joint.links[1] if joint.links[0] == GROUND else joint.links[0]
    return None
