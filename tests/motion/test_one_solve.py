"""An evaluation of the equation of motion from one solve (``motion.lean.effort_inertia_at``).

The integrator's evaluation takes the driver's effort and ``J`` from one solve of the
numeric plan over two states at the same ``q`` (the second at unit speed).  Checked against
the two solves it replaces, at states over three turns either way of the assembly
configuration (the reduction by whole turns), at speeds of either sign and at rest:

* ``J`` against the derived equations' (the generated functions of the compiled mechanism,
  which share no code with the numeric solver), to 1e-12 relative; a cam, which the
  symbolic layer does not derive, against the numeric solver's at that one state;
* the effort against the plan's solve of that one state alone, to 1e-12 relative;
* ``qdd`` against ``(M - E0) / J`` of the full runs (every state's whole analysis), to
  1e-12 relative, on a frozen piece's plan too and with friction (``qdd`` the root);
* a state that cannot be solved: the same :class:`StepFailure` and message as the effort's
  solve of that state alone.

The scenes: the crank-rocker with its motor (loads switching over the turn: pieces), the
shaper with its flywheel (two closed-form dyads), a six-bar with a class-3 group (solved by
continuation along the path), the eccentric-cam rocker and the press with friction.
"""

from __future__ import annotations

import copy

import numpy as np
import pytest

import linkage_sym
from linkage_sym.examples import example_dict
from linkage_sym.motion.equations import MotionEquations, StepFailure, motor_effort
from linkage_sym.motion.lean import effort_at, effort_inertia_at, inertia_at, numeric_inertia_at
from linkage_sym.motion.pieces import Pieces
from tests.support.marks import fast_cases

Q = np.linspace(-6 * np.pi, 6 * np.pi, 41) + 0.137  # three turns either way, not on a knot
QD = np.concatenate([np.linspace(-25.0, 25.0, 40), [0.0]])


def equations(name):
    data = copy.deepcopy(example_dict(name))
    data["drivers"][0].setdefault("motor", {"torque": [[0.0, 3.0], [20.0, 0.0]]})
    return MotionEquations(linkage_sym.load_scene(data), require_simulate=False)


@pytest.mark.parametrize("name", fast_cases(
    ["crank_rocker_motor", "shaper_flywheel", "sixbar_class3", "cam_eccentric_rocker",
     "slider_crank_press_friction"], {"crank_rocker_motor"}))
def test_one_solve_gives_the_effort_and_the_inertia_of_two(name):
    eq = equations(name)
    for q, qd in zip(Q, QD):
        qr = float(eq.reduce(q))
        e, J, status, message = effort_inertia_at(eq.effort_plan, eq.scene, eq.joint, qr, qd,
                                                  0.0)
        e1, status1, message1 = effort_at(eq.effort_plan, eq.joint, qr, qd, 0.0)
        assert (status, message) == (status1, message1) == ("ok", None)
        if eq.numeric_inertia:
            J1 = numeric_inertia_at(eq.mechanism, eq.scene, eq.joint, qr)[0]
        else:
            J1 = inertia_at(eq.mechanism, eq.scene, eq.joint, qr)[0]
        assert abs(J - J1) <= 1e-12 * J1
        assert abs(e - e1) <= 1e-12 * max(abs(e1), J1 * qd * qd, J1)


@pytest.mark.parametrize("name", fast_cases(
    ["crank_rocker_motor", "sixbar_class3", "cam_eccentric_rocker",
     "slider_crank_press_friction"], {"crank_rocker_motor"}))
def test_one_state_acceleration_is_the_full_runs_over_turns(name):
    eq = equations(name)
    want, J, _ = eq.accelerations(Q, QD)
    got = np.array([eq.acceleration(a, b) for a, b in zip(Q, QD)])
    M = motor_effort(eq.motor, QD)
    e0 = eq.effort(Q, QD)[0]
    scale = (np.abs(M) + np.abs(e0)) / J
    np.testing.assert_array_less(np.abs(got - want), 1e-12 * scale)


def test_a_frozen_pieces_acceleration_is_its_plans():
    eq = equations("crank_rocker_motor")
    pieces = Pieces(eq)
    for q, qd in zip(Q[::4], np.abs(QD[::4]) + 1.0):
        piece = pieces.at(q, qd, True, True)
        qr = float(eq.reduce(q))
        e0 = effort_at(piece.plan, eq.joint, qr, qd, 0.0)[0]
        J = inertia_at(eq.mechanism, eq.scene, eq.joint, qr)[0]
        want = (piece.motor(qd) - e0) / J
        got = eq.acceleration(q, qd, piece)
        assert abs(got - want) <= 1e-12 * (abs(piece.motor(qd)) + abs(e0)) / J


def test_a_state_that_cannot_be_solved_fails_as_its_effort_does():
    data = copy.deepcopy(example_dict("crank_rocker"))
    data["joints"][1]["at"] = [0.04, 0.0]  # a crank too long to turn round (not Grashof)
    data["drivers"][0]["motor"] = {"torque": 0.05}
    eq = MotionEquations(linkage_sym.load_scene(data), require_simulate=False)
    failed = 0
    for q in np.linspace(-np.pi, np.pi, 25):
        e, status, message = effort_at(eq.effort_plan, eq.joint, float(eq.reduce(q)), 1.0, 0.0)
        if status == "ok":
            continue
        failed += 1
        with pytest.raises(StepFailure) as exc:
            eq.acceleration(q, 1.0)
        assert str(exc.value) in (message, f"{status}: {message}")
    assert failed > 0
