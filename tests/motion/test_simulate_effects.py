"""``simulate`` under the contract's other machine effects: springs and joint friction.

* springs alone (no motor torque, no damping, no loads, no gravity): the kinetic energy
  (summed here from the numeric solver's velocities) plus the springs' potential energy
  (``tests.support.spring_checks``, written from the scene format alone) stays constant
  over a simulated second, to 1e-9 of the kinetic energy;
* joint friction: the simulated q, qd, qdd fed back as a prescribed motion to the *global*
  force method, whose friction is its own Newton on the whole system (no code shared with
  the group routines the equation's right-hand side uses), needs the motor's effort at
  that speed, to 1e-8 of it.
"""

from __future__ import annotations

import copy

import numpy as np
import pytest

import linkage_sym
from linkage_sym.examples import example_dict
from linkage_sym.motion.simulate import simulate
from tests.support.motion_energy import kinetic_energy
from tests.support.spring_checks import energy



@pytest.mark.slow
def test_springs_alone_conserve_kinetic_plus_spring_energy_over_a_second():
    data = copy.deepcopy(example_dict("crank_rocker_spring"))
    for k in data["springs"]:
        k["damping"] = 0.0
    data["loads"] = []
    data["links"][0]["inertia"] = 0.02  # the crank's shaft with a flywheel: it turns round
    data["effects"].update(inertia=True, gravity=False)
    data["drivers"][0]["motor"] = {"torque": 0.0}
    data["simulate"] = {"duration": 1.0, "start_deg": 0.0, "start_speed": 12.0, "samples": 101}
    scene = linkage_sym.load_scene(data)
    # over a whole second the integration's own error adds up: 1.5e-9 of T at the contract's
    # rtol 1e-10, so a tighter rtol (which the contract's "1e-10 or better" allows)
    res = simulate(scene, rtol=1e-12)
    assert res.trajectory.end == "duration"
    a = res.analysis
    assert a.ok.all()
    T = kinetic_energy(scene, a)
    V = sum(v[0] for v in energy(scene, a).values())
    assert np.ptp(T) > 1e-2 * T.max() and np.ptp(V) > 1e-2 * T.max()  # both do vary
    E = T + V
    assert np.max(np.abs(E - E[0])) <= 1e-9 * np.max(T)


@pytest.mark.slow
def test_friction_inverse_dynamics_closes_the_loop_with_the_global_method():
    data = copy.deepcopy(example_dict("slider_crank_press_friction"))
    table = [[0.0, 120.0], [20.0, 0.0]]
    data["drivers"][0]["motor"] = {"torque": table}
    data["simulate"] = {"duration": 0.04, "start_deg": 20.0, "start_speed": 10.0, "samples": 9}
    scene = linkage_sym.load_scene(data)
    res = simulate(scene)
    assert res.trajectory.end == "duration"
    d = res.analysis.drivers["A"]
    again = linkage_sym.compile_plan(scene).run({"A": d["q"]}, {"A": d["qd"]}, {"A": d["qdd"]},
                                                method="global")
    assert again.ok.all()
    assert np.all(again.forces.friction_power > 0)  # the friction does act
    motor = np.interp(d["qd"], *np.transpose(table))
    assert np.max(np.abs(again.forces.driving["A"] - motor)) <= 1e-8 * np.max(np.abs(motor))


def test_a_self_locking_state_ends_the_simulation_saying_where():
    """The inclined slider pushed by a force motor from 4° (friction 0.3 at its guide): no
    finite force moves it there (the kinetostatic solver's status ``self-locking``), so the
    simulation ends at once with a message giving the time, the driver's value and speed,
    the status once and the joint whose friction locks it."""
    from tests.support.friction_scenes import inclined_slider

    d = inclined_slider(0.3)
    d["effects"]["inertia"] = True
    d["links"][0].update(mass=0.5, com=d["joints"][0]["at"])
    d["drivers"][0]["motor"] = {"force": 400.0}
    d["simulate"] = {"duration": 1.0, "start": 0.0, "start_speed": 0.0, "samples": 201}
    res = simulate(linkage_sym.load_scene(d))
    assert res.message.startswith("the mechanism cannot be solved at t = 0 s, driver A at 0 m, "
                                  "0 m/s"), res.message
    assert res.message.count("self-locking") == 1 and "joint(s) C_guide" in res.message
    assert list(res.analysis.status) == ["self-locking"]
