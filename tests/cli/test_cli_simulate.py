"""``linkage-sym simulate`` and ``linkage-sym flywheel``: a summary on the console, the JSON
with ``-o``, exit status 2 with the field or option named and nothing written."""

from __future__ import annotations

import copy
import math
import json

import pytest

from linkage_sym.cli import main
from linkage_sym.examples import example_dict


def short_scene(tmp_path, **simulate):
    data = copy.deepcopy(example_dict("crank_rocker"))
    data["links"][0]["inertia"] = 2e-3
    data["drivers"][0]["motor"] = {"torque": [[0.0, 1.0], [16.0, 0.0]]}
    data["simulate"] = {"duration": 0.1, "start_deg": 0.0, "start_speed": 12.0, "samples": 11,
                        **simulate}
    path = tmp_path / "scene.json"
    path.write_text(json.dumps(data))
    return path


@pytest.mark.slow
def test_simulate_writes_the_result_and_prints_a_summary(tmp_path, capsys):
    out = tmp_path / "r" / "result.json"
    pics = tmp_path / "pics"
    assert main(["simulate", str(short_scene(tmp_path)), "-o", str(out), "--plots",
                 str(pics)]) == 0
    printed = capsys.readouterr().out
    assert sorted(p.name for p in pics.iterdir()) == ["crank-rocker_speed.png",
                                                       "crank-rocker_torque_balance.png"]
    assert "simulated crank-rocker: 11 samples over 0.1 s" in printed
    assert "no periodic motion" in printed
    got = json.loads(out.read_text())
    assert [s["time"] for s in got["steps"]] == [k / 100 for k in range(11)]
    assert got["integrator"]["rtol"] == 1e-10 and got["integrator"]["end"] == "duration"
    assert "reason" in got["motion"]
    assert set(got["steps"][3]) >= {"time", "status", "drivers", "joints", "links", "driving"}


def test_simulate_refuses_a_bad_scene_by_field_and_writes_nothing(tmp_path, capsys):
    out = tmp_path / "result.json"
    code = main(["simulate", str(short_scene(tmp_path, duration=0)), "-o", str(out)])
    assert code == 2
    assert "simulate.duration" in capsys.readouterr().err
    assert not out.exists()


def test_flywheel_refuses_a_fluctuation_out_of_range(tmp_path, capsys):
    code = main(["flywheel", str(short_scene(tmp_path)), "--fluctuation", "0"])
    assert code == 2
    assert "--fluctuation" in capsys.readouterr().err


def two_motor_scene(tmp_path, drop_motor=False):
    data = copy.deepcopy(example_dict("fivebar_motors"))
    data["simulate"].update(duration=0.05, samples=6)
    if drop_motor:
        del data["drivers"][1]["motor"]
    path = tmp_path / "fivebar.json"
    path.write_text(json.dumps(data))
    return path


@pytest.mark.slow
def test_simulate_with_two_motors_summarises_each_and_plots_their_speeds(tmp_path, capsys):
    out = tmp_path / "result.json"
    pics = tmp_path / "pics"
    assert main(["simulate", str(two_motor_scene(tmp_path)), "-o", str(out), "--plots",
                 str(pics)]) == 0
    printed = capsys.readouterr().out
    assert "simulated fivebar-motors: 6 samples over 0.05 s, 2 motors" in printed
    assert "  driver A: speed 0 ->" in printed and "  driver E: speed 0 ->" in printed
    assert sorted(p.name for p in pics.iterdir()) == ["fivebar-motors_speed.png",
                                                       "fivebar-motors_torque_balance.png"]
    got = json.loads(out.read_text())
    assert set(got["steps"][2]["drivers"]) == {"A", "E"}
    assert set(got["motion"]["drivers"]) == {"A", "E"}


def test_simulate_refuses_a_driver_without_a_motor_and_writes_nothing(tmp_path, capsys):
    out = tmp_path / "result.json"
    code = main(["simulate", str(two_motor_scene(tmp_path, drop_motor=True)), "-o", str(out)])
    assert code == 2
    assert "drivers[1].motor: required to simulate" in capsys.readouterr().err
    assert not out.exists()


def main_shaft_scene(tmp_path):
    """The flywheel problem of notebooks/flywheel.py (textbook-style, its numbers ours): a
    resisting moment of 300 N m over the first half of each turn of the main shaft (the
    crank-rocker's crank), a motor whose moment falls steeply through 150 N m at 100 rad/s."""
    data = copy.deepcopy(example_dict("crank_rocker"))
    data["name"] = "main-shaft"
    data["loads"] = [{"link": "crank", "torque": -300.0, "active_deg": [0, 180], "driver": "A"}]
    data["effects"]["gravity"] = False
    data["drivers"][0]["motor"] = {"torque": [[90.0, 450.0], [110.0, -150.0]]}
    path = tmp_path / "main_shaft.json"
    path.write_text(json.dumps(data))
    return path


@pytest.mark.slow
def test_flywheel_writes_the_result_and_its_three_plots_and_prints_both_estimates(
        tmp_path, capsys):
    out = tmp_path / "f" / "flywheel.json"
    pics = tmp_path / "pics"
    assert main(["flywheel", str(main_shaft_scene(tmp_path)), "--fluctuation", "0.02",
                 "-o", str(out), "--plots", str(pics)]) == 0
    printed = capsys.readouterr().out
    assert sorted(p.name for p in pics.iterdir()) == [
        "main-shaft_energy.png", "main-shaft_flywheel_speed.png", "main-shaft_flywheel_torque.png"]
    got = json.loads(out.read_text())
    assert got["link"] == "crank" and got["requested_fluctuation"] == 0.02
    # the contract: the inertia to add and the fluctuation the simulated motion then has,
    # within 1 % below the request
    assert 0.99 * 0.02 <= got["fluctuation"] <= 0.02
    assert got["iterations"][-1] == {"inertia": got["inertia"], "fluctuation": got["fluctuation"]}
    # by hand (the textbook's energy method): the surplus falls by (300 - 150) N m over half a
    # turn, dW_max = 150 pi J, J_F = dW_max / (w_m^2 [delta]) = 2.356 kg m^2 at w_m = 100 rad/s;
    # the trapezoid sum over the turn and the mean speed the motor settles at (not exactly 100)
    # put the computed values within 2e-3 of it
    e = got["energy_method"]
    assert e["delta_E_max"] == pytest.approx(150 * math.pi, rel=2e-3)
    assert e["inertia"] == pytest.approx(150 * math.pi / (100**2 * 0.02), rel=2e-3)
    assert f"largest energy surplus {e['delta_E_max']:.6g} J" in printed
    assert f"refined by simulation: flywheel {got['inertia']:.6g} kg m^2" in printed
    assert f"wrote {out}" in printed


def test_flywheel_refuses_a_bad_scene_by_field_and_writes_nothing(tmp_path, capsys):
    out = tmp_path / "flywheel.json"
    pics = tmp_path / "pics"
    code = main(["flywheel", str(short_scene(tmp_path, samples=0)), "--fluctuation", "0.02",
                 "-o", str(out), "--plots", str(pics)])
    assert code == 2
    assert "simulate.samples" in capsys.readouterr().err
    assert not out.exists() and not pics.exists()
