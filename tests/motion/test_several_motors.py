"""``simulate`` with several motors (a mechanism of as many degrees of freedom).

Checked against what shares no code with the equations' right-hand side:

* energy: without loads, motor torque, friction and damping, the kinetic energy from the
  numeric solver's link velocities plus gravity's potential energy stays constant to 1e-9;
* the mass matrix: ``½ q̇ᵀ M q̇`` equals the kinetic energy of the numeric solver's link
  velocities at random states to 1e-12; the velocity-product terms ``h`` from the derived
  equations equal the numeric solver's driving efforts at zero acceleration (inertia alone);
* inverse dynamics: the simulated q, q̇, q̈ fed back to the *global* force method gives every
  driver's effort equal to its motor's to 1e-8;
* two uncoupled parts (a crank-rocker and a block lifted on a guide): the block moves as its
  closed form, the crank-rocker as the one-driver simulation of it alone;
* bad input refused naming the field, a stall ended with a message naming the motor.
"""

from __future__ import annotations

import copy
import dataclasses

import numpy as np
import pytest

import linkage_sym
from linkage_sym.errors import SceneError
from linkage_sym.examples import example_dict
from linkage_sym.motion.multi import SeveralEquations
from linkage_sym.motion.simulate import simulate
from linkage_sym.scene.load import dump_scene
from tests.support.motion_energy import kinetic_energy


def fivebar(torques=(0.0, 0.0), loads=False, duration=0.12, speeds=(15.0, -10.0),
            samples=25, gravity=True):
    data = copy.deepcopy(example_dict("fivebar_motors"))
    for d, torque in zip(data["drivers"], torques):
        d["motor"] = {"torque": torque}
    if not loads:
        data["loads"] = []
    if not gravity:
        data["effects"]["gravity"] = False
    data["simulate"] = {"duration": duration, "start_deg": [20.0, 100.0],
                        "start_speed": list(speeds), "samples": samples}
    return linkage_sym.load_scene(data)


def potential_energy(scene, analysis):
    g = np.asarray(scene.effects.gravity)
    return sum(-link.mass * np.asarray(analysis.links[link.name].com) @ g for link in scene.links)


@pytest.mark.slow
def test_energy_is_conserved_without_loads_and_motor_torques():
    scene = fivebar()
    res = simulate(scene)
    assert res.trajectory.end == "duration"
    T = kinetic_energy(scene, res.analysis)
    E = T + potential_energy(scene, res.analysis)
    assert np.ptp(T) > 1e-3 * T.max()  # the speeds do vary
    assert np.max(np.abs(E - E[0])) <= 1e-9 * T.max()


def test_the_mass_matrix_gives_the_kinetic_energy_of_the_numeric_velocities():
    scene = fivebar()
    eq = SeveralEquations(scene)
    rng = np.random.default_rng(7)
    q = rng.uniform(-np.pi, np.pi, (2, 12))
    qd = rng.uniform(-20.0, 20.0, (2, 12))
    M = eq.mass_matrices(q, reduce=False)
    plan = linkage_sym.compile_plan(dataclasses.replace(scene, outputs=("kinematics",)))
    got = np.empty(12)
    for s in range(12):  # one state a run: the numeric solver's own path to each
        res = plan.run({"A": q[0, s:s + 1], "E": q[1, s:s + 1]},
                       {"A": qd[0, s:s + 1], "E": qd[1, s:s + 1]},
                       {"A": np.zeros(1), "E": np.zeros(1)})
        assert res.ok.all()
        got[s] = kinetic_energy(scene, res)[0]
    from_M = 0.5 * np.einsum("is,sij,js->s", qd, M, qd)
    assert np.max(np.abs(from_M - got) / got) <= 1e-12
    # the lean evaluation at one state is the same matrix
    from linkage_sym.motion.multi import mass_matrix_at

    lean = mass_matrix_at(eq.mechanism, scene, eq.joints, q[:, 3])
    assert np.max(np.abs(lean - M[3])) <= 1e-14 * np.max(np.abs(M[3]))


