"""``simulate`` of a cam mechanism: ``J`` and ``J'`` from the numeric solver's kinematics.

The symbolic layer derives no cam contact, so a cam scene's equivalent moment of inertia
comes from the numeric solver's velocities and accelerations at unit speed
(``J = sum m v_G^2 + I w^2``, ``J' = 2 sum m v_G . a_G + I w alpha`` at ``qd = 1``,
``qdd = 0``).  Checked:

* that route against the derived equations' ``J`` and ``J'`` on a linkage both can do (the
  crank-rocker with its motor), to 1e-12;
* energy: the eccentric-cam rocker with no loads and a motor giving no torque keeps its
  kinetic energy (summed here from the numeric solver's velocities at the integrated states)
  plus gravity's potential energy (from the centres of mass the solver reports) to 1e-9;
* inverse dynamics: the simulated q, qd, qdd of the cam under its follower's torque, gravity
  and a motor table, fed back to the *global* force method (one sparse system, no code
  shared with the group routines the right-hand side uses), need the motor's effort, to 1e-8.
"""

from __future__ import annotations

import copy

import numpy as np
import pytest

import linkage_sym
from linkage_sym.examples import example_dict
from linkage_sym.motion.equations import MotionEquations
from linkage_sym.motion.lean import numeric_inertia_at
from linkage_sym.motion.simulate import simulate
from tests.support.motion_energy import kinetic_energy

TABLE = [[0.0, 4.0], [8.0, 3.0], [14.0, 0.0]]


def cam_scene(duration, start_speed, samples, loads=True, gravity=True, torque=TABLE):
    data = copy.deepcopy(example_dict("cam_eccentric_rocker"))
    data["drivers"][0]["motor"] = {"torque": torque}
    if not loads:
        data["loads"] = []
    if not gravity:
        data["effects"]["gravity"] = False
    data["simulate"] = {"duration": duration, "start_speed": start_speed, "samples": samples}
    return linkage_sym.load_scene(data)


@pytest.mark.slow
def test_numeric_inertia_equals_the_derived_one_on_a_linkage():
    scene = linkage_sym.load_scene(example_dict("crank_rocker_motor"))
    derived = MotionEquations(scene, require_simulate=False)
    numeric = MotionEquations(scene, require_simulate=False, numeric_inertia=True)
    assert numeric.numeric_inertia and not derived.numeric_inertia
    q = np.linspace(-np.pi, np.pi, 73)
    J, dJ = derived.inertia(q)
    Jn, dJn = numeric.inertia(q)
    assert np.max(np.abs(Jn - J)) <= 1e-12 * np.max(J)
    assert np.max(np.abs(dJn - dJ)) <= 1e-12 * np.max(np.abs(dJ))
    one = np.array([numeric_inertia_at(numeric.mechanism, scene, "A", x) for x in q[::8]])
    assert np.max(np.abs(one[:, 0] - J[::8])) <= 1e-12 * np.max(J)
    assert np.max(np.abs(one[:, 1] - dJ[::8])) <= 1e-12 * np.max(np.abs(dJ))


def test_a_cam_scene_takes_the_numeric_route():
    eq = MotionEquations(cam_scene(0.1, 5.0, 3), require_simulate=False)
    assert eq.numeric_inertia


@pytest.mark.slow
def test_a_free_cam_conserves_its_energy():
    scene = cam_scene(0.5, 12.0, 41, loads=False, torque=0.0)
    # the contract's "rtol 1e-10 or better": 1e-12, so that the integration's own error stays
    # well under the check's 1e-9
    res = simulate(scene, rtol=1e-12)
    assert res.trajectory.end == "duration"
    a = res.analysis
    assert a.ok.all()
    T = kinetic_energy(scene, a)
    g = np.asarray(scene.effects.gravity)
    V = sum(-link.mass * np.asarray(a.links[link.name].com) @ g for link in scene.links)
    assert np.ptp(a.drivers["A"]["qd"]) > 1e-3 * np.max(a.drivers["A"]["qd"])  # it varies
    assert a.drivers["A"]["q"][-1] - a.drivers["A"]["q"][0] > 2 * np.pi
    E = T + V
    assert np.max(np.abs(E - E[0])) <= 1e-9 * T.max()


@pytest.mark.slow
def test_cam_inverse_dynamics_closes_the_loop_with_the_global_method():
    scene = cam_scene(0.5, 6.0, 21)
    res = simulate(scene)
    assert res.trajectory.end == "duration"
    d = res.analysis.drivers["A"]
    again = linkage_sym.compile_plan(scene).run({"A": d["q"]}, {"A": d["qd"]}, {"A": d["qdd"]},
                                                method="global")
    assert again.ok.all()
    motor = np.interp(d["qd"], *np.transpose(TABLE))
    assert np.ptp(d["qd"]) > 0.5  # the motion is not steady
    assert np.max(np.abs(again.forces.driving["A"] - motor)) <= 1e-8 * np.max(np.abs(motor))
    assert res.effort_error <= 1e-8
