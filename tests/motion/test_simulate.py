"""``simulate``: the motion of a machine driven by its motor (the contract's second part).

Checked against what shares no code with the equation of motion's right-hand side:

* energy: without loads, gravity's work aside, and with a motor that gives no torque, the
  kinetic energy (from the numeric solver's velocities at the integrated states, summed
  here link by link) plus gravity's potential energy (from the centres of mass the solver
  reports) stays constant to 1e-9 of its value;
* inverse dynamics: the simulated q, qd, qdd fed back as a prescribed motion to the
  *global* force method (one sparse system, no code shared with the group-by-group
  solver the right-hand side uses) needs the motor's effort at that speed, to 1e-8;
* J from the derived equations against the kinetic energy of the numeric solver's
  velocities (2 T / qd^2), and J' against a central difference of it;
* a stall and a refused scene end or stop with messages naming where and which field.
"""

from __future__ import annotations

import copy
import dataclasses

import numpy as np
import pytest

import linkage_sym
from linkage_sym.errors import SceneError
from linkage_sym.examples import example_dict
from linkage_sym.motion.equations import MotionEquations
from linkage_sym.motion.simulate import simulate
from tests.support.motion_energy import kinetic_energy


def motor_scene(torque, loads=None, gravity=(0.0, -9.81), duration=0.15, start_speed=12.0,
                samples=31):
    data = copy.deepcopy(example_dict("crank_rocker"))
    data["links"][0]["inertia"] = 2e-3
    data["drivers"][0]["motor"] = {"torque": torque}
    data["loads"] = [] if loads is None else loads
    data["effects"]["gravity"] = list(gravity) if gravity else False
    data["simulate"] = {"duration": duration, "start_deg": 30.0, "start_speed": start_speed,
                        "samples": samples}
    return linkage_sym.load_scene(data)



def potential_energy(scene, analysis):
    g = np.asarray(scene.effects.gravity)
    return sum(-link.mass * np.asarray(analysis.links[link.name].com) @ g for link in scene.links)


@pytest.mark.slow
def test_energy_is_conserved_without_loads_and_motor_torque():
    scene = motor_scene(0.0)
    res = simulate(scene)
    assert res.trajectory.end == "duration"
    E = kinetic_energy(scene, res.analysis) + potential_energy(scene, res.analysis)
    T = kinetic_energy(scene, res.analysis)
    assert np.ptp(T) > 1e-3 * T.max()  # the speed does vary
    assert np.max(np.abs(E - E[0])) <= 1e-9 * np.max(np.abs(T))


@pytest.mark.slow
def test_inverse_dynamics_closes_the_loop_with_the_global_method():
    loads = [{"link": "rocker", "torque": -0.8, "active_deg": [0, 200], "driver": "A"},
             {"link": "coupler", "force": [0.0, -5.0], "at": [0.05, 0.03]}]
    scene = motor_scene([[0.0, 3.0], [10.0, 2.5], [16.0, 0.0]], loads)
    res = simulate(scene)
    d = res.analysis.drivers["A"]
    again = linkage_sym.compile_plan(scene).run({"A": d["q"]}, {"A": d["qd"]}, {"A": d["qdd"]},
                                                method="global")
    motor = np.interp(d["qd"], [0.0, 10.0, 16.0], [3.0, 2.5, 0.0])
    assert again.ok.all()
    scale = np.max(np.abs(motor))
    assert np.max(np.abs(again.forces.driving["A"] - motor)) <= 1e-8 * scale
    assert res.effort_error <= 1e-8
    # the steps are at the sampled times, the first at the start
    assert res.time[0] == 0.0 and len(res.time) == 31
    assert d["q"][0] == pytest.approx(np.radians(30.0), abs=1e-15)
    assert d["qd"][0] == 12.0


def test_equivalent_inertia_against_the_kinetic_energy_of_the_numeric_velocities():
    scene = motor_scene(0.0)
    eq = MotionEquations(scene)
    q = np.linspace(0.0, 2 * np.pi, 37)
    J, dJ = eq.inertia(q, reduce=False)
    plan = linkage_sym.compile_plan(dataclasses.replace(scene, outputs=("kinematics",)))

    def numeric_J(qq, speed=3.0):
        res = plan.run({"A": qq}, {"A": np.full_like(qq, speed)}, {"A": np.zeros_like(qq)})
        return 2.0 * kinetic_energy(scene, res) / speed**2

    assert np.max(np.abs(J - numeric_J(q))) <= 1e-12 * J.max()
    h = 1e-4
    fd = (numeric_J(q + h) - numeric_J(q - h)) / (2 * h)
    assert np.max(np.abs(dJ - fd)) <= 1e-6 * np.max(np.abs(dJ))


