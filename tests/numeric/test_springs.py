"""Springs and dampers in the force analysis (the contract's ``springs``).

Checked against references that share no code with the solver:

* the power balance at every ``ok`` step, driver power + loads + gravity + the
  springs' power ``-dV/dt`` less the dampers' loss - ``dT/dt`` = 0, with ``V``
  written from the spring's own variables (:mod:`tests.support.spring_checks`),
  and every link's equilibrium, to 1e-9 of the sum of the terms' magnitudes, on
  the crank-rocker with a link spring and a joint spring with damping (the
  shipped example) and on the class-III six-bar with springs inside and across its
  triad, by every disconnection and by the global method;
* the dyad method against the global method, reactions, efforts, frame, to 1e-9;
* the frame: with the ground's ends of the springs counted, the frame's force
  and moment are the resultant of the inertia, weight and loads (the springs
  are internal to the machine);
* closed forms: a slider-crank held by a spring on its slider, its driving
  torque by virtual work, ``tau = -F_x dx/dphi``, plus a torsion spring at the
  crank's pivot, at static positions and with a damper at speed;
* a scene whose springs do not act gives the same bytes as one without springs.
"""

from __future__ import annotations

import copy
import dataclasses
import math

import numpy as np
import pytest

import linkage_sym
from linkage_sym.examples import example_dict
from linkage_sym.numeric.plan import compile_plan
from linkage_sym.structure.disconnection import usable_disconnections
from tests.support.force_checks import applied, link_residuals, max_rel, power_residual, reaction_scale
from tests.support.spring_checks import class3_with_springs, energy

TOL = 1e-9


def _checked(scene, res):
    """Every link in equilibrium and the power balance, to TOL, at every ok step."""
    assert res.ok.all()
    for link, (rf, rm, sf, sm) in link_residuals(scene, res).items():
        assert max_rel(rf, sf) <= TOL, (res.forces.method, link, "force")
        assert max_rel(rm, sm) <= TOL, (res.forces.method, link, "moment")
    r, s = power_residual(scene, res)
    assert max_rel(r, s) <= TOL, (res.forces.method, "power")


def _agree(scene, a, g):
    """The dyad (or superposition) run ``a`` against the global run ``g``, to TOL."""
    scale = reaction_scale(scene, g.forces)
    L = scene.characteristic_length()
    for j in g.forces.reactions:
        assert max_rel(a.forces.reactions[j] - g.forces.reactions[j], scale) <= TOL, j
    for d in scene.drivers:
        assert max_rel((a.forces.driving[d.joint] - g.forces.driving[d.joint]) / L, scale) <= TOL
    assert max_rel(a.forces.frame_force - g.forces.frame_force, scale) <= TOL
    assert max_rel((a.forces.frame_moment - g.forces.frame_moment) / L, scale) <= TOL
    for name, rec in g.forces.springs.items():
        for key, v in rec.items():
            np.testing.assert_array_equal(a.forces.springs[name][key], v)


def _frame_is_the_resultant(scene, res):
    """Frame force and moment about the origin = resultant of inertia, weight and loads."""
    F = np.zeros((res.n_steps, 2))
    M = np.zeros(res.n_steps)
    sF = np.zeros(res.n_steps)
    sM = np.zeros(res.n_steps)
    no_springs = dataclasses.replace(scene, springs=())
    for forces, couples in applied(no_springs, res).values():
        for f, p in forces:
            F = F + f
            M = M + p[:, 0] * f[:, 1] - p[:, 1] * f[:, 0]
            sF = sF + np.hypot(f[:, 0], f[:, 1])
            sM = sM + np.hypot(p[:, 0], p[:, 1]) * np.hypot(f[:, 0], f[:, 1])
        for c in couples:
            M = M + c
            sM = sM + np.abs(c)
    # the links' weights and loads are not all of the scale: the springs' pulls are too
    for name, rec in res.forces.springs.items():
        effort = np.abs(rec.get("force", rec.get("torque")))
        sF = sF + effort
        sM = sM + effort * max(scene.characteristic_length(), 1.0)
    assert max_rel(res.forces.frame_force - F, sF) <= TOL
    assert max_rel(res.forces.frame_moment - M, sM) <= TOL


def test_crank_rocker_with_a_link_spring_and_a_damped_joint_spring():
    d = example_dict("crank_rocker_spring")
    d["springs"][1]["damping"] = 0.01  # the joint spring damped too
    scene = linkage_sym.load_scene(d)
    plan = compile_plan(scene)
    a, g = plan.run(), plan.run(method="global")
    assert a.stages == ("position", "velocity", "acceleration", "forces")
    for res in (a, g):
        _checked(scene, res)
        _frame_is_the_resultant(scene, res)
    _agree(scene, a, g)
    # the springs do work: their power is a sizeable part of the balance
    V, dV, lost, _ = energy(scene, a)["k1"]
    assert np.abs(dV).max() > 0.1 * np.abs(a.forces.driving["A"] * 10.0).max()
    assert lost.min() >= 0.0 and lost.max() > 0.0


