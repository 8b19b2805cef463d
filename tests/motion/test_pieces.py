"""The integration restarts at the breakpoints of the equation of motion (``motion.pieces``).

* every crossing of a load's switch angle (``active_deg``) and of a motor table's row speed
  is the end of a step: the solver stops there and restarts on the next smooth piece;
* the frozen equation of a piece is the scene's within the piece (to rounding);
* the motion integrated piece by piece at the contract's rtol 1e-10 agrees with a reference
  integrated at rtol 1e-12 to 1e-9 of the crank's top speed (the global error of rtol 1e-10
  over the run).
"""

from __future__ import annotations

import copy
import math

import numpy as np
import pytest

import linkage_sym
from linkage_sym.examples import example_dict
from linkage_sym.motion.equations import MotionEquations
from linkage_sym.motion.integrate import integrate_motion
from linkage_sym.motion.pieces import Pieces

MOTOR = [[0.0, 3.0], [10.0, 2.5], [16.0, 0.0]]


def scene(duration=0.3):
    data = copy.deepcopy(example_dict("crank_rocker"))
    data["links"][0]["inertia"] = 2e-3
    data["drivers"][0]["motor"] = {"torque": MOTOR}
    data["loads"] = [{"link": "rocker", "torque": -0.8, "active_deg": [40, 200],
                      "driver": "A"}]
    data["effects"]["gravity"] = False
    data["simulate"] = {"duration": duration, "start_deg": 30.0, "start_speed": 8.0,
                        "samples": 31}
    return linkage_sym.load_scene(data)


@pytest.mark.slow
def test_each_breakpoint_crossed_ends_a_step():
    eq = MotionEquations(scene())
    traj = integrate_motion(eq, 0.0, (math.radians(30.0), 8.0), 0.3, method="LSODA")
    t = np.asarray(traj.t)
    q, qd = traj(t)
    # the switch angles crossed and the motor's row (10 rad/s) crossed
    turns = np.floor((q[-1] - math.radians(40.0)) / (2 * math.pi))
    ons = math.radians(40.0) + 2 * math.pi * np.arange(turns + 1)
    offs = math.radians(200.0) + 2 * math.pi * np.arange(turns + 1)
    crossed = [b for b in np.concatenate([ons, offs]) if q[0] < b < q[-1]]
    assert len(crossed) == 2
    for b in crossed:
        assert np.min(np.abs(q - b)) <= 1e-12 * abs(b)
    assert qd[0] < 10.0 < qd[-1]
    assert np.min(np.abs(qd - 10.0)) <= 1e-12 * 10.0


def test_the_frozen_equation_is_the_scenes_within_its_piece():
    eq = MotionEquations(scene())
    pieces = Pieces(eq)
    for deg, speed in [(35.0, 7.0), (120.0, 12.0), (300.0, 14.0), (399.0, 9.9)]:
        q = math.radians(deg)
        piece = pieces.at(q, speed, True, True)
        assert piece.lo <= q <= piece.hi and piece.slo <= speed <= piece.shi
        frozen = eq.acceleration(q, speed, piece)
        assert abs(frozen - eq.acceleration(q, speed)) <= 1e-12 * abs(frozen)


@pytest.mark.slow
def test_piecewise_motion_agrees_with_a_tighter_reference():
    eq = MotionEquations(scene())
    y0 = (math.radians(30.0), 8.0)
    times = np.linspace(0.0, 0.3, 31)
    got = integrate_motion(eq, 0.0, y0, 0.3, method="LSODA")(times)
    ref = integrate_motion(eq, 0.0, y0, 0.3, method="LSODA", rtol=1e-12)(times)
    assert np.max(np.abs(got[1] - ref[1])) <= 1e-9 * np.max(np.abs(ref[1]))
    assert np.max(np.abs(got[0] - ref[0])) <= 1e-9 * np.max(np.abs(ref[0]))