def test_a_machine_that_slows_to_rest_stalls_with_a_message():
    loads = [{"link": "rocker", "torque": -3.0}]
    scene = motor_scene(0.0, loads, gravity=None, duration=2.0, start_speed=3.0)
    res = simulate(scene)
    assert res.trajectory.end == "stall"
    assert "stalls at t =" in res.message and "driver A at" in res.message
    assert res.time[-1] <= res.trajectory.t_end
    assert "reason" in res.motion
    out = res.to_dict()
    assert out["end"] == res.message and out["steps"][0]["time"] == 0.0
    assert out["integrator"]["rtol"] <= 1e-10


@pytest.mark.parametrize("change, field", [
    (lambda d: d["effects"].update(inertia=False), "effects.inertia"),
    (lambda d: d["drivers"][0].pop("motor"), "drivers[0].motor"),
    (lambda d: d.pop("simulate"), "simulate"),
])
def test_scenes_that_cannot_be_simulated_are_refused_by_field(change, field):
    data = copy.deepcopy(example_dict("crank_rocker"))
    data["drivers"][0]["motor"] = {"torque": 1.0}
    data["simulate"] = {"duration": 1.0, "samples": 11}
    change(data)
    with pytest.raises(SceneError) as err:
        simulate(linkage_sym.load_scene(data))
    assert any(p.startswith(field + ":") for p in err.value.problems)


@pytest.mark.slow
def test_the_refined_flywheel_gives_the_requested_fluctuation_to_one_percent():
    from linkage_sym.motion.flywheel import flywheel
    from linkage_sym.motion.periodic import periodic_motion
    from linkage_sym.motion.simulate import with_inertia

    loads = [{"link": "rocker", "torque": -0.8, "active_deg": [0, 200], "driver": "A"}]
    scene = motor_scene([[0.0, 3.0], [20.0, 0.0]], loads, gravity=None)
    got = flywheel(scene, 0.02)
    assert 0.99 * 0.02 <= got.fluctuation <= 0.02
    # the energy method's estimate is within its approximation (constant speed in the
    # efforts and in J) of the refined inertia: here 10 %
    assert got.estimate == pytest.approx(got.inertia, rel=0.1)
    # an independent check: simulate the machine with that flywheel from rest until the
    # motion is periodic, and measure the fluctuation of its last turn
    fitted = with_inertia(scene, "crank", got.inertia)
    fitted = dataclasses.replace(fitted, simulate=dataclasses.replace(
        scene.simulate, duration=40 * 2 * np.pi / got.mean_speed, start_speed=got.mean_speed))
    res = simulate(fitted)
    assert "speed_fluctuation" in res.motion, res.motion
    assert res.motion["speed_fluctuation"] == pytest.approx(got.fluctuation, rel=1e-3)


def test_a_block_lifted_by_a_constant_force_moves_as_the_closed_form():
    # one block on a vertical guide, 2 kg, pushed up by 30 N against gravity: q'' = 30/2 - 9.81
    data = {"name": "lift", "links": [{"name": "block", "mass": 2.0, "com": [0.0, 0.0]}],
            "joints": [{"name": "S", "type": "P", "links": ["ground", "block"], "at": [0, 0],
                        "axis_deg": 90}],
            "drivers": [{"joint": "S", "start": 0, "stop": 0.1, "steps": 3, "speed": 0,
                         "motor": {"force": 30.0}}],
            "effects": {"inertia": True, "gravity": [0, -9.81]},
            "simulate": {"duration": 0.2, "start": 0.01, "start_speed": 0.5, "samples": 5}}
    scene = linkage_sym.load_scene(data)
    res = simulate(scene)
    a = 30.0 / 2.0 - 9.81
    t = res.time
    d = res.analysis.drivers["S"]
    assert np.allclose(d["q"], 0.01 + 0.5 * t + 0.5 * a * t**2, rtol=0, atol=1e-12)
    assert np.allclose(d["qd"], 0.5 + a * t, rtol=0, atol=1e-12)
    assert np.allclose(d["qdd"], a, rtol=1e-12, atol=0)
    assert np.allclose(res.inertia, 2.0, rtol=1e-14)
    assert "P joint" in res.motion["reason"]


@pytest.mark.slow
def test_a_crank_that_cannot_turn_round_ends_the_simulation_where_it_fails():
    data = copy.deepcopy(example_dict("crank_rocker"))
    data["joints"][1]["at"] = [0.04, 0.0]  # a crank too long to turn round (not Grashof)
    data["drivers"][0]["motor"] = {"torque": 0.05}
    data["loads"] = []
    data["effects"]["gravity"] = False
    data["simulate"] = {"duration": 1.0, "samples": 11, "start_speed": 1.0}
    res = simulate(linkage_sym.load_scene(data))
    assert res.trajectory.end == "failure"
    assert "cannot be solved at t =" in res.message and "driver A at" in res.message
    assert res.time[-1] <= res.trajectory.t_end < 1.0
    assert res.analysis.n_steps == len(res.time) >= 1