def test_velocity_terms_equal_the_numeric_effort_at_zero_acceleration():
    scene = fivebar(gravity=False)
    eq = SeveralEquations(scene)
    rng = np.random.default_rng(3)
    for _ in range(5):
        q, qd = rng.uniform(-3.0, 3.0, 2), rng.uniform(-20.0, 20.0, 2)
        h = eq.velocity_terms(q, qd)
        e0 = eq.efforts(q.reshape(2, 1), qd.reshape(2, 1), reduce=False)[0][:, 0]
        assert np.max(np.abs(h - e0)) <= 1e-12 * np.max(np.abs(e0))


@pytest.mark.slow
def test_inverse_dynamics_closes_the_loop_with_the_global_method():
    torques = ([[0.0, 4.0], [15.0, 2.0], [20.0, 0.0]], [[0.0, 3.0], [10.0, 0.0]])
    scene = fivebar(torques, loads=True, speeds=(12.0, 6.0))
    res = simulate(scene)
    assert res.trajectory.end == "duration"
    d = res.analysis.drivers
    again = linkage_sym.compile_plan(scene).run(
        {j: d[j]["q"] for j in "AE"}, {j: d[j]["qd"] for j in "AE"},
        {j: d[j]["qdd"] for j in "AE"}, method="global")
    assert again.ok.all()
    motor = {"A": np.interp(d["A"]["qd"], [0.0, 15.0, 20.0], [4.0, 2.0, 0.0]),
             "E": np.interp(d["E"]["qd"], [0.0, 10.0], [3.0, 0.0])}
    scale = max(np.max(np.abs(m)) for m in motor.values())
    for j in "AE":
        assert np.max(np.abs(again.forces.driving[j] - motor[j])) <= 1e-8 * scale
    assert res.effort_error <= 1e-8
    assert res.time[0] == 0.0 and len(res.time) == 25
    assert d["A"]["q"][0] == pytest.approx(np.radians(20.0), abs=1e-15)
    assert d["E"]["qd"][0] == 6.0
    out = res.to_dict()
    assert out["steps"][1]["drivers"].keys() == {"A", "E"} and out["integrator"]["rtol"] <= 1e-10
    assert set(out["motion"]) == {"reason", "drivers"}


def uncoupled_data():
    data = copy.deepcopy(example_dict("crank_rocker"))
    data["links"][0]["inertia"] = 2e-3
    data["loads"] = [{"link": "rocker", "torque": -0.3}]
    data["links"].append({"name": "block", "mass": 2.0, "com": [0.3, 0.0]})
    data["joints"].append({"name": "S", "type": "P", "links": ["ground", "block"],
                           "at": [0.3, 0.0], "axis_deg": 90})
    data["drivers"][0]["motor"] = {"torque": [[0.0, 2.0], [20.0, 0.0]]}
    data["drivers"].append({"joint": "S", "start": 0, "stop": 0.1, "steps": 361, "speed": 0,
                            "motor": {"force": 30.0}})
    data["simulate"] = {"duration": 0.2, "start_deg": [30.0, None], "start": [None, 0.01],
                        "start_speed": [12.0, 0.5], "samples": 11}
    return data


@pytest.mark.slow
def test_two_uncoupled_parts_move_as_each_alone():
    scene = linkage_sym.load_scene(uncoupled_data())
    res = simulate(scene)
    assert res.trajectory.end == "duration"
    t = res.time
    a = 30.0 / 2.0 - 9.81  # the block: pushed up by 30 N against its weight
    s = res.analysis.drivers["S"]
    assert np.allclose(s["q"], 0.01 + 0.5 * t + 0.5 * a * t**2, rtol=0, atol=1e-11)
    assert np.allclose(s["qdd"], a, rtol=1e-12, atol=0)
    assert np.allclose(res.mass_matrix[:, 0, 1], 0.0, atol=0) and np.allclose(
        res.mass_matrix[:, 1, 1], 2.0, rtol=1e-14)
    alone = copy.deepcopy(example_dict("crank_rocker"))
    alone["links"][0]["inertia"] = 2e-3
    alone["loads"] = [{"link": "rocker", "torque": -0.3}]
    alone["drivers"][0]["motor"] = {"torque": [[0.0, 2.0], [20.0, 0.0]]}
    alone["simulate"] = {"duration": 0.2, "start_deg": 30.0, "start_speed": 12.0, "samples": 11}
    one = simulate(linkage_sym.load_scene(alone)).analysis.drivers["A"]
    a_ = res.analysis.drivers["A"]
    assert np.max(np.abs(a_["q"] - one["q"])) <= 1e-8 * np.max(np.abs(one["q"]))
    assert np.max(np.abs(a_["qd"] - one["qd"])) <= 1e-8 * np.max(np.abs(one["qd"]))
    assert res.motion["drivers"]["S"] == {"reason": "a P driver: its motion has no turns"}


