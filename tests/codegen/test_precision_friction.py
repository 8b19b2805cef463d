"""Joint friction at arbitrary precision (``--precision``, contract part two, issue 29).

The mpmath backend solves each step's friction laws with the evaluator's friction solve
in mpmath (Newton carried to the working precision):

* the press with friction in every joint at 50 digits against float64 (the dyad routines,
  which share no code with it) to 1e-12 of each quantity's scale, as the precision tests
  of the frictionless forces do;
* the friction law holds at the working precision: ``|Mf| = f r |R|``, ``|Ff| = f |N|``
  from the unrounded values, to 1e-45 (the friction's Newton is not stopped at float64's
  rounding);
* the inclined slider's self-locking steps are the float64 run's.
"""

from __future__ import annotations

import dataclasses

import mpmath as mp
import numpy as np
import pytest

import linkage_sym
from linkage_sym.codegen.precision import run_precise
from tests.support.friction_scenes import inclined_slider

PRESS = "slider_crank_press_friction"


def _press(steps=19):
    scene = linkage_sym.load_example(PRESS)
    return dataclasses.replace(scene, drivers=tuple(
        dataclasses.replace(dr, steps=steps) for dr in scene.drivers))


@pytest.fixture(scope="module")
def press50():
    scene = _press()
    return scene, run_precise(scene, 50), linkage_sym.analyze(scene)


def test_press_at_50_digits_equals_float64(press50):
    scene, pr, num = press50
    got = pr.analysis
    assert got.forces.method == "mpmath" and list(got.status) == list(num.status)
    g, n = got.forces, num.forces
    pairs = [(g.driving["A"], n.driving["A"]), (g.frame_force, n.frame_force),
             (g.frame_moment, n.frame_moment), (g.friction_power, n.friction_power)]
    pairs += [(g.reactions[k], n.reactions[k]) for k in n.reactions]
    pairs += [(g.friction[k], n.friction[k]) for k in n.friction]
    pairs += [(g.driving_ideal[k], n.driving_ideal[k]) for k in n.driving_ideal]
    for a, b in pairs:
        scale = float(np.nanmax(np.abs(b))) or 1.0
        assert float(np.nanmax(np.abs(a - b))) <= 1e-12 * scale
    # the efficiency, a ratio of efforts, to 1e-12 of the efforts' scale over the effort
    e = np.abs(n.driving["A"])
    size = np.maximum(1.0, np.abs(n.efficiency)) * np.maximum(1.0, np.nanmax(e) / e)
    assert np.array_equal(np.isnan(g.efficiency), np.isnan(n.efficiency))
    assert np.nanmax(np.abs(g.efficiency - n.efficiency) / size) <= 1e-12
    assert np.all(g.friction_power[got.ok] > 0)
    got.to_json()  # strict JSON


def test_the_friction_law_holds_at_the_working_precision(press50):
    scene, pr, _ = press50
    checked = 0
    with mp.workdps(50):
        for rec in pr.steps:
            if rec is None or "friction" not in rec:
                continue
            for j in scene.joints:
                mu = rec["friction"][j.name]
                if j.type == "R":
                    fx, fy = rec["reactions"][j.name]
                    size = mp.mpf(j.friction.coefficient) * mp.mpf(j.friction.radius) * mp.sqrt(
                        fx * fx + fy * fy)
                else:  # the normal force: the reaction across the slide
                    fx, fy = rec["reactions"][j.name]
                    size = mp.mpf(j.friction.coefficient) * mp.sqrt(fx * fx + fy * fy)
                assert abs(abs(mu) - size) <= mp.mpf(10) ** -45 * (size + 1)
                checked += 1
    assert checked == len(scene.joints) * len(pr.steps)


def test_self_locking_steps_are_the_float64_runs():
    scene = linkage_sym.load_scene(inclined_slider(0.35, steps=13))
    got = linkage_sym.analyze(scene, precision=30)
    num = linkage_sym.analyze(scene)
    assert "self-locking" in set(got.status)
    assert list(got.status) == list(num.status) and got.messages == num.messages
    ok = got.ok
    scale = float(np.nanmax(np.abs(num.forces.driving["A"])))
    assert np.nanmax(np.abs(got.forces.driving["A"][ok] - num.forces.driving["A"][ok])) \
        <= 1e-12 * scale
    assert np.all(np.isnan(got.forces.driving["A"][~ok]))
