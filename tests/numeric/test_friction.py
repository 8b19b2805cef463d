"""Joint friction (contract part two, issue 29) against references that share no solver code.

* power balance at every ``ok`` step of the press with friction in every joint: the
  driver's power plus the loads' and gravity's minus dT/dt equals ``friction_power``
  (<= 1e-9 of the largest term), and ``friction_power`` equals the dissipation rebuilt
  here from the reported friction and the relative motion;
* the friction law itself, from the reported reactions and kinematics: ``|mu| = rho |R|``
  (``f |N|``), opposing the relative velocity;
* the dyad routines against the global method's own nonlinear solve (<= 1e-9);
* a slider-crank with friction at the guide only against its closed form;
* a friction coefficient of 0 gives the frictionless result exactly;
* an inclined slider pushed through a rod self-locks where the rod lies within the
  friction angle of the guide's normal (the closed form ``tan(theta) = f``);
* a scene whose friction does not act gives byte for byte the result it gave before.
"""

from __future__ import annotations

import copy
import math

import numpy as np
import pytest

import linkage_sym
from linkage_sym.examples import example_dict
from linkage_sym.numeric.plan import compile_plan
from tests.support.force_checks import max_rel, power_residual, reaction_scale
from tests.support.friction_scenes import assert_zero_friction_is_frictionless
from tests.support.friction_scenes import inclined_slider as _inclined_slider
from tests.support.friction_scenes import with_friction as _with_friction

PRESS = "slider_crank_press_friction"
TOL = 1e-9


def _relative_rate(scene, a, j):
    """``w1 - w0`` of an R joint, the slip velocity along a P joint's axis (from the result's
    kinematics: links[0]'s motion at the joint's point)."""
    def omega(link):
        return 0.0 if link == "ground" else a.links[link].omega

    if j.type == "R":
        return omega(j.links[1]) - omega(j.links[0])
    p, v1 = a.joints[j.name].position, a.joints[j.name].velocity
    if j.links[0] == "ground":
        v0, th = np.zeros_like(v1), np.zeros(a.n_steps)
    else:
        lk = a.links[j.links[0]]
        r = p - lk.origin
        v0 = lk.origin_velocity + lk.omega[:, None] * np.stack([-r[:, 1], r[:, 0]], -1)
        th = lk.rotation
    t = np.stack([np.cos(th + j.axis), np.sin(th + j.axis)], -1)
    return np.sum((v1 - v0) * t, axis=1)


@pytest.fixture(scope="module")
def press():
    scene = linkage_sym.load_example(PRESS)
    plan = compile_plan(scene)
    return scene, plan.run(), plan.run(method="global")


def test_press_power_balance_every_step(press):
    scene, a, g = press
    assert a.ok.all() and g.ok.all()
    for res in (a, g):
        r, s = power_residual(scene, res)
        assert max_rel(r, s) <= TOL
        # the dissipation rebuilt from the reported friction and the relative motion
        P = np.zeros(res.n_steps)
        for j in scene.joints:
            P = P - res.forces.friction[j.name] * _relative_rate(scene, res, j)
        scale = sum(np.abs(res.forces.friction[j.name] * _relative_rate(scene, res, j))
                    for j in scene.joints)
        assert np.all(res.forces.friction_power >= 0)
        assert max_rel(res.forces.friction_power - P, np.maximum(scale, 1e-300)) <= 1e-12
        assert res.forces.friction_power.max() > 10.0  # the press does lose power


def test_press_friction_law(press):
    scene, a, _ = press
    for j in scene.joints:
        R = a.forces.reactions[j.name]
        size = np.hypot(R[:, 0], R[:, 1])
        arm = j.friction.coefficient * (j.friction.radius or 1.0)
        mu = a.forces.friction[j.name]
        v = _relative_rate(scene, a, j)
        moving = np.abs(v) > 1e-9 * np.abs(v).max()
        assert np.allclose(np.abs(mu), arm * size, rtol=1e-13, atol=0), j.name
        assert np.all(np.sign(mu[moving]) == -np.sign(v[moving])), j.name


def test_press_dyad_equals_global(press):
    scene, a, g = press
    scale = reaction_scale(scene, g.forces)
    L = scene.characteristic_length()
    for j in scene.joints:
        assert max_rel(a.forces.reactions[j.name] - g.forces.reactions[j.name], scale) <= TOL
        div = L if j.type == "R" else 1.0
        assert max_rel((a.forces.friction[j.name] - g.forces.friction[j.name]) / div, scale) <= TOL
    assert max_rel((a.forces.driving["A"] - g.forces.driving["A"]) / L, scale) <= TOL
    assert max_rel(a.forces.frame_force - g.forces.frame_force, scale) <= TOL


