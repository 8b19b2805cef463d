"""Joint friction in the compiled symbolic runtime (contract part two, issue 29).

The runtime evaluates the generated force blocks (the frictions among their known forces)
and solves the friction laws itself (:mod:`linkage_sym.codegen.friction`), sharing no
solving code with the dyad routines or the global method; both are its references here:

* the press with friction in every joint and every derivable shipped example with friction
  put in every ``R`` and ``P`` joint: every force, friction, the friction power and the
  efficiency against the dyad routines and the global method, to 1e-9 of each quantity's
  scale;
* the inclined slider self-locks at the same steps, with the same message;
* a joint without relative motion is named in the same warning;
* a friction coefficient of 0 gives the frictionless result exactly.
"""

from __future__ import annotations

import copy

import numpy as np
import pytest

import linkage_sym
from linkage_sym.codegen.compile import compile_mechanism
from linkage_sym.errors import SYMBOLIC_LACKS
from linkage_sym.examples import example_dict
from linkage_sym.numeric.plan import compile_plan
from tests.support.example_sets import example_names, joint_types
from tests.support.force_checks import max_rel, reaction_scale
from tests.support.friction_scenes import (assert_zero_friction_is_frictionless, inclined_slider,
                                           with_friction)
from tests.support.marks import fast_cases

PRESS = "slider_crank_press_friction"
TOL = 1e-9


def _agree(scene, a, b) -> None:
    """Every force and friction quantity of ``a`` equals ``b``'s to :data:`TOL` of its scale
    (NaN at the same steps): a force's the sweep's largest reaction or effort ``F`` (couples
    and torques ``F L``), the friction power's the largest driver power, the efficiency's
    ``max(1, |eta|)`` times how much the effort's ratio amplifies the efforts' errors."""
    fa, fb = a.forces, b.forces
    assert np.array_equal(a.status, b.status)
    scale = reaction_scale(scene, fb)
    L = scene.characteristic_length()
    F = float(np.nanmax(scale))
    kind = {j.name: j.type for j in scene.joints}
    power = max(float(np.nanmax(np.abs(fb.driving[k] * b.drivers[k]["qd"]))) for k in fb.driving)
    pairs = [(fa.frame_force, fb.frame_force, F), (fa.frame_moment, fb.frame_moment, F * L),
             (fa.friction_power, fb.friction_power, power)]
    if fb.efficiency is not None:  # a ratio of efforts: e0 / e moves by (de0 + eta de) / e
        (k,) = fb.driving
        e = np.abs(fb.driving[k])
        size_e = F * L if kind[k] == "R" else F
        with np.errstate(divide="ignore"):
            pairs.append((fa.efficiency, fb.efficiency,
                          np.maximum(1.0, np.abs(fb.efficiency)) * np.maximum(1.0, size_e / e)))
    else:
        assert fa.efficiency is None
    pairs += [(fa.driving[k], fb.driving[k], F * L if kind[k] == "R" else F) for k in fb.driving]
    pairs += [(fa.friction[k], fb.friction[k], F * L if kind[k] == "R" else F)
              for k in fb.friction]
    for j in scene.joints:
        assert max_rel(fa.reactions[j.name] - fb.reactions[j.name], scale) <= TOL
        assert max_rel((fa.reaction_moments[j.name] - fb.reaction_moments[j.name]) / L,
                       scale) <= TOL
    for x, y, size in pairs:
        assert np.array_equal(np.isnan(x), np.isnan(y))
        assert np.nanmax(np.abs(x - y) / size) <= TOL


def _derivable_with_forces() -> list[str]:
    return [n for n in example_names() if not joint_types(n) & set(SYMBOLIC_LACKS)
            and {"reactions", "driving", "frame"} & set(example_dict(n).get(
                "outputs", ["reactions"]))]


def test_press_symbolic_equals_dyad_and_global():
    scene = linkage_sym.load_example(PRESS)
    plan = compile_plan(scene)
    s = compile_mechanism(scene).run()
    assert s.forces.method == "symbolic" and s.ok.all()
    assert np.any(s.forces.friction_power > 0)
    for ref in (plan.run(), plan.run(method="global")):
        _agree(scene, s, ref)


# a dyad and a triad mechanism in the fast lane, every example in the default run
@pytest.mark.parametrize("name", fast_cases(_derivable_with_forces(), {"crank_rocker", "sixbar_class3"}))
def test_every_derivable_example_with_friction_everywhere(name):
    scene = linkage_sym.load_scene(with_friction(name))
    plan = compile_plan(scene)
    s = compile_mechanism(scene).run()
    assert any(np.any(v != 0) for v in s.forces.friction.values())
    for ref in (plan.run(), plan.run(method="global")):
        _agree(scene, s, ref)


@pytest.mark.parametrize("f", [0.2, 0.35])
def test_inclined_slider_self_locks_as_the_numeric_methods_say(f):
    scene = linkage_sym.load_scene(inclined_slider(f))
    s = linkage_sym.analyze(scene, method="symbolic")
    d = linkage_sym.analyze(scene)
    assert np.sum(s.status == "self-locking") > 10
    assert list(s.status) == list(d.status)
    assert s.messages == d.messages
    _agree(scene, s, d)
    i = int(np.flatnonzero(s.status == "self-locking")[0])
    assert s.to_dict()["steps"][i] == d.to_dict()["steps"][i]  # status and message only


def test_a_joint_without_relative_motion_is_named_as_the_numeric_methods_name_it():
    d = example_dict(PRESS)
    d["drivers"][0].update(speed=0.0, acceleration=0.0, steps=5, stop_deg=40)
    scene = linkage_sym.load_scene(d)
    s, n = linkage_sym.analyze(scene, method="symbolic"), linkage_sym.analyze(scene)
    assert [w for w in s.warnings if w.startswith("joint ")] == \
        [w for w in n.warnings if w.startswith("joint ")]
    assert len([w for w in s.warnings if w.startswith("joint ")]) == len(d["joints"])
    for j in d["joints"]:
        assert np.array_equal(s.forces.friction[j["name"]], np.zeros(5))


def test_coefficient_zero_is_the_frictionless_result_exactly():
    d = example_dict(PRESS)
    zero = copy.deepcopy(d)
    for j in zero["joints"]:
        j["friction"]["coefficient"] = 0.0
    plain = copy.deepcopy(d)
    plain["effects"]["friction"] = False
    a = compile_mechanism(linkage_sym.load_scene(zero)).run().forces
    b = compile_mechanism(linkage_sym.load_scene(plain)).run().forces
    assert_zero_friction_is_frictionless(a, b)


def test_the_result_json_has_the_numeric_methods_keys():
    scene = linkage_sym.load_example(PRESS)
    s = linkage_sym.analyze(scene, method="symbolic").to_dict()
    d = linkage_sym.analyze(scene).to_dict()
    assert s["force_method"] == "symbolic"
    for a, b in zip(s["steps"], d["steps"]):
        assert set(a) == set(b)
        assert {k: set(v) for k, v in a["joints"].items()} == \
            {k: set(v) for k, v in b["joints"].items()}
