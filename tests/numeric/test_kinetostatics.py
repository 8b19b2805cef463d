"""Kinetostatics: one contract that every force routine must pass.

Every dyad type (RRR, RRP, RPR, PRP, RPP, in both orientations and with
every joint's links in either order), input links driven at an R or a P
joint, the class-III group by every disconnection, the driven (actuator)
group, and both methods (``dyad`` and ``global``) must satisfy, at every
step:

* the dyad method equals the global sparse solve (<= 1e-9 relative to the
  step's largest reaction);
* every link is in equilibrium under its reported reactions, efforts and
  loads (:func:`force_checks.link_residuals`, written from the scene format
  alone; <= 1e-9 relative to the sum of the magnitudes of the terms);
* power balance: driver power = dT/dt - P_gravity - P_loads (<= 1e-9
  relative to the sum of the magnitudes of the power terms);
* inertia only: frame force = -sum m a_G and frame moment = -dH_O/dt
  (<= 1e-9 relative to the sum of the terms' magnitudes).

Why 1e-9 holds with room: the test mechanisms stay away from singular
positions (dimensionless condition numbers below ~1e4, asserted), so
round-off leaves ~1e-12 at most; a wrong sign or a missing term gives O(1).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import linkage_sym
from tests.support.force_checks import (
    link_residuals,
    max_rel,
    momentum_frame,
    power_residual,
    reaction_scale,
)
from linkage_sym.examples import example_dict, example_names
from linkage_sym.numeric.plan import compile_plan
from linkage_sym.structure.disconnection import usable_disconnections

TOL = 1e-9


# --------------------------------------------------------------------------- scenes
def loop_scene(types, *, flip=(False, False, False, False), seed=0, driver="R",
               effects=None, steps=25, outputs=None):
    """A single-loop mechanism ground-crank-coupler-rocker with joint types ``types``.

    ``types`` gives the types of joints B (crank-coupler), C (coupler-rocker)
    and D (rocker-ground); A (ground-crank) is the driven joint, of type
    ``driver``.  ``flip[k]`` swaps the two links of joint A, B, C, D.  Masses,
    centres of mass, inertias, loads and slide axes are drawn from ``seed``.
    Any assembly configuration is consistent (link geometry is read off it);
    the sweep is +-12 degrees (or +-0.02 m) about it.
    """
    rng = np.random.default_rng(seed)
    A = np.array([0.0, 0.0])
    B = np.array([0.25, 0.05]) + rng.uniform(-0.03, 0.03, 2)
    C = np.array([0.75, 0.45]) + rng.uniform(-0.05, 0.05, 2)
    D = np.array([0.95, 0.0]) + rng.uniform(-0.05, 0.05, 2)
    pts = {"A": A, "B": B, "C": C, "D": D}
    pairs = {"A": ["ground", "crank"], "B": ["crank", "coupler"], "C": ["coupler", "rocker"],
             "D": ["rocker", "ground"]}
    jtypes = {"A": driver, "B": types[0], "C": types[1], "D": types[2]}
    joints = []
    for k, name in enumerate("ABCD"):
        links = list(pairs[name])
        if flip[k]:
            links.reverse()
        if name == "B" and driver == "R" and jtypes["B"] == "P":
            # an R driver's `toward` point must be fixed on the crank: B's links[1]
            links = ["coupler", "crank"]
        j = {"name": name, "type": jtypes[name], "links": links,
             "at": [float(v) for v in pts[name]]}
        if jtypes[name] == "P":
            j["axis_deg"] = float(rng.uniform(-80, 80) + (30 if name == "A" else 0))
        joints.append(j)
    links = []
    for name, (P, Q) in {"crank": (A, B), "coupler": (B, C), "rocker": (C, D)}.items():
        com = P + rng.uniform(0.2, 0.8) * (Q - P) + rng.uniform(-0.05, 0.05, 2)
        links.append({"name": name, "mass": float(rng.uniform(0.5, 3.0)),
                      "com": [float(v) for v in com], "inertia": float(rng.uniform(1e-3, 2e-2))})
    loads = [
        {"link": "rocker", "torque": float(rng.uniform(-5, 5))},
        {"link": "coupler", "force": [float(v) for v in rng.uniform(-30, 30, 2)],
         "at": [float(v) for v in (B + C) / 2 + rng.uniform(-0.05, 0.05, 2)]},
    ]
    if driver == "R":
        # the toward joint must be on links[1]: an R driver's joint A is never flipped
        a_deg = math.degrees(math.atan2(B[1] - A[1], B[0] - A[0]))
        drv = {"joint": "A", "toward": "B", "start_deg": a_deg - 12, "stop_deg": a_deg + 12,
               "steps": steps, "speed": float(rng.uniform(2, 8)),
               "acceleration": float(rng.uniform(-20, 20))}
    else:
        drv = {"joint": "A", "start": -0.02, "stop": 0.02, "steps": steps,
               "speed": float(rng.uniform(0.2, 1.0)), "acceleration": float(rng.uniform(-3, 3))}
    scene = {"name": f"loop-{driver}{''.join(types)}-{seed}", "links": links, "joints": joints,
             "drivers": [drv], "loads": loads,
             "effects": effects or {"inertia": True, "gravity": [0.0, -9.81], "loads": True}}
    if outputs is not None:
        scene["outputs"] = outputs
    return scene


DYADS = ["RRR", "RRP", "PRR", "RPR", "PRP", "RPP", "PPR"]
FLIPS = [(False, False, False, False), (True, True, False, True), (False, False, True, True),
         (True, False, True, False)]


def loop_cases():
    cases = []
    for i, t in enumerate(DYADS):
        for k, flip in enumerate(FLIPS):
            for driver in ("R", "P"):
                f = flip if driver == "P" else (False,) + flip[1:]
                cases.append(pytest.param(t, f, driver, 17 * i + 3 * k,
                                          id=f"{driver}-{t}-flip{k}"))
    return cases


def well_conditioned(make, seed, tries=30):
    """The first scene ``make(seed + 1000 k)`` solvable at every step with condition < 1e4.

    Random slide axes can put a sweep past a limit position; such draws are
    skipped (the choice of test geometry only, never an expected value).
    """
    for k in range(tries):
        d = make(seed + 1000 * k)
        a = compile_plan(linkage_sym.load_scene(d)).run(exact_condition=True)
        if a.ok.all() and np.nanmax(a.condition) < 1e4:
            return d
    raise AssertionError(f"no well-conditioned draw in {tries} tries")


def run_both(scene_dict, **kw):
    scene = linkage_sym.load_scene(scene_dict)
    plan = compile_plan(scene, **kw)
    return scene, plan, plan.run(exact_condition=True), plan.run(method="global")


def check_contract(scene, a, g, *, tol=TOL, inertia_only=False):
    assert a.stages[-1] == "forces" and g.stages[-1] == "forces"
    ok = a.ok
    assert ok.all(), [m for m in a.messages if m][:3]
    # keep away from singular positions, so round-off is far below the tolerance
    assert np.nanmax(a.condition) < 1e5
    fa, fg = a.forces, g.forces
    scale = reaction_scale(scene, fg)
    L = scene.characteristic_length()
    for j in fa.reactions:
        assert max_rel(fa.reactions[j] - fg.reactions[j], scale) <= tol, j
        assert max_rel((fa.reaction_moments[j] - fg.reaction_moments[j]) / L, scale) <= tol, j
    for d in scene.drivers:
        div = L if d.kind == "R" else 1.0
        assert max_rel((fa.driving[d.joint] - fg.driving[d.joint]) / div, scale) <= tol
    for res in (a, g):
        for link, (rf, rm, sf, sm) in link_residuals(scene, res).items():
            assert max_rel(rf, sf) <= tol, (res.forces.method, link, "force")
            assert max_rel(rm, sm) <= tol, (res.forces.method, link, "moment")
        r, s = power_residual(scene, res)
        assert max_rel(r, s) <= tol, (res.forces.method, "power")
    if inertia_only:
        F, M, sF, sM = momentum_frame(scene, a)
        for res in (a, g):
            assert max_rel(res.forces.frame_force - F, sF) <= tol
            assert max_rel(res.forces.frame_moment - M, sM) <= tol


@pytest.mark.parametrize("types, flip, driver, seed", loop_cases())
def test_every_dyad_type_and_orientation(types, flip, driver, seed):
    d = well_conditioned(lambda s: loop_scene(types, flip=flip, seed=s, driver=driver), seed)
    scene, plan, a, g = run_both(d)
    (dy,) = [x for x in plan.decomposition.groups if x.kind == "dyad"]
    assert dy.dyad_type == {"PRR": "RRP", "PPR": "RPP"}.get(types, types)
    check_contract(scene, a, g)


@pytest.mark.parametrize("types", ["RRR", "RRP", "RPR", "PRP", "RPP"])
def test_inertia_only_frame_is_the_shaking_force_and_moment(types):
    d = well_conditioned(
        lambda s: loop_scene(types, seed=s, effects={"inertia": True, "loads": False}), 5
    )
    scene, plan, a, g = run_both(d)
    check_contract(scene, a, g, inertia_only=True)


@pytest.mark.parametrize("name", example_names())
def test_every_shipped_example(name):
    scene, plan, a, g = run_both(example_dict(name))
    check_contract(scene, a, g)


@pytest.mark.parametrize("name", example_names())
def test_every_shipped_example_inertia_only(name):
    d = example_dict(name)
    d["effects"] = {"inertia": True, "loads": False, "springs": False}  # inertia only
    scene, plan, a, g = run_both(d)
    check_contract(scene, a, g, inertia_only=True)


@pytest.mark.parametrize("name", ["sixbar_class3",
                                  pytest.param("printing_mechanism", marks=pytest.mark.slow),
                                  "hydraulic_boom"])
def test_every_disconnection_gives_the_same_reactions(name):
    scene = linkage_sym.load_example(name)
    plan = compile_plan(scene)
    ref = plan.run(method="global").forces
    scale = reaction_scale(scene, ref)
    (gi, group), = [(i, x) for i, x in enumerate(plan.decomposition.groups)
                    if x.kind not in ("input", "dyad")]
    choices = usable_disconnections(scene, group)
    assert choices
    for k in range(len(choices)):
        a = compile_plan(scene, disconnection=k).run()
        info = a.forces.groups[gi]
        assert info.method == "disconnection"
        assert len(info.choices) == len(choices)
        # the requested choice is used wherever it is well conditioned
        assert (info.used == k).sum() >= 0.9 * a.n_steps
        for j in ref.reactions:
            assert max_rel(a.forces.reactions[j] - ref.reactions[j], scale) <= TOL, (k, j)
        for d in scene.drivers:
            assert max_rel((a.forces.driving[d.joint] - ref.driving[d.joint])
                           / scene.characteristic_length(), scale) <= TOL
        r, s = power_residual(scene, a)
        assert max_rel(r, s) <= TOL


def test_result_says_which_disconnection_was_used():
    a = linkage_sym.analyze(linkage_sym.load_example("printing_mechanism"))
    info = a.forces.groups[1]
    assert info.links == ("coupler", "lever", "rocker", "slider")
    assert (info.used >= 0).all() and info.amplification.shape == (a.n_steps,)
    d = a.to_dict()
    grp = d["groups"][1]
    assert grp["method"] == "disconnection"
    assert sum(grp["steps_per_choice"].values()) == a.n_steps
    assert set(grp["steps_per_choice"]) <= set(grp["choices"])


# --------------------------------------------------------------- only what is asked for
def test_static_scene_computes_no_velocities_or_accelerations():
    d = well_conditioned(lambda s: loop_scene(
        "RRR", seed=s, effects={"inertia": False, "gravity": [0, -9.81]},
        outputs=["reactions", "driving", "frame"]), 1)
    scene = linkage_sym.load_scene(d)
    a = compile_plan(scene).run()
    assert a.stages == ("position", "forces")
    for lk in a.links.values():
        assert lk.omega is None and lk.alpha is None
    assert np.isfinite(a.forces.driving["A"]).all()
    # statics: the virtual work of the loads balances the driver (checked with
    # the kinematics of a second, full run: rates do not affect static forces)
    full = dict(d, outputs=["kinematics", "reactions", "driving", "frame"])
    b = compile_plan(linkage_sym.load_scene(full)).run()
    assert b.stages == ("position", "velocity", "acceleration", "forces")
    np.testing.assert_allclose(a.forces.driving["A"], b.forces.driving["A"], rtol=1e-12)
    object.__setattr__(b, "forces", a.forces)
    r, s = power_residual(scene, b)
    assert max_rel(r, s) <= TOL


def test_kinematics_only_scene_computes_no_forces():
    d = well_conditioned(lambda s: loop_scene("RRP", seed=s, outputs=["kinematics"]), 2)
    a = compile_plan(linkage_sym.load_scene(d)).run()
    assert a.stages == ("position", "velocity", "acceleration")
    assert a.forces is None
    step = a.to_dict()["steps"][0]
    assert "driving" not in step and "frame" not in step
    assert all("reaction" not in rec for rec in step["joints"].values())


def test_massless_links_add_no_inertia_work():
    d = well_conditioned(lambda s: loop_scene(
        "RPR", seed=s, effects={"inertia": True, "gravity": [0, -9.81]}, outputs=["driving"]), 3)
    for link in d["links"]:
        link.pop("mass"), link.pop("com"), link.pop("inertia")
    a = compile_plan(linkage_sym.load_scene(d)).run()
    # inertia asked for, but nothing has mass: no rates are computed
    assert a.stages == ("position", "forces")
    step = a.to_dict()["steps"][3]
    # besides the step's estimated accuracy (an extension of the format): position and forces
    assert set(step) == {"status", "drivers", "driving", "accuracy"}
    assert set(step["accuracy"]) == {"position", "forces"}


def test_outputs_select_the_json_fields():
    d = well_conditioned(lambda s: loop_scene("RRP", seed=s, outputs=["reactions"]), 4)
    a = compile_plan(linkage_sym.load_scene(d)).run()
    step = a.to_dict()["steps"][0]
    assert set(step) == {"status", "drivers", "joints", "accuracy"}  # accuracy: an extension
    assert set(step["joints"]["C"]) == {"reaction"}
    assert set(step["joints"]["D"]) == {"reaction", "reaction_moment"}  # a P joint


def test_steps_that_are_not_ok_carry_no_forces():
    # a crank too long for part of the turn: those steps are unassemblable
    d = example_dict("crank_rocker")
    d["drivers"][0]["steps"] = 73
    for j in d["joints"]:
        if j["name"] == "B":
            j["at"] = [0.045, 0.0]
    a = compile_plan(linkage_sym.load_scene(d)).run()
    bad = ~a.ok
    assert bad.any() and a.ok.any()
    assert np.isnan(a.forces.driving["A"][bad]).all()
    assert np.isfinite(a.forces.driving["A"][a.ok]).all()
    for i in np.flatnonzero(bad)[:3]:
        step = a.to_dict()["steps"][i]
        assert "driving" not in step and "frame" not in step