def test_press_efficiency_is_ideal_over_actual_effort(press):
    scene, a, _ = press
    d = example_dict(PRESS)
    d["effects"]["friction"] = False
    ideal = linkage_sym.analyze(linkage_sym.load_scene(d)).forces.driving["A"]
    e = a.forces.driving["A"]
    same = (ideal != 0) & (np.sign(ideal) == np.sign(e))
    assert np.array_equal(np.isfinite(a.forces.efficiency), same)
    assert np.allclose(a.forces.efficiency[same], ideal[same] / e[same], rtol=1e-12, atol=0)
    # a working stroke: the driver's power goes in, and friction takes a part of it
    work = (a.forces.driving["A"] > 0) & (ideal > 0)
    assert np.all((a.forces.efficiency[work] > 0) & (a.forces.efficiency[work] < 1))


def _slider_crank(f, steps=73):
    """An offset slider-crank with massless links, a constant axial load on the slider and
    friction ``f`` at the guide only."""
    r, l, e = 0.05, 0.18, 0.02
    x0 = r + math.sqrt(l * l - e * e)
    return {
        "name": "guide-friction",
        "links": [{"name": "crank"}, {"name": "rod"}, {"name": "slider"}],
        "joints": [
            {"name": "A", "type": "R", "links": ["ground", "crank"], "at": [0.0, 0.0]},
            {"name": "B", "type": "R", "links": ["crank", "rod"], "at": [r, 0.0]},
            {"name": "C", "type": "R", "links": ["rod", "slider"], "at": [x0, e]},
            {"name": "G", "type": "P", "links": ["ground", "slider"], "at": [x0, e], "axis_deg": 0,
             "friction": {"coefficient": f}},
        ],
        "drivers": [{"joint": "A", "toward": "B", "start_deg": 3, "stop_deg": 357, "steps": steps,
                     "speed": 10.0}],
        "loads": [{"link": "slider", "force": [-250.0, 0.0], "at": [x0, e]}],
        "effects": {"inertia": False, "loads": True, "friction": True},
        "outputs": ["kinematics", "reactions", "driving"],
    }


def test_guide_friction_closed_form():
    """The rod is a two-force member: its force S e (e the unit vector B -> C) on the slider,
    the guide's normal force N = -S e_y and friction -f |N| sign(v); along the guide
    S e_x - f |S e_y| s + Fx = 0, so S = -Fx / (e_x - f s sign(S) |e_y|) (the sign of S
    the one that makes it consistent), and the crank's torque (B - A) x (S e)."""
    f, Fx = 0.25, -250.0
    res = linkage_sym.analyze(linkage_sym.load_scene(_slider_crank(f)))
    assert res.ok.all()
    B, C = res.joints["B"].position, res.joints["C"].position
    u = C - B
    e = u / np.hypot(u[:, 0], u[:, 1])[:, None]
    s = np.sign(res.joints["C"].velocity[:, 0])
    assert np.all(s != 0)
    S = np.full(res.n_steps, np.nan)
    for sigma in (1.0, -1.0):
        cand = -Fx / (e[:, 0] - f * s * sigma * np.abs(e[:, 1]))
        fits = np.sign(cand) == sigma
        S[fits] = cand[fits]
    assert np.all(np.isfinite(S))
    torque = B[:, 0] * S * e[:, 1] - B[:, 1] * S * e[:, 0]
    scale = np.abs(S).max()
    assert np.allclose(res.forces.driving["A"], torque, rtol=0, atol=1e-12 * scale * 0.05)
    assert np.allclose(res.forces.friction["G"], -f * np.abs(S * e[:, 1]) * s, rtol=0,
                       atol=1e-12 * scale)
    assert np.allclose(res.forces.reactions["G"][:, 1], -S * e[:, 1], rtol=0, atol=1e-12 * scale)


def test_coefficient_zero_is_the_frictionless_result_exactly():
    d = example_dict(PRESS)
    zero = copy.deepcopy(d)
    for j in zero["joints"]:
        j["friction"]["coefficient"] = 0.0
    plain = copy.deepcopy(d)
    plain["effects"]["friction"] = False
    for method in ("dyad", "global"):
        a = compile_plan(linkage_sym.load_scene(zero)).run(method=method).forces
        b = compile_plan(linkage_sym.load_scene(plain)).run(method=method).forces
        assert_zero_friction_is_frictionless(a, b)


