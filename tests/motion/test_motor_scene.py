"""Reading ``drivers[i].motor`` and ``simulate``: every problem names its field, and a scene
with them analyses as without them (``analyze`` does not read a motor)."""

from __future__ import annotations

import copy

import numpy as np
import pytest

import linkage_sym
from linkage_sym.errors import SceneError
from linkage_sym.examples import example_dict
from linkage_sym.motion.equations import motor_effort


def with_motor(motor=None, simulate=None):
    data = copy.deepcopy(example_dict("crank_rocker"))
    if motor is not None:
        data["drivers"][0]["motor"] = motor
    if simulate is not None:
        data["simulate"] = simulate
    return data


def problems(data):
    with pytest.raises(SceneError) as err:
        linkage_sym.load_scene(data)
    return err.value.problems


@pytest.mark.parametrize("motor, simulate, field", [
    ({"torque": [[0, 1], [0, 2]]}, None, "drivers[0].motor.torque[1][0]"),
    ({"torque": [[0, 1], [5, 2], [3, 0]]}, None, "drivers[0].motor.torque[2][0]"),
    ({"torque": []}, None, "drivers[0].motor.torque"),
    ({"torque": "fast"}, None, "drivers[0].motor.torque"),
    ({"torque": [[0, 1, 2]]}, None, "drivers[0].motor.torque[0]"),
    ({"force": 3.0}, None, "drivers[0].motor.force"),
    ({}, None, "drivers[0].motor.torque"),
    ({"torque": 1.0, "power": 2}, None, "drivers[0].motor.power"),
    ({"torque": 1.0}, {"duration": 0, "samples": 11}, "simulate.duration"),
    ({"torque": 1.0}, {"duration": -1.0, "samples": 11}, "simulate.duration"),
    ({"torque": 1.0}, {"samples": 11}, "simulate.duration"),
    ({"torque": 1.0}, {"duration": 1.0, "samples": 1}, "simulate.samples"),
    ({"torque": 1.0}, {"duration": 1.0, "samples": 10**8}, "simulate.samples"),
    ({"torque": 1.0}, {"duration": 1.0, "samples": 11, "start": 0.1}, "simulate.start"),
    ({"torque": 1.0}, {"duration": 1.0, "samples": 11, "speed": 1}, "simulate.speed"),
])
def test_bad_motor_and_simulate_fields_are_named(motor, simulate, field):
    got = problems(with_motor(motor, simulate))
    assert any(p.startswith(field + ":") for p in got), got


def test_too_many_samples_say_why():
    got = problems(with_motor({"torque": 1.0}, {"duration": 1.0, "samples": 10**8}))
    assert "too many for memory" in " ".join(got)


def test_a_motor_table_reads_and_interpolates_with_its_ends_held():
    scene = linkage_sym.load_scene(with_motor({"torque": [[0, 60.0], [150, 0.0]]},
                                              {"duration": 2.0, "samples": 5}))
    motor = scene.drivers[0].motor
    assert motor.kind == "torque" and motor.speeds == (0.0, 150.0)
    assert motor_effort(motor, np.array([-1.0, 75.0, 151.0])).tolist() == [60.0, 30.0, 0.0]
    sim = scene.simulate
    assert (sim.duration, sim.samples, sim.start_speed) == (2.0, 5, 0.0)
    assert sim.start == scene.drivers[0].start  # start_deg defaults to the driver's


def test_analyze_does_not_read_the_motor_or_simulate():
    plain = linkage_sym.analyze(linkage_sym.load_scene(with_motor()))
    motored = linkage_sym.analyze(linkage_sym.load_scene(
        with_motor({"torque": [[0, 3.0], [20, 0.0]]}, {"duration": 1.0, "samples": 3})))
    assert plain.to_json() == motored.to_json()


def test_a_p_driver_takes_a_force_motor():
    data = copy.deepcopy(example_dict("slider_crank_offset"))
    for d in data["drivers"]:
        d["motor"] = {"force": [[0.0, 10.0], [1.0, 0.0]]}
    if data["drivers"][0].get("start") is None:  # an R-driven example: the crank takes torque
        assert any(p.startswith("drivers[0].motor.force:") for p in problems(data))
    else:
        assert linkage_sym.load_scene(data).drivers[0].motor.kind == "force"