@pytest.mark.slow
def test_a_weak_motor_stalls_with_a_message_naming_it():
    scene = fivebar((2.0, 0.0), loads=True, duration=1.0, speeds=(5.0, 1.0))
    res = simulate(scene)
    assert res.trajectory.end == "stall"
    assert "the motor of driver E stalls at t =" in res.message
    assert "drivers A at" in res.message and "; E at" in res.message
    assert res.to_dict()["end"] == res.message
    assert res.motion["reason"].startswith("the motion ended early")


def test_the_start_lists_read_and_dump_back():
    scene = linkage_sym.load_scene(uncoupled_data())
    assert scene.simulate.start == (np.radians(30.0), 0.01)
    assert scene.simulate.start_speed == (12.0, 0.5)
    back = linkage_sym.load_scene(dump_scene(scene))
    assert back.simulate == scene.simulate
    data = uncoupled_data()
    del data["simulate"]["start_deg"], data["simulate"]["start"], data["simulate"]["start_speed"]
    plain = linkage_sym.load_scene(data).simulate
    assert plain.start == (scene.drivers[0].start, 0.0) and plain.start_speed == (0.0, 0.0)


def problems(data, run=False):
    with pytest.raises(SceneError) as err:
        scene = linkage_sym.load_scene(data)
        if run:
            simulate(scene)
    return err.value.problems


@pytest.mark.parametrize("change, field", [
    (lambda d: d["simulate"].update(start_deg=[30.0]), "simulate.start_deg"),
    (lambda d: d["simulate"].update(start_deg=30.0), "simulate.start_deg"),
    (lambda d: d["simulate"].update(start_speed=[1.0, "fast"]), "simulate.start_speed[1]"),
    (lambda d: d["simulate"].update(start=[0.1, 0.01]), "simulate.start[0]"),
    (lambda d: d["simulate"].update(start_deg=[30.0, 5.0]), "simulate.start_deg[1]"),
    (lambda d: d["simulate"].update(start_deg=[1e9, None]), "simulate.start_deg[0]"),
])
def test_bad_starts_are_refused_by_field(change, field):
    data = uncoupled_data()
    change(data)
    got = problems(data)
    assert any(p.startswith(field + ":") for p in got), got


def test_motors_on_only_some_drivers_are_refused_by_field():
    data = uncoupled_data()
    del data["drivers"][1]["motor"]
    got = problems(data, run=True)
    assert got == ["drivers[1].motor: required to simulate (the force the motor gives against "
                   "its speed)"]


def test_the_flywheel_takes_one_driver():
    from linkage_sym.motion.flywheel import flywheel

    with pytest.raises(SceneError) as err:
        flywheel(linkage_sym.load_scene(uncoupled_data()), 0.05)
    assert err.value.problems[0].startswith("drivers: ")


@pytest.mark.slow  # 3-5 s: the fast lane stays under two minutes
def test_with_friction_in_every_joint_the_motors_efforts_move_the_mechanism_as_integrated():
    data = copy.deepcopy(example_dict("fivebar_motors"))
    for joint in data["joints"]:
        joint["friction"] = {"coefficient": 0.1, "radius": 0.005}
    data["effects"]["friction"] = True
    data["simulate"].update(duration=0.03, samples=7, start_speed=[5.0, 3.0])
    scene = linkage_sym.load_scene(data)
    res = simulate(scene)
    assert res.trajectory.end == "duration"
    d = res.analysis.drivers
    again = linkage_sym.compile_plan(scene).run(
        {j: d[j]["q"] for j in "AE"}, {j: d[j]["qd"] for j in "AE"},
        {j: d[j]["qdd"] for j in "AE"}, method="global")  # its own nonlinear friction solve
    assert again.ok.all()
    scale = max(np.max(np.abs(m)) for m in res.motor.values())
    for j in "AE":
        assert np.max(np.abs(again.forces.driving[j] - res.motor[j])) <= 1e-8 * scale