@pytest.mark.parametrize("method", ["dyad", "global"])
@pytest.mark.parametrize("f", [0.2, 0.35])
def test_inclined_slider_self_locks_at_the_friction_angle(f, method):
    """Block: S e_y - f |S e_x| = W along the guide (e the rod's direction from pusher to
    block, S its compression), so S = W / (e_y - f |e_x|): finite while tan(theta) > f, and
    no finite push moves the block once the rod lies within the friction angle
    atan(f) of the guide's normal.  The pusher's effort is -S e . (-1, 0)."""
    d = _inclined_slider(f)
    scene = linkage_sym.load_scene(d)
    res = compile_plan(scene).run(method=method)
    B = res.drivers["A"]["q"]
    l, xb0 = 0.1, d["joints"][0]["at"][0]
    xb = xb0 - B
    yc = np.sqrt(l * l - xb * xb)
    tan = yc / xb
    phi = math.atan(f)
    free, locked = tan > f * (1 + 1e-9), tan < f * (1 - 1e-9)
    assert free.sum() > 20 and locked.sum() > 10  # the sweep crosses the friction angle
    assert np.all(res.status[free] == "ok")
    assert np.all(res.status[locked] == "self-locking")
    for i in np.flatnonzero(locked):
        assert "C_guide" in res.messages[i] and "self-locking" in res.messages[i]
    ex, ey = -xb / l, yc / l
    W = 2.0 * 9.81
    S = W / (ey - f * np.abs(ex))
    push = -S * ex  # the effort along the pusher's axis (-1, 0)
    assert np.allclose(res.forces.driving["A"][free], push[free], rtol=1e-11, atol=0)
    assert np.all(np.isnan(res.forces.driving["A"][locked]))
    # the onset is where the rod's angle above the horizontal is the friction angle
    theta = np.arctan(tan)
    last_free = theta[free].min()
    first_locked = theta[locked].max()
    assert first_locked < phi < last_free


def test_inclined_slider_result_json():
    """A self-locking step carries its status and message only (no forces), like a step
    that does not assemble; the ok steps carry the friction's keys."""
    res = linkage_sym.analyze(linkage_sym.load_scene(_inclined_slider(0.35, steps=21)))
    steps = res.to_dict()["steps"]
    kinds = {s["status"] for s in steps}
    assert kinds == {"ok", "self-locking"}
    for s in steps:
        if s["status"] == "self-locking":
            assert set(s) == {"status", "message", "drivers"}
        else:
            assert "friction_force" in s["joints"]["C_guide"]
            assert s["friction_power"] >= 0
            assert "efficiency" in s


def test_friction_not_acting_leaves_the_result_byte_identical():
    d = example_dict(PRESS)
    off = copy.deepcopy(d)
    off["effects"]["friction"] = False
    bare = copy.deepcopy(off)
    del bare["effects"]["friction"]
    for j in bare["joints"]:
        del j["friction"]
    a = linkage_sym.analyze(linkage_sym.load_scene(off)).to_json()
    b = linkage_sym.analyze(linkage_sym.load_scene(bare)).to_json()
    assert a == b
    assert '"friction_' not in a and '"efficiency"' not in a


@pytest.mark.parametrize("name", ["sixbar_class3", "hydraulic_boom", "printing_mechanism",
                                  "planetary_train", "gear_linkage", "guide_bar_quick_return"])
def test_every_group_kind_with_friction_against_the_global_method(name):
    """Class-III groups (the disconnection and superposition: the friction's Newton is
    outside it, the superposition only ever solves the linear problem), a driven group
    (the boom's actuator), dense gear groups and an RPR dyad: the group routines with
    friction in every joint against the global method's own nonlinear solve, and both
    against each link's equilibrium and the power balance (<= 1e-9)."""
    from tests.support.force_checks import link_residuals

    scene = linkage_sym.load_scene(_with_friction(name))
    plan = compile_plan(scene)
    a, g = plan.run(), plan.run(method="global")
    assert a.ok.all() and g.ok.all()
    scale = reaction_scale(scene, g.forces)
    L = scene.characteristic_length()
    for j in scene.joints:
        assert max_rel(a.forces.reactions[j.name] - g.forces.reactions[j.name], scale) <= TOL
        if j.friction is not None:
            div = L if j.type == "R" else 1.0
            assert max_rel((a.forces.friction[j.name] - g.forces.friction[j.name]) / div,
                           scale) <= TOL
            assert np.any(a.forces.friction[j.name] != 0)
    for d in scene.drivers:
        div = L if d.kind == "R" else 1.0
        assert max_rel((a.forces.driving[d.joint] - g.forces.driving[d.joint]) / div, scale) <= TOL
    for res in (a, g):
        for link, (rf, rm, sf, sm) in link_residuals(scene, res).items():
            assert max_rel(rf, sf) <= TOL and max_rel(rm, sm) <= TOL, link
        r, s = power_residual(scene, res)
        assert max_rel(r, s) <= TOL