def test_damping_alone_needs_velocities_stiffness_alone_does_not():
    d = example_dict("crank_rocker_spring")
    d["effects"]["inertia"] = False
    d["outputs"] = ["driving"]
    scene = linkage_sym.load_scene(d)
    assert compile_plan(scene).stages == ("position", "velocity", "acceleration", "forces")
    d["springs"][0]["damping"] = 0.0
    assert compile_plan(linkage_sym.load_scene(d)).stages == ("position", "forces")



def test_class_three_group_by_every_disconnection_and_the_global_method():
    scene = class3_with_springs()
    g = compile_plan(scene).run(method="global")
    _checked(scene, g)
    _frame_is_the_resultant(scene, g)
    (triad,) = [x for x in compile_plan(scene).decomposition.groups if x.kind == "triad"]
    choices = usable_disconnections(scene, triad)
    assert len(choices) >= 2
    for k in range(len(choices)):
        a = compile_plan(scene, disconnection=k).run()
        assert a.forces.groups[1].method == "disconnection"
        _checked(scene, a)
        _agree(scene, a, g)


def _slider_crank(r=0.05, l=0.2, phi0_deg=30.0, anchor=0.4, k=2000.0, free=0.1, c=0.0,
                  torsion=0.0, speed=0.0, steps=13):
    """A centred slider-crank, massless, no loads: a spring from the ground point
    (anchor, 0) to the slider, and a torsion spring at the crank's pivot."""
    phi0 = math.radians(phi0_deg)
    B = [r * math.cos(phi0), r * math.sin(phi0)]
    xs = B[0] + math.sqrt(l * l - B[1] ** 2)
    springs = [{"name": "k", "links": ["ground", "slider"], "at": [[anchor, 0.0], [xs, 0.0]],
                "stiffness": k, "free_length": free, "damping": c}]
    if torsion:
        springs.append({"name": "t", "joint": "A", "stiffness": torsion, "free_angle_deg": 10.0})
    return {
        "name": "slider-crank-spring",
        "links": [{"name": "crank"}, {"name": "rod"}, {"name": "slider"}],
        "joints": [
            {"name": "A", "type": "R", "links": ["ground", "crank"], "at": [0.0, 0.0]},
            {"name": "B", "type": "R", "links": ["crank", "rod"], "at": B},
            {"name": "C", "type": "R", "links": ["rod", "slider"], "at": [xs, 0.0]},
            {"name": "S", "type": "P", "links": ["ground", "slider"], "at": [xs, 0.0], "axis_deg": 0},
        ],
        "drivers": [{"joint": "A", "toward": "B", "start_deg": 10, "stop_deg": 170, "steps": steps,
                     "speed": speed}],
        "effects": {"inertia": False, "loads": False},
        "outputs": ["driving", "reactions"],
        "springs": springs,
    }


def _virtual_work(phi, r, l, anchor, k, free, c, speed):
    """``tau = -F_x dx/dphi``: the slider at ``x = r cos phi + sqrt(l^2 - r^2 sin^2 phi)``,
    pulled toward the anchor by the tension ``k (L - free) + c dL/dt``, ``L = anchor - x``."""
    s = np.sin(phi)
    root = np.sqrt(l * l - (r * s) ** 2)
    x = r * np.cos(phi) + root
    dx = -r * s - r * r * s * np.cos(phi) / root
    L = anchor - x
    tension = k * (L - free) + c * (-dx * speed)
    Fx = tension  # toward the anchor, +x
    return -Fx * dx


@pytest.mark.parametrize("c, speed", [(0.0, 0.0), (0.0, 3.0), (40.0, 3.0), (40.0, -2.0)])
def test_slider_crank_held_by_a_spring_against_virtual_work(c, speed):
    r, l, anchor, k, free = 0.05, 0.2, 0.4, 2000.0, 0.1
    for method in ("dyad", "global"):
        res = linkage_sym.analyze(linkage_sym.load_scene(
            _slider_crank(r, l, anchor=anchor, k=k, free=free, c=c, speed=speed)), method=method)
        phi = res.drivers["A"]["q"]
        want = _virtual_work(phi, r, l, anchor, k, free, c, speed)
        tau = res.forces.driving["A"]
        assert np.abs(tau - want).max() <= 1e-12 * np.abs(want).max() * 10, method
        L = res.forces.springs["k"]["length"]
        x = r * np.cos(phi) + np.sqrt(l * l - (r * np.sin(phi)) ** 2)
        np.testing.assert_allclose(L, anchor - x, rtol=0, atol=1e-15)