def test_mean_efficiency_in_the_summary_whole_and_in_chunks(tmp_path):
    """Work out over work in: the driver's work with the friction left out over its work
    with it (trapezoids over the driver's angle), the same from a sweep written in chunks;
    the console summary says it."""
    from linkage_sym import output
    from linkage_sym.cli.analyze import summary

    scene = linkage_sym.load_example(PRESS)
    res = linkage_sym.analyze(scene)
    d = example_dict(PRESS)
    d["effects"]["friction"] = False
    ideal = linkage_sym.analyze(linkage_sym.load_scene(d)).forces.driving["A"]
    q = res.drivers["A"]["q"]
    w_in = np.trapezoid(res.forces.driving["A"], q)
    w_out = np.trapezoid(ideal, q)
    assert 0.5 < w_out / w_in < 1.0
    whole = output.SweepStats.of(res)
    assert whole.work.work_in == pytest.approx(w_in, rel=1e-12)
    assert whole.work.efficiency() == pytest.approx(w_out / w_in, rel=1e-12)
    stats = output.write_sweep(output.plan_sweep(compile_plan(scene), "dyad"),
                               tmp_path / "r.npz", "npz", chunk=37)
    assert stats.work.efficiency() == pytest.approx(w_out / w_in, rel=1e-12)
    assert stats.work.friction_peak.value == whole.work.friction_peak.value
    text = "\n".join(summary(scene, res))
    assert f"mean efficiency over the sweep: {w_out / w_in:.4g}" in text
    assert "peak friction power" in text


def test_a_joint_without_relative_motion_has_no_friction_and_is_named():
    """At rest (driver speed and acceleration 0) no joint has a direction of friction: each
    is named with its steps in a warning, and the forces are the frictionless ones."""
    d = example_dict(PRESS)
    d["drivers"][0].update(speed=0.0, acceleration=0.0, steps=5, stop_deg=40)
    res = linkage_sym.analyze(linkage_sym.load_scene(d))
    for j in d["joints"]:
        (w,) = [w for w in res.warnings if w.startswith(f"joint {j['name']}:")]
        assert "at 5 step(s) (steps 0, 1, 2, 3, 4)" in w
        assert np.array_equal(res.forces.friction[j["name"]], np.zeros(5))
    d["effects"]["friction"] = False
    plain = linkage_sym.analyze(linkage_sym.load_scene(d))
    assert np.array_equal(res.forces.driving["A"], plain.forces.driving["A"])


@pytest.mark.parametrize("types, flip, driver, seed", __import__(
    "tests.numeric.test_kinetostatics", fromlist=["loop_cases"]).loop_cases())
def test_every_dyad_type_and_orientation_with_friction(types, flip, driver, seed):
    """The kinetostatics contract (tests/numeric/test_kinetostatics.py: dyad routines against
    the global method, every link's equilibrium, the power balance, each <= 1e-9) with
    friction in every joint, the driven one (an R or a P driver) too, for every dyad type
    with its joints' links in either order; and the friction law of every joint."""
    from tests.numeric.test_kinetostatics import check_contract, loop_scene, run_both, well_conditioned

    def make(s):
        d = loop_scene(types, flip=flip, seed=s, driver=driver)
        d["effects"]["friction"] = True
        for j in d["joints"]:
            j["friction"] = ({"coefficient": 0.15, "radius": 0.02} if j["type"] == "R"
                             else {"coefficient": 0.12})
        return d

    scene, plan, a, g = run_both(well_conditioned(make, seed))
    check_contract(scene, a, g)
    for j in scene.joints:
        R = a.forces.reactions[j.name]
        mu = a.forces.friction[j.name]
        v = _relative_rate(scene, a, j)
        # (with a P driver a PRP, RPP or PPR loop only translates: its pins never turn, have
        # no friction, and a warning names them)
        moving = np.abs(v) > 1e-9 * max(np.abs(v).max(), 1e-300)
        assert np.allclose(np.abs(mu[moving]), j.friction.arm * np.hypot(R[moving, 0], R[moving, 1]),
                           rtol=1e-12, atol=0), j.name
        assert np.all(np.sign(mu[moving]) == -np.sign(v[moving])), j.name
        if not moving.any() and not np.any(mu):
            assert any(w.startswith(f"joint {j.name}: neither") for w in a.warnings), j.name
        assert max_rel(a.forces.friction[j.name] - g.forces.friction[j.name],
                       reaction_scale(scene, g.forces) * (scene.characteristic_length()
                                                          if j.type == "R" else 1.0)) <= TOL