def test_torsion_spring_at_the_driven_pivot_adds_its_torque():
    r, l, anchor, k, free, kt = 0.05, 0.2, 0.4, 2000.0, 0.1, 3.0
    res = linkage_sym.analyze(linkage_sym.load_scene(
        _slider_crank(r, l, anchor=anchor, k=k, free=free, torsion=kt)))
    phi = res.drivers["A"]["q"]
    theta = phi - math.radians(30.0)  # the crank's rotation from the assembly configuration
    want = _virtual_work(phi, r, l, anchor, k, free, 0.0, 0.0) + kt * (theta - math.radians(10.0))
    assert np.abs(res.forces.driving["A"] - want).max() <= 1e-11 * np.abs(want).max()
    np.testing.assert_allclose(res.forces.springs["t"]["angle"], theta, rtol=0, atol=1e-15)
    np.testing.assert_allclose(res.forces.springs["t"]["torque"],
                               -kt * (theta - math.radians(10.0)), rtol=0, atol=1e-14)


def test_result_records_and_columns():
    res = linkage_sym.analyze(linkage_sym.load_example("crank_rocker_spring"))
    step = res.to_dict()["steps"][7]
    assert list(step)[-2:] == ["springs", "accuracy"]
    assert set(step["springs"]) == {"k1", "k2"}
    assert list(step["springs"]["k1"]) == ["length", "force"]
    assert list(step["springs"]["k2"]) == ["angle", "torque"]
    rec = step["springs"]["k1"]
    assert rec["force"] == pytest.approx(500.0 * (rec["length"] - 0.03)
                                         + 2.0 * _rate(res, 7), rel=1e-12)
    names = [n for n, _, _ in res.columns()]
    i = names.index("frame.moment")
    assert names[i + 1:i + 5] == ["springs.k1.length", "springs.k1.force",
                                  "springs.k2.angle", "springs.k2.torque"]


def _rate(res, i):
    """dL/dt of the example's spring k1 at step ``i``, by the chain rule on the result."""
    lk = res.links["rocker"]
    p, v = lk.point((0.07, 0.02))[i], lk.point_velocity((0.07, 0.02))[i]
    d = p - np.array([0.10, 0.05])
    return float(d @ v / np.hypot(*d))


def test_no_spring_record_at_steps_that_are_not_ok():
    # a longer crank: a non-Grashof four-bar, whose crank cannot turn through every step
    d = example_dict("crank_rocker_spring")
    d["joints"][1]["at"] = [0.045, 0.0]
    d["drivers"][0]["steps"] = 37
    res = linkage_sym.analyze(linkage_sym.load_scene(d))
    steps = res.to_dict()["steps"]
    assert 0 < [s["status"] for s in steps].count("ok") < len(steps)
    assert all(("springs" in s) == (s["status"] == "ok") for s in steps)


def test_springs_that_do_not_act_give_the_same_bytes_as_none():
    base = example_dict("crank_rocker")
    with_springs = copy.deepcopy(example_dict("crank_rocker_spring"))
    with_springs["name"] = base["name"]
    with_springs["effects"]["springs"] = False
    for method in ("dyad", "global"):
        a = linkage_sym.analyze(linkage_sym.load_scene(base), method=method).to_json()
        b = linkage_sym.analyze(linkage_sym.load_scene(with_springs), method=method).to_json()
        assert a == b


def test_the_symbolic_layer_derives_acting_springs():
    """The symbolic layer no longer refuses springs (it derives them:
    ``tests/codegen/test_symbolic_springs.py`` checks its forces); its kinematics are
    unchanged by them."""
    scene = linkage_sym.load_example("crank_rocker_spring")
    sym = linkage_sym.analyze(scene, method="symbolic")
    assert set(sym.forces.springs) == {"k1", "k2"}
    assert linkage_sym.derive(scene, forces=True).spring_efforts
    kin = dataclasses.replace(scene, outputs=("kinematics",))
    sym = linkage_sym.analyze(kin, method="symbolic")
    num = linkage_sym.analyze(kin)
    assert np.abs(sym.links["rocker"].rotation - num.links["rocker"].rotation).max() < 1e-12


def test_design_sweeps_compute_force_metrics_with_springs():
    """Design sweeps no longer refuse force metrics under springs
    (``tests/design/test_design_springs.py`` checks them against analyze)."""
    scene = linkage_sym.load_example("crank_rocker_spring")
    res = linkage_sym.sweep(scene, {"l_AB": [0.024]}, ["K", "rms_driving"])
    assert len(res) == 1
    ok = linkage_sym.analyze(scene).forces.driving["A"][:-1]  # a whole turn: the end once
    assert abs(res["rms_driving_A"][0] - np.sqrt(np.mean(ok ** 2))) <= 1e-10 * np.abs(ok).max()
